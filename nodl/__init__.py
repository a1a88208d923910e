"""NoDL toolkit: the ROS 2 Node Definition Language (v2) in Python.

The public API (importable without ROS)::

    from nodl import load_nodl, dump_nodl, ValidationError

    node = load_nodl(pathlib.Path('driver.nodl.yaml'))

The names are loaded on first use (PEP 562 ``__getattr__``), here and nowhere else:
this package is the one the command line must import before anything else, and
``nodl validate FILE`` would pay about a third more start-up time if it loaded the
whole API (the composition, the resolved node, the system; measured for issue 16).
Below this package every module imports plainly, at its top; the command line loads
only the verb that runs.
"""

from __future__ import annotations

import importlib
import warnings
from typing import TYPE_CHECKING, Any

from nodl.version import __version__ as __version__

#: Where each public name is defined.
_EXPORTS = {
    'load_nodl': 'nodl.loading',
    'load_parameter': 'nodl.loading',
    'load_interface': 'nodl.loading',
    'load_node': 'nodl.loading',
    'validate_parameter': 'nodl.loading',
    'validate_interface': 'nodl.loading',
    'validate_node': 'nodl.loading',
    'dump_nodl': 'nodl.loading',
    'check_source': 'nodl.loading',
    'model_from_data': 'nodl.loading',
    'CheckedSource': 'nodl.loading',
    'Document': 'nodl.loading',
    'Interface': 'nodl.model',
    'Node': 'nodl.model',
    'ParameterDefinition': 'nodl.model',
    'Base': 'nodl.model',
    'QoSProfile': 'nodl.model',
    'TopicEndpoint': 'nodl.model',
    'ServiceEndpoint': 'nodl.model',
    'ActionEndpoint': 'nodl.model',
    'ValidationError': 'nodl.diagnostics',
    'Diagnostic': 'nodl.diagnostics',
    'Severity': 'nodl.diagnostics',
    'Kind': 'nodl.validation.kinds',
    'detect_kind': 'nodl.validation.kinds',
    'compose': 'nodl.composition',
    'ComposedNode': 'nodl.composition',
    'load_schema': 'nodl.schemas',
    'bundled_schema': 'nodl.schemas',
    'expand_name': 'nodl.naming',
    'resolve_name': 'nodl.naming',
    'node_fqn': 'nodl.naming',
    'parse_remap_rules': 'nodl.naming',
    'RemapRule': 'nodl.naming',
    'NodeNames': 'nodl.naming',
    'InvalidNameError': 'nodl.naming',
    'InvalidRemapRuleError': 'nodl.naming',
    'check_qos_compatible': 'nodl.qos_compat',
    'ResolvedNode': 'nodl.system',
    'resolve_node': 'nodl.system',
    'Entity': 'nodl.system',
    'EntityKind': 'nodl.system',
    'Provider': 'nodl.system',
    'InterfaceType': 'nodl.system',
    'Location': 'nodl.system',
    'NodeInstance': 'nodl.system',
    'System': 'nodl.system',
    'Connection': 'nodl.system',
}

#: The public names, written out for type checkers and readers; a test keeps it equal
#: to the keys of _EXPORTS and to the imports for type checkers below.
__all__ = ['ActionEndpoint', 'Base', 'ComposedNode', 'Diagnostic', 'Document', 'Interface',
    'Kind', 'Node', 'ParameterDefinition', 'QoSProfile', 'CheckedSource', 'ServiceEndpoint',
    'Severity', 'TopicEndpoint', 'ValidationError', 'bundled_schema', 'check_source',
    'compose', 'detect_kind', 'dump_nodl', 'load_interface', 'load_node', 'load_nodl',
    'load_parameter', 'load_schema', 'model_from_data', 'validate_interface', 'validate_node',
    'validate_parameter',
    'InvalidNameError', 'InvalidRemapRuleError', 'NodeNames', 'RemapRule', 'check_qos_compatible',
    'expand_name', 'node_fqn', 'parse_remap_rules', 'resolve_name',
    'Connection', 'Entity', 'EntityKind', 'InterfaceType', 'Location', 'NodeInstance', 'Provider',
    'ResolvedNode', 'System', 'resolve_node']

if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from nodl.composition.compose import ComposedNode, compose
    from nodl.diagnostics import Diagnostic, Severity, ValidationError
    from nodl.loading import (
        CheckedSource,
        Document,
        check_source,
        dump_nodl,
        load_interface,
        load_node,
        load_nodl,
        load_parameter,
        model_from_data,
        validate_interface,
        validate_node,
        validate_parameter,
    )
    from nodl.model import (
        ActionEndpoint,
        Base,
        Interface,
        Node,
        ParameterDefinition,
        QoSProfile,
        ServiceEndpoint,
        TopicEndpoint,
    )
    from nodl.naming import (
        InvalidNameError,
        InvalidRemapRuleError,
        NodeNames,
        RemapRule,
        expand_name,
        node_fqn,
        parse_remap_rules,
        resolve_name,
    )
    from nodl.qos_compat import check_qos_compatible
    from nodl.schemas import bundled_schema, load_schema
    from nodl.system import (
        Connection,
        Entity,
        EntityKind,
        InterfaceType,
        Location,
        NodeInstance,
        Provider,
        ResolvedNode,
        System,
        resolve_node,
    )
    from nodl.validation.kinds import Kind, detect_kind


#: Former public names -> their names now (each warns when used, for one release).
_RENAMED = {'Report': 'CheckedSource'}


def __getattr__(name: str) -> Any:
    if name in _RENAMED:
        warnings.warn(f'nodl.{name} is now nodl.{_RENAMED[name]}', DeprecationWarning, stacklevel=2)
        return __getattr__(_RENAMED[name])
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
