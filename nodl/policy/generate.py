"""A whole policy from node instances (a launched system, or definitions placed by name).

:func:`policy_for_instances` gives every instance its profile
(:mod:`nodl.policy.grants`), puts it in its enclave
(:mod:`nodl.policy.enclaves`) and reports, as coded diagnostics, what
keeps the policy from being exact: nodes without a definition (NODL601: an
error, or with ``allow_missing`` a warning and a profile granting nothing,
with a comment marking the gap), names that cannot be granted (NODL602),
two instances with one name (NODL611: DDS cannot tell them apart), nodes served by an
extracted draft whose gaps are still commented out (NODL617: an error, or with
``allow_gaps`` a warning; nothing is granted for those entities and a comment
in the profile says so).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, NamedTuple

from nodl.composition.entities import Location
from nodl.composition.instance import NodeInstance
from nodl.diagnostics import Diagnostic, Severity
from nodl.policy.distros import DEFAULT_DISTRO
from nodl.policy.enclaves import EnclaveMapping, assign_enclaves
from nodl.policy.grants import display_path, profile_for_instance
from nodl.policy.model import Policy, Profile
from nodl.system.gc_tuning import batch_collection
from nodl.targets.drafts import describe, draft_gaps
from nodl.vocabulary import SECTION_BY_KEY

if TYPE_CHECKING:
    from nodl.targets.drafts import DraftGap
    from nodl.targets.resolve import Provenance

__all__ = ['MissingNode', 'GappedNode', 'PolicyResult', 'gapped_nodes', 'policy_for_instances']


class MissingNode(NamedTuple):
    """A node of the system whose definition is unknown: its profile cannot be written."""

    #: Its fully qualified name.
    fqn: str
    #: Why (``no definition registered for demo_nodes_cpp talker``).
    reason: str
    #: Where it is launched, if known.
    location: Location | None = None


class GappedNode(NamedTuple):
    """A node whose definition is an extracted draft with entities still under ``# GAP``
    (see :func:`nodl.targets.drafts.draft_gaps`): the policy grants them nothing."""

    #: Its fully qualified name.
    fqn: str
    #: The draft.
    file: str
    #: Its unresolved entities (:class:`~nodl.targets.drafts.DraftGap`) a policy would grant.
    gaps: tuple[DraftGap, ...]
    #: Where it is launched, if known (else the draft's first GAP line is the place).
    location: Location | None = None


def gapped_nodes(nodes: Iterable[tuple[str, str | None, Location | None]]) -> list[GappedNode]:
    """The nodes among ``(fqn, definition file, launch location)`` whose definition is an
    extracted draft with communication entities still under ``# GAP`` (parameters need no
    grant); each draft read once."""
    read: dict[str, tuple[DraftGap, ...]] = {}
    out: list[GappedNode] = []
    for fqn, file, location in nodes:
        if file is None:
            continue
        if file not in read:
            read[file] = tuple(gap for gap in draft_gaps(file) if gap.communication)
        if read[file]:
            out.append(GappedNode(fqn, file, read[file], location))
    return out


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
                         notes: Sequence[str] = (), containers: Mapping[str, str] | None = None,
                         gapped: Sequence[GappedNode] = (), allow_gaps: bool = False
                         ) -> PolicyResult:
    """The least-privilege policy of ``instances`` (plus ``missing`` nodes, as gaps).

    ``containers`` maps composable nodes to their container (fully qualified
    names): they share its process, hence its enclave.  ``gapped``: instances whose
    definition is a draft with unresolved entities (:func:`gapped_nodes`); each is
    NODL617, an error unless ``allow_gaps``.
    """
    # a large system allocates many objects that live until the end: collect less often
    with batch_collection():
        result = _policy_for_instances(list(instances), missing, distro, enclaves, allow_missing,
                                       notes, containers)
    if gapped:
        result = _mark_gaps(result, gapped, allow_gaps)
    return result


def _mark_gaps(result: PolicyResult, gapped: Sequence[GappedNode], allow_gaps: bool) -> PolicyResult:
    """NODL617 for each node of ``gapped``, and a note in its profile per unresolved entity."""
    profiles = {profile.fqn: profile for enclave in result.policy.enclaves
                for profile in enclave.profiles}
    diagnostics = list(result.diagnostics)
    for node in gapped:
        count = len(node.gaps)
        first = node.gaps[0].lines[0]
        where = node.location or Location(first.file, first.line, first.column)
        severity = Severity.WARNING if allow_gaps else Severity.ERROR
        hint = ('written with --allow-gaps: fill them in before deploying, or the node is denied '
                'that traffic' if allow_gaps else
                'fill in what each GAP says is missing and uncomment the entities in the draft (or '
                'extract again), or pass --allow-gaps to write the policy without them')
        diagnostics.append(Diagnostic(
            severity, f'{node.fqn}: its definition {node.file} is a draft nodl extract wrote, with '
            f'{count} unresolved entit{"y" if count == 1 else "ies"} ({describe(list(node.gaps))}, '
            f'under # GAP): the policy grants nothing for {"it" if count == 1 else "them"}, so '
            f'SROS 2 would deny that traffic; {hint}', (), where.file, where.line, where.column,
            code='NODL617',
            related=[(line.file, line.line, line.column, f'GAP {line.reason}')
                     for gap in node.gaps for line in gap.lines]))
        profile = profiles.get(node.fqn)
        if profile is not None:
            for gap in node.gaps:
                line = gap.lines[0]
                what = f'{_word(gap.section)} {gap.name}' if gap.name else f'a {_word(gap.section)}'
                profile.notes.append(f'GAP: {what} of the extracted draft is unresolved '
                                     f'({display_path(line.file)}:{line.line}:{line.column}); '
                                     'nothing is granted for it')
    return result._replace(diagnostics=diagnostics)


def _word(section: str) -> str:
    return SECTION_BY_KEY[section].word


def _policy_for_instances(instances: list[NodeInstance], missing: Sequence[MissingNode], distro: str,
                          enclaves: str | EnclaveMapping, allow_missing: bool, notes: Sequence[str],
                          containers: Mapping[str, str] | None) -> PolicyResult:
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
