"""The intermediate model every consumer shares: resolved nodes, instances, systems.

* :class:`ResolvedNode` (:func:`resolve_node`): a node definition composed
  (base of a client library, mixins, main) into typed :class:`Entity`
  objects: kind, provider, layer, typed QoS, parsed :class:`InterfaceType`,
  source :class:`Location`.
* :class:`NodeInstance`: a resolved node with a name, namespace, remapping
  rules and parameter overrides; every entity's final name, as rcl computes it.
* :class:`System`: instances and the :class:`Connection` on each topic,
  service and action, with :meth:`System.peers`.

Names are imported lazily, like the package's other ``__init__`` modules.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

_EXPORTS = {
    'Entity': 'entities', 'EntityKind': 'entities', 'InterfaceType': 'entities',
    'Location': 'entities', 'Provider': 'entities',
    'ResolvedNode': 'resolved', 'resolve_node': 'resolved', 'resolve_report': 'resolved',
    'resolve_registered': 'resolved',
    'InstanceEntity': 'instance', 'NodeInstance': 'instance',
    'Connection': 'connections', 'System': 'connections',
    'ClientLibraryChoice': '..composition.client_library',
    'choose_client_library': '..composition.client_library',
}

#: The public names (a test keeps this list equal to the keys of _EXPORTS).
__all__ = ['ClientLibraryChoice', 'Connection', 'Entity', 'EntityKind', 'InstanceEntity',
           'InterfaceType', 'Location', 'NodeInstance', 'Provider', 'ResolvedNode', 'System',
           'choose_client_library', 'resolve_node', 'resolve_registered', 'resolve_report']

if TYPE_CHECKING:  # pragma: no cover
    from nodl.composition.client_library import (
        ClientLibraryChoice,
        choose_client_library,
    )
    from nodl.system.connections import Connection, System
    from nodl.system.entities import (
        Entity,
        EntityKind,
        InterfaceType,
        Location,
        Provider,
    )
    from nodl.system.instance import InstanceEntity, NodeInstance
    from nodl.system.resolved import (
        ResolvedNode,
        resolve_node,
        resolve_registered,
        resolve_report,
    )


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    target = f'nodl{module[1:]}' if module.startswith('..') else f'{__name__}.{module}'
    value = getattr(importlib.import_module(target), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
