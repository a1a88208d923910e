"""The system layer every consumer shares: launched nodes, instances, systems, their checks.

* :class:`ResolvedNode` (:func:`resolve_node`), :class:`Entity`, :class:`NodeInstance`:
  the resolved node and its instances, made by composition (:mod:`nodl.composition.resolved`,
  :mod:`~nodl.composition.entities`, :mod:`~nodl.composition.instance`) and exported here
  too, as the documented API has them;
* :class:`System`: instances and the :class:`Connection` on each topic, service and action,
  with :meth:`System.peers`;
* :mod:`~nodl.system.run`: a launch file's launched nodes matched to their definitions,
  named, remapped, given their parameters, and checked (:mod:`~nodl.system.checks`).
"""

from __future__ import annotations

from nodl.composition.client_library import ClientLibraryChoice, choose_client_library
from nodl.composition.entities import (
           Entity,
           EntityKind,
           InterfaceType,
           Location,
           Provider,
)
from nodl.composition.instance import InstanceEntity, NodeInstance
from nodl.composition.resolved import ResolvedNode, resolve_node, resolve_report
from nodl.system.connections import Connection, System
from nodl.targets.resolve import resolve_registered

__all__ = ['ClientLibraryChoice', 'Connection', 'Entity', 'EntityKind', 'InstanceEntity',
           'InterfaceType', 'Location', 'NodeInstance', 'Provider', 'ResolvedNode', 'System',
           'choose_client_library', 'resolve_node', 'resolve_registered', 'resolve_report']
