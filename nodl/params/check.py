"""Parameter files checked against a node definition, without starting anything.

A node started as a process reads its parameter files with rcl: the node keys
that match its fully qualified name apply (``/*`` one name token, ``/**`` any
number), values are typed by rcl's YAML rules, and a declared parameter takes
the value of the last file that sets it.  Each value is then checked as the
node would check it: its type exactly (an integer is not a double), every
built-in validator; parameters the definition does not declare are reported
with a suggestion, and required parameters that no file sets are reported at
their declaration.  An empty list for a statically typed parameter is reported
too: rcl reads it as no value, so the node's parameter ends up unset.  rcl
refuses every YAML alias ("Will not support aliasing"): each is an error at its
line (NODL710) and no value of that file is checked, as the node gets none; an
anchor is a warning (NODL711: rcl ignores it), a merge key ``<<`` an error
(NODL712: rcl reads it as a parameter name).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from nodl.diagnostics import Diagnostic, Severity
from nodl.launch.params import load_parameter_file
from nodl.launch.rcl_yaml import match_parameter_file_nodes
from nodl.model.parameter_types import TypeSpec
from nodl.plan.parameter_plan import (
    ParametersPlan,
    plan_parameters,
    type_problem,
    value_problems,
)
from nodl.system import Entity, ResolvedNode
from nodl.system.checks.parameters import launch_value_verdict
from nodl.system.run import LAUNCH_KIND, analyse_launch
from nodl.wording import did_you_mean

if TYPE_CHECKING:
    from nodl.launch.sandbox import LaunchLimits

__all__ = ['check_parameter_files', 'check_launch_parameters', 'is_wildcard_key']


def is_wildcard_key(key: str) -> bool:
    """True for a node key holding ``*`` (it serves more nodes than one)."""
    return '*' in key


def _plan(node: ResolvedNode) -> tuple[ParametersPlan, dict[str, Entity]]:
    entities = [e for e in node.parameters]
    return plan_parameters(entities), {e.name: e for e in entities}


def _declared_here(name: str, entity: Any) -> list[tuple[str, int, int, str]]:
    where = getattr(entity, 'location', None)
    return [(where.file, where.line, where.column, f'{name!r} is declared here')] \
        if where is not None and where.line else []


def check_parameter_files(files: Sequence[str], node: ResolvedNode, fqn: str) -> list[Diagnostic]:
    """Every problem of ``files`` for ``node`` started as ``fqn`` (``/ns/name``)."""
    plan, entities = _plan(node)
    names = [p.name for p in plan.parameters]
    out: list[Diagnostic] = []
    given: set[str] = set()
    matched_any = False
    readable = False
    for path in files:
        loaded = load_parameter_file(path)
        readable = readable or not loaded.diagnostics
        out.extend(loaded.diagnostics)
        out.extend(loaded.rcl_diagnostics)  # (a node started as a process reads it with rcl)
        keys = match_parameter_file_nodes(loaded.keys, fqn)
        for entry in loaded.nodes:
            if entry.key not in keys:
                continue
            matched_any = True
            if loaded.rcl_refuses:  # rcl reads no value of the file: said at its aliases
                continue
            wildcard = is_wildcard_key(entry.key)
            for name, value in entry.rcl_parameters.items():
                line, column = entry.positions.get(name, (entry.line, entry.column))
                parameter = plan.get(name)
                if parameter is None:
                    hint = did_you_mean(name, names)
                    severity = Severity.WARNING if wildcard else Severity.ERROR
                    out.append(Diagnostic(
                        severity, f"{fqn} does not declare a parameter {name!r} (key {entry.key!r})"
                        f"{hint or '; a node ignores parameters it does not declare'}", (), path,
                        line, column, anchor='key', code='NODL701'))
                    continue
                given.add(name)
                entity = entities[name]
                if not parameter.dynamic_typing and isinstance(entity.type, TypeSpec) \
                        and launch_value_verdict(value, entity.type) == 'unset':
                    # rcl reads an empty list as no value (what the launch analysis says too)
                    out.append(Diagnostic(
                        Severity.ERROR, f"parameter {name!r} of {fqn}: an empty list is no value "
                        'for rcl: a statically typed parameter ends up unset (its default is '
                        'lost) and the node fails when it reads it', (), path, line, column,
                        code='NODL703', related=_declared_here(name, entity)))
                    continue
                problems = value_problems(parameter, value)
                if not problems:
                    continue
                code = 'NODL702' if type_problem(parameter, value) is not None else 'NODL703'
                out.append(Diagnostic(
                    Severity.ERROR, f"parameter {name!r} of {fqn}: {value!r} is invalid: "
                    + '; '.join(problems), (), path, line, column, code=code,
                    related=_declared_here(name, entity)))
    if not matched_any and readable:  # (a file that cannot be read is said once, above)
        out.append(Diagnostic(Severity.WARNING, f'no node key of the parameter file(s) applies to {fqn} '
                              '(keys match the fully qualified name; /** matches every node)',
                              (), files[0], 1, 1, code='NODL705'))
    for parameter in plan.required:
        if parameter.name in given:
            continue
        entity = entities[parameter.name]
        where = entity.location
        out.append(Diagnostic(
            Severity.ERROR, f"required parameter {parameter.name!r} ({parameter.type_name}) of {fqn} "
            'is set by none of the parameter files; a node without it fails to start',
            (), where.file, where.line, where.column, anchor='key', code='NODL704'))
    return out


def check_launch_parameters(launch_file: str, files: Sequence[str] = (),
                            arguments: dict[str, str] | None = None,
                            prefixes: list[str] | None = None,
                            limits: LaunchLimits | None = None) -> list[Diagnostic]:
    """The parameters a launch file gives its nodes, and ``files``, checked against the nodes' definitions.

    The launch file's own parameter files and values are checked by the launch
    analysis (NODL560-563); ``files`` are checked for every launched node that
    has a definition, under its final name.  ``prefixes``: the install prefixes
    definitions are looked up in (default: ``AMENT_PREFIX_PATH``).  ``limits``: how the
    launch's Python code runs, if at all (:class:`~nodl.launch.sandbox.LaunchLimits`).
    """
    analysis = analyse_launch(launch_file, arguments or {}, prefixes=prefixes, limits=limits)
    out = [f.diagnostic for f in analysis.findings
           if (f.kind == LAUNCH_KIND and f.severity is Severity.ERROR)
           or f.code in ('NODL560', 'NODL561', 'NODL562', 'NODL563')]
    if analysis.unreadable:
        return out
    defined = [n for n in analysis.nodes if getattr(n.match, 'resolved', None) is not None]
    if not defined:
        out.append(Diagnostic(Severity.ERROR, 'the launch file starts no node that has a registered '
                              'definition: there is nothing to check the parameters against',
                              (), launch_file, code='NODL706'))
        return out
    unmatched: list[Diagnostic] = []
    for node in defined:
        resolved = node.match.resolved
        assert resolved is not None
        found = check_parameter_files(files, resolved, node.fqn)
        unmatched += [d for d in found if d.code == 'NODL705']
        out.extend(d for d in found if d.code != 'NODL705')
    if files and len(unmatched) == len(defined):  # no key of the files applies to any node
        out.append(Diagnostic(Severity.WARNING, 'no node key of the parameter file(s) applies to a node '
                              'the launch file starts (' + ', '.join(n.fqn for n in defined) + ')',
                              (), files[0], 1, 1, code='NODL705'))
    return out
