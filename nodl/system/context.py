"""What every check is given: the analysed nodes, the system, the settings, and indexes.

Everything a check asks is indexed once (by final node name, by instance),
so that checks stay linear in the size of the system.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from nodl.composition.instance import NodeInstance
from nodl.system.connections import System
from nodl.system.launched import SystemNode
from nodl.system.settings import SETTINGS_KEYS, AnalysisSettings
from nodl.targets.drafts import DraftGap, draft_gaps

__all__ = ['SETTINGS_KEYS', 'AnalysisContext', 'AnalysisSettings']

@dataclass
class AnalysisContext:
    """The launched system as the checks see it."""

    #: Every launched node, in launch order.
    nodes: list[SystemNode]
    settings: AnalysisSettings = field(default_factory=AnalysisSettings)
    #: The ament prefixes definitions were looked up in (None: ``AMENT_PREFIX_PATH``).
    prefixes: list[str] | None = None

    def __post_init__(self) -> None:
        self._by_instance = {id(n.instance): n for n in self.nodes if n.instance is not None}
        #: The system of the nodes that have a definition.
        self.system = System([n.instance for n in self.nodes if n.instance is not None])
        self._by_fqn: dict[str, list[SystemNode]] | None = None
        self._gaps: dict[int, list[DraftGap]] | None = None

    @property
    def by_fqn(self) -> dict[str, list[SystemNode]]:
        """Final name -> the nodes launched under it (more than one is a duplicate); made on
        first use (a list per launched node is a lot for the collector to keep walking)."""
        by_fqn = self._by_fqn
        if by_fqn is None:
            by_fqn = self._by_fqn = {}
            for node in self.nodes:
                by_fqn.setdefault(node.fqn, []).append(node)
        return by_fqn

    def node_of(self, instance: NodeInstance) -> SystemNode:
        """The analysed node of an instance."""
        return self._by_instance[id(instance)]

    @property
    def undefined(self) -> list[SystemNode]:
        """The nodes without a usable definition (their endpoints are unknown), containers
        of composable nodes left out."""
        return [n for n in self.nodes if n.instance is None and n.entry.role != 'container']

    @property
    def draft_gaps(self) -> dict[int, list[DraftGap]]:
        """``id(node)`` -> the unresolved entities of its extracted draft, for every analysed
        node served by a draft ``nodl extract`` wrote with gaps still commented out (each file
        read once, on first use)."""
        gaps = self._gaps
        if gaps is None:
            by_file: dict[str, list[DraftGap]] = {}
            gaps = self._gaps = {}
            for node in self.analysed():
                file = node.match.file
                if file is None:
                    continue
                if file not in by_file:  # (only a file nodl extract wrote can be a draft)
                    by_file[file] = draft_gaps(file) \
                        if node.match.provenance().made_by == 'extracted' else []
                if by_file[file]:
                    gaps[id(node)] = by_file[file]
        return gaps

    def gaps_of(self, node: SystemNode) -> list[DraftGap]:
        """The unresolved entities of ``node``'s extracted draft (none for a complete definition)."""
        return self.draft_gaps.get(id(node), [])

    def analysed(self) -> Iterable[SystemNode]:
        """The nodes with an instance."""
        return (n for n in self.nodes if n.instance is not None)
