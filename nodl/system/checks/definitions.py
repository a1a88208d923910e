"""``no-definition``: launched executables without a registered definition; ``draft-gaps``:
nodes served by an extracted draft whose gaps are still commented out."""

from __future__ import annotations

from collections.abc import Iterator

from nodl.registry.registrations import describe_missing
from nodl.system.checks import CheckExtension
from nodl.system.context import AnalysisContext
from nodl.system.findings import Finding, make_finding
from nodl.targets.drafts import describe

__all__ = ['NoDefinitionCheck']


class NoDefinitionCheck(CheckExtension):
    """A launched node whose package registers no definition for it: its endpoints are
    unknown, so the analysis cannot check it (and draws no orphan findings from it).
    Containers of composable nodes are not reported: their composable nodes are."""

    kinds = ('no-definition', 'draft-gaps')

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per node without a registered definition."""
        reasons: dict[tuple[str, str], str] = {}
        for node in context.nodes:
            if node.match.file is not None or node.entry.role == 'container':
                continue  # a container's own interface is rclcpp_components'
            key = (node.match.package, node.match.key)
            if key not in reasons:
                reasons[key] = describe_missing(*key, prefixes=context.prefixes)
            how = f' (plugin {node.entry.plugin}: looked up as {node.match.key!r})' \
                if node.entry.plugin else ''
            yield make_finding(
                'no-definition', f'{node.fqn} ({node.executable_label}) has no definition{how}: '
                f'{reasons[key]}; its endpoints are unknown and it is not checked (write one '
                f'as DIR/{node.match.package}/{node.match.key}.nodl.yaml and give --definitions DIR)',
                node.location, [node.fqn])
        yield from _draft_gaps(context)


def _draft_gaps(context: AnalysisContext) -> Iterator[Finding]:
    """One ``draft-gaps`` finding per node whose definition is an extracted draft with entities
    still under ``# GAP``: the analysis sees only the rest of the node, so what it says about
    those entities (orphans, QoS, types) cannot be judged."""
    for node in context.analysed():
        gaps = context.gaps_of(node)
        if not gaps:
            continue
        count = len(gaps)
        yield make_finding(
            'draft-gaps', f'{node.fqn} ({node.executable_label}): its definition '
            f'{node.match.file} is a draft nodl extract wrote, with {count} '
            f'entit{"y" if count == 1 else "ies"} still unknown ({describe(gaps)}, commented '
            'out under # GAP): findings about them (orphans, QoS, types) cannot be judged; fill '
            'in what each GAP says is missing and uncomment the entity (or extract again)',
            node.location, [node.fqn],
            related=[(line.file, line.line, line.column,
                      f'GAP {line.reason}' + (f' [{line.code}]' if line.code else ''))
                     for gap in gaps for line in gap.lines])
