"""NoDL toolkit: the ROS 2 Node Definition Language (v2) in Python.

The public API (importable without ROS)::

    from nodl_schema import load_nodl, dump_nodl, ValidationError

    node = load_nodl(pathlib.Path('driver.nodl.yaml'))

Names are imported lazily so that the command line starts fast.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

__version__ = '0.1.0'

_EXPORTS = {
    'load_nodl': 'nodl_schema.loading',
    'load_parameter': 'nodl_schema.loading',
    'load_interface': 'nodl_schema.loading',
    'load_node': 'nodl_schema.loading',
    'validate_parameter': 'nodl_schema.loading',
    'validate_interface': 'nodl_schema.loading',
    'validate_node': 'nodl_schema.loading',
    'dump_nodl': 'nodl_schema.loading',
    'check_source': 'nodl_schema.loading',
    'model_from_data': 'nodl_schema.loading',
    'Report': 'nodl_schema.loading',
    'Document': 'nodl_schema.loading',
    'Interface': 'nodl_schema.model',
    'Node': 'nodl_schema.model',
    'ParameterDefinition': 'nodl_schema.model',
    'Base': 'nodl_schema.model',
    'QoSProfile': 'nodl_schema.model',
    'TopicEndpoint': 'nodl_schema.model',
    'ServiceEndpoint': 'nodl_schema.model',
    'ActionEndpoint': 'nodl_schema.model',
    'ValidationError': 'nodl_schema.diagnostics',
    'Diagnostic': 'nodl_schema.diagnostics',
    'Severity': 'nodl_schema.diagnostics',
    'Kind': 'nodl_schema.validation.kinds',
    'detect_kind': 'nodl_schema.validation.kinds',
    'compose': 'nodl_schema.composition',
    'ComposedNode': 'nodl_schema.composition',
    'load_schema': 'nodl_schema.schemas',
    'bundled_schema': 'nodl_schema.schemas',
    'expand_name': 'nodl_schema.naming',
    'resolve_name': 'nodl_schema.naming',
    'node_fqn': 'nodl_schema.naming',
    'parse_remap_rules': 'nodl_schema.naming',
    'RemapRule': 'nodl_schema.naming',
    'NodeNames': 'nodl_schema.naming',
    'InvalidNameError': 'nodl_schema.naming',
    'InvalidRemapRuleError': 'nodl_schema.naming',
    'check_qos_compatible': 'nodl_schema.qos_compat',
    'ResolvedNode': 'nodl_schema.system',
    'resolve_node': 'nodl_schema.system',
    'Entity': 'nodl_schema.system',
    'EntityKind': 'nodl_schema.system',
    'Provider': 'nodl_schema.system',
    'InterfaceType': 'nodl_schema.system',
    'Location': 'nodl_schema.system',
    'NodeInstance': 'nodl_schema.system',
    'System': 'nodl_schema.system',
    'Connection': 'nodl_schema.system',
}

#: The public names, written out for type checkers and readers; a test keeps it equal
#: to the keys of _EXPORTS.
__all__ = ['ActionEndpoint', 'Base', 'ComposedNode', 'Diagnostic', 'Document', 'Interface',
    'Kind', 'Node', 'ParameterDefinition', 'QoSProfile', 'Report', 'ServiceEndpoint',
    'Severity', 'TopicEndpoint', 'ValidationError', 'bundled_schema', 'check_source',
    'compose', 'detect_kind', 'dump_nodl', 'load_interface', 'load_node', 'load_nodl',
    'load_parameter', 'load_schema', 'model_from_data', 'validate_interface', 'validate_node',
    'validate_parameter',
    'InvalidNameError', 'InvalidRemapRuleError', 'NodeNames', 'RemapRule', 'check_qos_compatible',
    'expand_name', 'node_fqn', 'parse_remap_rules', 'resolve_name',
    'Connection', 'Entity', 'EntityKind', 'InterfaceType', 'Location', 'NodeInstance', 'Provider',
    'ResolvedNode', 'System', 'resolve_node']

if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from nodl_schema.composition.compose import ComposedNode, compose
    from nodl_schema.diagnostics import Diagnostic, Severity, ValidationError
    from nodl_schema.loading import (
        Document, Report, check_source, dump_nodl, load_interface, load_node, load_nodl,
        load_parameter, model_from_data, validate_interface, validate_node, validate_parameter)
    from nodl_schema.model import (
        ActionEndpoint, Base, Interface, Node, ParameterDefinition, QoSProfile, ServiceEndpoint,
        TopicEndpoint)
    from nodl_schema.naming import (InvalidNameError, InvalidRemapRuleError, NodeNames, RemapRule,
                                    expand_name, node_fqn, parse_remap_rules, resolve_name)
    from nodl_schema.qos_compat import check_qos_compatible
    from nodl_schema.schemas import bundled_schema, load_schema
    from nodl_schema.system import (
        Connection, Entity, EntityKind, InterfaceType, Location, NodeInstance, Provider,
        ResolvedNode, System, resolve_node)
    from nodl_schema.validation.kinds import Kind, detect_kind


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
