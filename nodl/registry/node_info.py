"""What a registration records about a node besides its definition: plugin and node name.

``ament_nodl_register_node(KEY FILE f PLUGIN pkg::ClassName NODE_NAME n)`` (and
``nodl_data_files(..., node_info={KEY: {'plugin': ..., 'node_name': ...}})``)
write a second index entry next to ``nodl_nodes/<package>__<KEY>``:
``nodl_node_info/<package>__<KEY>``, one ``name=value`` line per attribute:

* ``plugin=pkg::ClassName``: the composable node class the definition describes,
  so that ``load_composable_node`` / ``ComposableNode(plugin=...)`` finds it;
* ``node_name=n``: the name the executable gives its node when launched without
  ``name`` (NoDL keeps identity out of the definition, so the registration holds it).

Unknown attribute names are ignored (newer toolkits may record more).

Definitions folders in force (:mod:`nodl.registry.overlay`) come first: their
packages' ``nodes.yaml`` record the same attributes.
"""

from __future__ import annotations

import re
from typing import NamedTuple

from nodl import ament_index
from nodl.registry import overlay
from nodl.vocabulary import NODE_INFO_RESOURCE, resource_name

__all__ = ['NODE_INFO_RESOURCE', 'NODE_INFO_ATTRIBUTES', 'NodeInfo', 'parse_node_info',
           'read_node_info', 'find_plugin', 'format_node_info', 'plugin_key']

#: The attributes an entry may hold, and what each is.
NODE_INFO_ATTRIBUTES = {
    'plugin': 'the composable node class (pkg::ClassName) the definition describes',
    'node_name': 'the name the executable gives its node when launched without a name',
}
_PLUGIN = re.compile(r'[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)*')
_NODE_NAME = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')


class NodeInfo(NamedTuple):
    """The attributes recorded for ``package``'s registration ``key``."""

    package: str
    key: str
    plugin: str | None = None
    node_name: str | None = None


def parse_node_info(package: str, key: str, content: str) -> NodeInfo:
    """The attributes of an entry's content (``name=value`` lines)."""
    values: dict[str, str] = {}
    for line in content.splitlines():
        name, sep, value = line.partition('=')
        if sep and name.strip() in NODE_INFO_ATTRIBUTES and value.strip():
            values[name.strip()] = value.strip()
    return NodeInfo(package, key, values.get('plugin'), values.get('node_name'))


def format_node_info(plugin: str | None = None, node_name: str | None = None) -> str:
    """The content of an entry; ValueError for a malformed plugin class or node name."""
    lines = []
    if plugin is not None:
        if not _PLUGIN.fullmatch(plugin):
            raise ValueError(f"'{plugin}' is not a plugin class name (expected pkg::ClassName)")
        lines.append(f'plugin={plugin}')
    if node_name is not None:
        if not _NODE_NAME.fullmatch(node_name):
            raise ValueError(f"'{node_name}' is not a valid node name (letters, digits and '_', "
                             'not starting with a digit)')
        lines.append(f'node_name={node_name}')
    return ''.join(line + '\n' for line in lines)


def read_node_info(package: str, key: str, prefixes: list[str] | None = None) -> NodeInfo:
    """What ``package``'s registration ``key`` records (empty attributes if nothing)."""
    definitions = overlay.active()
    if definitions:
        recorded = definitions.node_info(package, key)
        if recorded is not None:
            return NodeInfo(package, key, *recorded)
    resource = ament_index.get_resource(NODE_INFO_RESOURCE, resource_name(package, key), prefixes)
    if resource is None:
        return NodeInfo(package, key)
    return parse_node_info(package, key, resource.content)


def find_plugin(package: str, plugin: str, prefixes: list[str] | None = None) -> NodeInfo | None:
    """The registration of ``package`` that records ``plugin`` as its class, or None."""
    definitions = overlay.active()
    if definitions:
        key = definitions.find_plugin(package, plugin)
        if key is not None:
            return NodeInfo(package, key, *(definitions.node_info(package, key) or (None, None)))
    start = resource_name(package, '')
    for name, prefix in ament_index.get_resources(NODE_INFO_RESOURCE, prefixes).items():
        if not name.startswith(start):
            continue
        resource = ament_index.get_resource(NODE_INFO_RESOURCE, name, [prefix])
        if resource is None:
            continue
        info = parse_node_info(package, name[len(start):], resource.content)
        if info.plugin == plugin:
            return info
    return None


def plugin_key(plugin: str) -> str:
    """The registration key a plugin class falls back to: its class name in snake case
    (``rover_sensors::CameraDriver`` -> ``camera_driver``, ``HTTPServer`` -> ``http_server``)."""
    name = plugin.rsplit('::', 1)[-1]
    name = re.sub(r'([A-Z]+)([A-Z][a-z])', r'\1_\2', name)
    name = re.sub(r'([a-z0-9])([A-Z])', r'\1_\2', name)
    return name.lower()

