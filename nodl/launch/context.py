"""The state a launch walk carries, as ``launch.LaunchContext`` holds it.

Launch configurations (arguments, ``let``) live in one dictionary together with
what launch_ros keeps there: ``ros_namespace`` (pushed namespaces), ``ros_remaps``
(``set_remap``) and ``global_params`` (``set_parameter``, ``set_parameters_from_file``).
A scoped group pushes a *shallow* copy of that dictionary and pops it afterwards,
exactly as launch does; so, as in launch, a ``set_remap`` or ``set_parameter`` inside a
scoped group appends to the list the enclosing scope already holds (and is seen after
the group) when the enclosing scope had set one before the group.
"""

from __future__ import annotations

import hashlib
import os
from typing import Any

from nodl.diagnostics import Diagnostic, Severity
from nodl.launch.errors import MAX_ENTITIES, LaunchProblem, SubstitutionTooLarge
from nodl.launch.model import LaunchArgument, LaunchResult, SourceLocation
from nodl.launch.shared_yaml import SharedYaml

__all__ = ['LaunchContext']


class LaunchContext:
    """Configurations, environment, the current file and include chain, and the result."""

    def __init__(self, result: LaunchResult, environment: dict[str, str] | None = None,
                 prefixes: list[str] | None = None) -> None:
        self.result = result
        self.configurations: dict[str, Any] = {}
        self._configuration_stack: list[dict[str, Any]] = []
        self.environment: dict[str, str] = dict(os.environ if environment is None else environment)
        self._environment_stack: list[dict[str, str]] = []
        if prefixes is None:
            from nodl.ament_index import prefix_paths

            prefixes = prefix_paths(self.environment)
        self.prefixes = prefixes
        self._packages: dict[str, str | None] = {}
        self.current_file = ''
        #: Include entries from the root launch file to the current one.
        self.include_chain: tuple[SourceLocation, ...] = ()
        #: The real paths of the launch files being read, outermost first (cycle detection).
        self.file_stack: list[str] = []
        self.entities = 0
        self._missing: set[str] = set()
        self._anonymous: dict[str, str] = {}
        self._seen_diagnostics: set[tuple[str, int, int, str]] = set()
        #: (where a let sets a run-time value, its name) -> the one diagnostic said there.
        self._run_time_lets: dict[tuple[tuple[str, int, int], str], Diagnostic] = {}
        self._namespace_errors: dict[str, str | None] = {}
        #: Environment variables an ``append_env`` would have made longer than the substitution
        #: limit -> the problem reported there (raised again where they are read).
        self.oversized_environment: dict[str, SubstitutionTooLarge] = {}
        #: PyYAML as the launch's Python code gets it: a text it reads again, or data it writes
        #: again, is parsed or emitted once in the walk (nav2's RewrittenYaml, one per file).
        self.shared_yaml = SharedYaml()

    # -- what launch.LaunchContext offers to substitutions written in helper packages ------
    @property
    def launch_configurations(self) -> dict[str, Any]:
        """``launch.LaunchContext.launch_configurations``: the configurations of the scope."""
        return self.configurations

    def perform_substitution(self, substitution: Any) -> str:
        """``launch.LaunchContext.perform_substitution``."""
        return str(substitution.perform(self))

    # -- scoping -------------------------------------------------------------------------
    def push_configurations(self) -> None:
        """Start a scope (a shallow copy, as launch makes)."""
        self._configuration_stack.append(self.configurations.copy())

    def pop_configurations(self) -> None:
        """End a scope."""
        self.configurations = self._configuration_stack.pop()

    def reset_configurations(self, keep: dict[str, Any]) -> None:
        """Forget every configuration but ``keep`` (a group with ``forwarding`` false)."""
        self.configurations = dict(keep)

    def push_environment(self) -> None:
        """Start an environment scope."""
        self._environment_stack.append(dict(self.environment))

    def pop_environment(self) -> None:
        """End an environment scope."""
        self.environment = self._environment_stack.pop()

    # -- lookups -------------------------------------------------------------------------
    def package_prefix(self, package: str) -> str:
        """The ament prefix of ``package`` (``find-pkg-prefix``); NODL511 if it is not installed."""
        if package not in self._packages:
            from nodl.ament_index import get_resource

            resource = get_resource('packages', package, self.prefixes)
            self._packages[package] = resource.prefix if resource is not None else None
        prefix = self._packages[package]
        if prefix is None:
            from nodl.ament_index import get_resources
            from nodl.wording import did_you_mean

            hint = did_you_mean(package, get_resources('packages', self.prefixes))
            raise LaunchProblem('NODL511', f"package '{package}' not found in the ament index "
                                           f'(AMENT_PREFIX_PATH){hint}; build and source it, or '
                                           'fix the name')
        return prefix

    def anonymous_name(self, name: str) -> str:
        """A unique name for ``$(anon name)``: stable for the same root file and name."""
        root = self.result.file
        digest = hashlib.sha1(f'{root}\0{name}'.encode('utf-8', 'surrogatepass')).hexdigest()[:12]
        value = f'{name}_{digest}'
        for old, new in (('.', '_'), ('-', '_'), (':', '_')):
            value = value.replace(old, new)
        return value

    def namespace_error(self, namespace: str) -> str | None:
        """:func:`nodl.naming.namespace_error`, once per namespace (nodes share them)."""
        try:
            return self._namespace_errors[namespace]
        except KeyError:
            from nodl.naming.validation import namespace_error

            problem = self._namespace_errors[namespace] = namespace_error(namespace)
            return problem

    def note_missing_configuration(self, name: str) -> None:
        """Remember that ``$(var name)`` failed (to say so once)."""
        self._missing.add(name)

    def configuration_hint(self, name: str) -> str:
        """"; did you mean ..." among the configurations set, or how to set it."""
        from nodl.wording import did_you_mean

        names = [k for k, v in self.configurations.items() if isinstance(v, str)]
        hint = did_you_mean(name, names)
        return hint or f"; declare it (<arg name=\"{name}\"/>) and pass it ({name}:=VALUE), or set it with <let>"

    # -- results -------------------------------------------------------------------------
    def count_entity(self) -> None:
        """Count one evaluated entity; stop at :data:`MAX_ENTITIES`."""
        self.entities += 1
        if self.entities > MAX_ENTITIES:
            raise LaunchProblem('NODL508', f'the launch evaluates more than {MAX_ENTITIES:,} '
                                           'entities; stopped (is something including itself?)')

    def report(self, diagnostic: Diagnostic) -> None:
        """Add a diagnostic once (the same problem met twice at one place is said once)."""
        key = (diagnostic.file, diagnostic.line, diagnostic.column, diagnostic.message)
        if key in self._seen_diagnostics:
            return
        self._seen_diagnostics.add(key)
        self.result.diagnostics.append(diagnostic)

    def problem(self, problem: LaunchProblem, at: SourceLocation | None) -> None:
        """Report a :class:`LaunchProblem` at its own place or at ``at`` (a value a ``let``
        sets that only the running launch knows: at the ``let``, see :meth:`run_time`)."""
        if at is None:
            at = SourceLocation(self.current_file, 0, 0)
        if getattr(problem, 'origin', None) is not None and not (problem.file and problem.line):
            self.run_time(problem, problem.message, at)
            return
        self.report(problem.diagnostic(at.file, at.line, at.column))

    def warn(self, code: str, message: str, at: SourceLocation, cause: LaunchProblem | None = None) -> None:
        """Report a warning at ``at``; ``cause``: the problem it says, when it is one (a
        run-time value a ``let`` sets is said at the ``let``: :meth:`run_time`)."""
        if cause is not None and getattr(cause, 'origin', None) is not None:
            self.run_time(cause, message, at)
            return
        self.report(Diagnostic(Severity.WARNING, message, (), at.file, at.line, at.column, code=code))

    def run_time(self, problem: LaunchProblem, message: str, at: SourceLocation) -> None:
        """Say that a value only the running launch knows is used at ``at`` (``message``:
        what that leaves out).  A value a ``let`` or an ``arg`` default sets
        (:attr:`~nodl.launch.errors.Unevaluable.origin`) is one NODL513 warning at
        that ``let``, each place that uses it a related location; else one at ``at``."""
        origin = getattr(problem, 'origin', None)
        if origin is None:
            self.warn(problem.code, message, at)
            return
        name = getattr(problem, 'configuration', '')
        message = message.replace(f' (set at {origin[0]}:{origin[1]}:{origin[2]})', '')
        use = (at.file, at.line, at.column, f'used here: {message}')
        key = (origin, name)
        said = self._run_time_lets.get(key)
        related = (use,) if said is None else (*said.related, use)
        if said is not None and any(r[:3] == use[:3] for r in said.related):
            return  # (a use met twice: an include read again)
        places = [f'{line}:{column}' if file == origin[0] else f'{file}:{line}:{column}'
                  for file, line, column, _ in related]
        shown = ', '.join(places[:5]) + (f' and {len(places) - 5} more' if len(places) > 5 else '')
        text = (f"launch configuration '{name}': {getattr(problem, 'reason', '') or problem.message}; "
                f'what uses it is analysed without its value (used at {shown})')
        more = Diagnostic(Severity.WARNING, text, (), origin[0], origin[1], origin[2],
                          code=problem.code, related=related)
        if said is None:
            self._run_time_lets[key] = more
            self.result.diagnostics.append(more)
            return
        diagnostics = self.result.diagnostics
        for index in range(len(diagnostics) - 1, -1, -1):
            if diagnostics[index] is said:
                diagnostics[index] = more
                break
        self._run_time_lets[key] = more

    def declare(self, argument: LaunchArgument) -> None:
        """Record a declared argument (the first declaration of a name is kept)."""
        self.result.arguments.setdefault(argument.name, argument)
