"""The document model: typed classes for the three kinds of NoDL document.

Names are imported lazily: validation needs only ``parameter_types``, and the
command line should not pay for the dataclasses it does not use.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

_EXPORTS = {
    'ENDPOINT_SECTIONS': 'interface', 'ActionEndpoint': 'interface', 'Endpoint': 'interface',
    'Interface': 'interface', 'ServiceEndpoint': 'interface', 'TopicEndpoint': 'interface',
    'Base': 'node', 'Mixin': 'node', 'Node': 'node',
    'ParameterDefinition': 'parameter',
    'QOS_POLICIES': 'qos', 'QoSProfile': 'qos',
}

#: The public names, written out for type checkers and readers; a test keeps it equal
#: to the keys of _EXPORTS.
__all__ = ['ActionEndpoint', 'Base', 'ENDPOINT_SECTIONS', 'Endpoint', 'Interface', 'Mixin',
    'Node', 'ParameterDefinition', 'QOS_POLICIES', 'QoSProfile', 'ServiceEndpoint',
    'TopicEndpoint']

if TYPE_CHECKING:  # pragma: no cover
    from nodl.model.interface import (
        ENDPOINT_SECTIONS,
        ActionEndpoint,
        Endpoint,
        Interface,
        ServiceEndpoint,
        TopicEndpoint,
    )
    from nodl.model.node import Base, Mixin, Node
    from nodl.model.parameter import ParameterDefinition
    from nodl.model.qos import QOS_POLICIES, QoSProfile


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    value = getattr(importlib.import_module(f'{__name__}.{module}'), name)
    globals()[name] = value
    return value
