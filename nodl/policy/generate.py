"""A whole policy from node instances (a launched system, or definitions placed by name).

:func:`policy_for_instances` gives every instance its profile
(:mod:`nodl.policy.grants`), puts it in its enclave
(:mod:`nodl.policy.enclaves`) and reports, as coded diagnostics, what
keeps the policy from being exact: nodes without a definition (NODL601: an
error, or with ``allow_missing`` a warning and a profile granting nothing,
with a comment marking the gap), names that cannot be granted (NODL602),
two instances with one name (NODL611: DDS cannot tell them apart).
"""

from __future__ import annotations

from typing import Iterable, Mapping, NamedTuple, Sequence

from nodl.diagnostics import Diagnostic, Severity
from nodl.policy.distros import DEFAULT_DISTRO
from nodl.policy.enclaves import EnclaveMapping, assign_enclaves
from nodl.policy.model import Policy, Profile
from nodl.system.entities import Location
from nodl.system.instance import NodeInstance

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from nodl.targets.resolve import Provenance

__all__ = ['MissingNode', 'PolicyResult', 'policy_for_instances']


class MissingNode(NamedTuple):
    """A node of the system whose definition is unknown: its profile cannot be written."""

    #: Its fully qualified name.
    fqn: str
    #: Why (``no definition registered for demo_nodes_cpp talker``).
    reason: str
    #: Where it is launched, if known.
    location: Location | None = None


class PolicyResult(NamedTuple):
    """A generated policy and what was found while making it."""

    policy: Policy
    diagnostics: list[Diagnostic]
    #: Where each node's definition came from (a :class:`~nodl.targets.resolve.Provenance`,
    #: or ``index``, ``overlay``, ``file``, ``none``), for the coverage line
    #: (:func:`nodl.targets.resolve.coverage_line`).
    sources: tuple[Provenance | str, ...] = ()
    #: Every file read to make the policy (launch files and what they include, parameter
    #: files, definitions and their mixins), each once: ``policy -o`` writes none of them.
    files: tuple[str, ...] = ()

    @property
    def ok(self) -> bool:
        """True when nothing is an error."""
        return not any(d.severity is Severity.ERROR for d in self.diagnostics)


def policy_for_instances(instances: Iterable[NodeInstance], *,
                         missing: Sequence[MissingNode] = (), distro: str = DEFAULT_DISTRO,
                         enclaves: str | EnclaveMapping = 'node', allow_missing: bool = False,
                         notes: Sequence[str] = (), containers: Mapping[str, str] | None = None
                         ) -> PolicyResult:
    """The least-privilege policy of ``instances`` (plus ``missing`` nodes, as gaps).

    ``containers`` maps composable nodes to their container (fully qualified
    names): they share its process, hence its enclave.
    """
    from nodl.analysis.gc_tuning import batch_collection

    # a large system allocates many objects that live until the end: collect less often
    with batch_collection():
        return _policy_for_instances(list(instances), missing, distro, enclaves, allow_missing, notes,
                                     containers)


def _policy_for_instances(instances: list[NodeInstance], missing: Sequence[MissingNode], distro: str,
                          enclaves: str | EnclaveMapping, allow_missing: bool, notes: Sequence[str],
                          containers: Mapping[str, str] | None) -> PolicyResult:
    from nodl.policy.grants import display_path, profile_for_instance

    diagnostics: list[Diagnostic] = []
    profiles: list[Profile] = []
    seen: dict[str, NodeInstance] = {}
    for instance in instances:
        if instance.fqn in seen:
            where = instance.location or Location('<system>', 0, 0)
            diagnostics.append(Diagnostic(
                Severity.ERROR, f'two nodes are named {instance.fqn}: DDS security cannot tell them '
                'apart, so no policy is written; give each a unique name (or --ignore NODL611 to '
                'write one profile with the grants of both)',
                (), where.file, where.line, where.column, code='NODL611'))
        seen.setdefault(instance.fqn, instance)
        profile, found = profile_for_instance(instance, distro=distro)
        diagnostics.extend(found)
        profiles.append(profile)
    for gap in missing:
        where = gap.location or Location('<system>', 0, 0)
        severity = Severity.WARNING if allow_missing else Severity.ERROR
        hint = ('nothing is granted to it' if allow_missing else
                'register a definition for it, or pass --allow-missing to write the policy '
                'with an empty profile for it')
        diagnostics.append(Diagnostic(severity, f'{gap.fqn} has no node definition ({gap.reason}): '
                                      f'its profile cannot be written; {hint}', (), where.file,
                                      where.line, where.column, code='NODL601'))
        namespace, _, name = gap.fqn.rpartition('/')
        launch = ''
        if gap.location is not None and gap.location.file:
            launch = f'{display_path(gap.location.file)}:{gap.location.line}:{gap.location.column}'
        profiles.append(Profile(namespace or '/', name, launch=launch,
                                notes=[f'GAP: no node definition ({gap.reason}); nothing is granted']))
    merged: dict[str, Profile] = {}
    for profile in profiles:
        first = merged.setdefault(profile.fqn, profile)
        if first is not profile:
            for grant in profile.grants.values():
                for source in grant.sources or [None]:  # type: ignore[list-item]
                    first.grant(grant.communication, grant.access, grant.name, source)
            first.notes.extend(profile.notes)
    assignment, problems = assign_enclaves(merged, enclaves, containers)
    diagnostics.extend(problems)
    for fqn, container in (containers or {}).items():
        if fqn in merged and container in merged and assignment.get(fqn) == assignment.get(container):
            merged[fqn].notes.append(f'loaded into the container {container}: runs in its process, '
                                     'so in its enclave')
    policy = Policy(notes=list(notes))
    for fqn, profile in merged.items():
        path = assignment.get(fqn)
        if path is not None:
            policy.enclave(path).profiles.append(profile)
    if not merged:  # (nodes the enclave mapping leaves out are reported above)
        diagnostics.append(Diagnostic(Severity.ERROR, 'the system has no nodes to write a policy for '
                                      '(a policy needs at least one enclave)', (), '<system>',
                                      code='NODL612'))
    return PolicyResult(policy, diagnostics)
