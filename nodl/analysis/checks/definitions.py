"""``no-definition``: launched executables without a registered definition."""

from __future__ import annotations

from typing import Iterator

from nodl.analysis.checks import CheckExtension
from nodl.analysis.context import AnalysisContext
from nodl.analysis.findings import Finding, make_finding

__all__ = ['NoDefinitionCheck']


class NoDefinitionCheck(CheckExtension):
    """A launched node whose package registers no definition for it: its endpoints are
    unknown, so the analysis cannot check it (and draws no orphan findings from it).
    Containers of composable nodes are not reported: their composable nodes are."""

    kinds = ('no-definition',)

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        """One finding per node without a registered definition."""
        from nodl.index.registry import describe_missing

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
