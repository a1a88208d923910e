"""The document model: typed classes for the three kinds of NoDL document.

Names are imported lazily (PEP 562 ``__getattr__``), on purpose: ``nodl validate`` needs
only :mod:`nodl.model.parameter_types` (which loads this package), and plain imports here
would load the four dataclass modules and ``dataclasses`` itself (with ``inspect``) into
every validation.  Measured for issue 16 (``nodl validate FILE``, 60 interleaved cold starts
on a loaded machine): 67.6 ms lazy against 78.4 ms plain at best, 82 against 102 ms median,
where ``python -I -c "import yaml"`` takes 39 ms: the cold-start budget (1.5x) has no room
for that.  A module that needs the classes loads them when it is imported, as before.
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
