"""The ROS and NoDL vocabulary: every table of names the toolkit knows, written once.

Each fact here is defined in one place and everything else derives from it:

* endpoint sections (key, word in messages, kind, role, legacy XML role,
  interface namespace, sros2 permission);
* document kinds and the keys that tell them apart;
* ament index resource types (also used by ``cmake/ament_nodl``, which a
  test keeps in agreement with this table);
* parameter types;
* QoS keys, in the order a NoDL file writes them, and their values.

The built-in parameter validators have their own table, with behaviour, in
:mod:`nodl.validation.validators`.

This module imports nothing but :mod:`enum` and is cheap to import on the
command line path.
"""

from __future__ import annotations

import enum
from collections import namedtuple
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import NamedTuple

__all__ = [
    # endpoint sections
    'Section', 'SECTIONS', 'SECTION_KEYS', 'SECTION_BY_KEY', 'SECTION_WORDS',
    'ENDPOINT_KINDS', 'KIND_NAMESPACES', 'TOPIC_SECTIONS', 'SERVICE_SECTIONS', 'ACTION_SECTIONS',
    'sections_of_kind', 'section_for_role', 'legacy_roles',
    # document kinds
    'Kind', 'NODE_KEYS', 'INTERFACE_KEYS', 'INCLUDE_KEYS',
    # ament index
    'NODE_RESOURCE', 'INTERFACE_RESOURCE', 'LEGACY_RESOURCE', 'NODE_INFO_RESOURCE', 'REFERENCE_RESOURCE',
    'RESOURCE_TYPES',
    'RESOURCE_SEPARATOR', 'resource_name',
    # parameter types
    'SCALAR_TYPES', 'ARRAY_TYPES', 'FIXED_BASES', 'PARAMETER_TYPES', 'ALL_TYPE_WORDS',
    'ROS_PARAMETER_TYPES', 'ROS_PARAMETER_TYPE_NAMES', 'PARAMETER_TYPE_BY_NUMBER',
    # QoS
    'QOS_KEYS', 'QOS_REQUIRED', 'QOS_ENUMS', 'QOS_DURATIONS', 'QOS_DEFAULT_VALUE',
    # client libraries
    'CLIENT_LIBRARIES', 'BUILD_TYPE_LIBRARIES',
    # launch-file code
    'LAUNCH_CODE_TIMEOUT', 'LAUNCH_CODE_MEMORY_MIB',
    # ROS names
    'NAME_SUBSTITUTIONS',
]


# --------------------------------------------------------------------------
# Endpoint sections

if TYPE_CHECKING:
    class _SectionFields(NamedTuple):
        key: str
        word: str
        kind: str
        role: str
        legacy_role: str
        namespace: str
        permission: str
else:
    _SectionFields = namedtuple('Section', ['key', 'word', 'kind', 'role', 'legacy_role',
                                            'namespace', 'permission'])


class Section(_SectionFields):
    """One endpoint section of an interface definition.

    * ``key``: the key in a NoDL file (``publishers``);
    * ``word``: what one entry is called in messages (``publisher``);
    * ``kind``: ``topic``, ``service`` or ``action``;
    * ``role``: the node's role for that kind (``publisher``, ``subscription``,
      ``server``, ``client``);
    * ``legacy_role``: the role's name in the legacy XML formats (spec 000-002);
    * ``namespace``: the interface namespace of its types (``msg``, ``srv``, ``action``);
    * ``permission``: the sros2 permission it needs (``publish``, ``subscribe``,
      ``reply``, ``request``, ``execute``, ``call``).
    """

    __slots__ = ()


#: Every endpoint section, in the order a NoDL file writes them.
SECTIONS: tuple[Section, ...] = (
    Section('publishers', 'publisher', 'topic', 'publisher', 'publisher', 'msg', 'publish'),
    Section('subscriptions', 'subscription', 'topic', 'subscription', 'subscription', 'msg',
            'subscribe'),
    Section('service_servers', 'service server', 'service', 'server', 'server', 'srv', 'reply'),
    Section('service_clients', 'service client', 'service', 'client', 'client', 'srv', 'request'),
    Section('action_servers', 'action server', 'action', 'server', 'server', 'action', 'execute'),
    Section('action_clients', 'action client', 'action', 'client', 'client', 'action', 'call'),
)

#: Section keys in file order.
SECTION_KEYS: tuple[str, ...] = tuple(s.key for s in SECTIONS)
#: Section key -> its :class:`Section`.
SECTION_BY_KEY: dict[str, Section] = {s.key: s for s in SECTIONS}
#: Section key -> what one of its entries is called in messages.
SECTION_WORDS: dict[str, str] = {s.key: s.word for s in SECTIONS}
#: Endpoint kinds, in file order.
ENDPOINT_KINDS: tuple[str, ...] = tuple(dict.fromkeys(s.kind for s in SECTIONS))
#: Endpoint kind -> the interface namespace of its types.
KIND_NAMESPACES: dict[str, str] = {s.kind: s.namespace for s in SECTIONS}


def sections_of_kind(kind: str) -> tuple[str, ...]:
    """The section keys of an endpoint kind (``topic`` -> publishers, subscriptions)."""
    return tuple(s.key for s in SECTIONS if s.kind == kind)


def section_for_role(kind: str, legacy_role: str) -> str | None:
    """The section of a legacy ``(kind, role)`` pair, or None if there is none."""
    for s in SECTIONS:
        if s.kind == kind and s.legacy_role == legacy_role:
            return s.key
    return None


def legacy_roles(kind: str) -> tuple[str, ...]:
    """The legacy XML roles of an endpoint kind, in canonical order."""
    return tuple(s.legacy_role for s in SECTIONS if s.kind == kind)


#: Topic, service and action section keys.
TOPIC_SECTIONS: tuple[str, ...] = sections_of_kind('topic')
SERVICE_SECTIONS: tuple[str, ...] = sections_of_kind('service')
ACTION_SECTIONS: tuple[str, ...] = sections_of_kind('action')


# --------------------------------------------------------------------------
# Document kinds

class Kind(str, enum.Enum):
    """A kind of NoDL document; each has a schema."""

    PARAMETER = 'parameter'
    INTERFACE = 'interface'
    NODE = 'node'

    def __str__(self) -> str:
        return self.value


#: Keys only a node definition has.
NODE_KEYS: tuple[str, ...] = ('base', 'main', 'mixins')
#: Keys of the entities of an interface definition.
INTERFACE_KEYS: tuple[str, ...] = ('parameters',) + SECTION_KEYS
#: The reference implementation's key for composition, in both its spellings: a document
#: with it (and no base, main or mixins) is a node definition in the ``include`` dialect
#: (see :mod:`nodl.frontends.include`).
INCLUDE_KEYS: tuple[str, ...] = ('include', 'includes')


# --------------------------------------------------------------------------
# The ament index

#: Resource type of node definitions (``nodl_nodes/<package>__<executable>``).
NODE_RESOURCE = 'nodl_nodes'
#: Resource type of interface definitions (``nodl_interfaces/<package>__<name>``).
INTERFACE_RESOURCE = 'nodl_interfaces'
#: Resource type of the legacy marker (spec 001: ``nodl_desc/<package>``).
LEGACY_RESOURCE = 'nodl_desc'
#: Resource type of what a registered node records besides its file (its plugin class, its
#: default node name: ``nodl_node_info/<package>__<executable>``, see :mod:`nodl.registry.node_info`).
NODE_INFO_RESOURCE = 'nodl_node_info'
#: Resource type the reference implementation's current ``ament_nodl_register(NAME FILE f
#: [PACKAGE p])`` installs (``nodl/<package>__<name>``, the entry holding the document itself,
#: its ``local://`` includes rewritten to ``nodl://``): read as a node definition of executable
#: NAME and, for ``nodl://<package>/<name>``, as a document to include.
REFERENCE_RESOURCE = 'nodl'
#: Document kind -> resource type it is registered under.
RESOURCE_TYPES: dict[Kind, str] = {Kind.NODE: NODE_RESOURCE, Kind.INTERFACE: INTERFACE_RESOURCE}
#: Between the package and the executable (or interface name) in a resource name.
RESOURCE_SEPARATOR = '__'


def resource_name(package: str, name: str) -> str:
    """``<package>__<name>``: the resource name of a registration."""
    return f'{package}{RESOURCE_SEPARATOR}{name}'


# --------------------------------------------------------------------------
# Parameter types

#: Scalar parameter types (``none`` holds no value).
SCALAR_TYPES: tuple[str, ...] = ('bool', 'int', 'double', 'string', 'none')
#: Array parameter types.
ARRAY_TYPES: tuple[str, ...] = ('bool_array', 'int_array', 'double_array', 'string_array',
                                'byte_array')
#: Types that have a fixed-size form ``<base>_fixed_<N>``.
FIXED_BASES: tuple[str, ...] = ('string', 'int_array', 'double_array', 'string_array')
#: Every type name without a size.
PARAMETER_TYPES: tuple[str, ...] = SCALAR_TYPES + ARRAY_TYPES
#: For messages and suggestions.
ALL_TYPE_WORDS: tuple[str, ...] = PARAMETER_TYPES + tuple(f'{b}_fixed_N' for b in FIXED_BASES)
#: Parameter type -> ``rcl_interfaces/msg/ParameterType``: its constant's name and number.
ROS_PARAMETER_TYPES: dict[str, tuple[str, int]] = {
    'none': ('PARAMETER_NOT_SET', 0), 'bool': ('PARAMETER_BOOL', 1),
    'int': ('PARAMETER_INTEGER', 2), 'double': ('PARAMETER_DOUBLE', 3),
    'string': ('PARAMETER_STRING', 4), 'byte_array': ('PARAMETER_BYTE_ARRAY', 5),
    'bool_array': ('PARAMETER_BOOL_ARRAY', 6), 'int_array': ('PARAMETER_INTEGER_ARRAY', 7),
    'double_array': ('PARAMETER_DOUBLE_ARRAY', 8), 'string_array': ('PARAMETER_STRING_ARRAY', 9),
}
#: Parameter type -> its ``ParameterType`` constant's name (derived).
ROS_PARAMETER_TYPE_NAMES: dict[str, str] = {w: n for w, (n, _) in ROS_PARAMETER_TYPES.items()}
#: ``ParameterType`` number (as a running node reports it) -> parameter type (derived).
PARAMETER_TYPE_BY_NUMBER: dict[int, str] = {k: w for w, (_, k) in ROS_PARAMETER_TYPES.items()}


# --------------------------------------------------------------------------
# QoS

#: QoS keys in the order a NoDL file (and the model) writes them.
QOS_KEYS: tuple[str, ...] = ('history', 'reliability', 'depth', 'durability', 'deadline_ns',
                             'lifespan_ns', 'liveliness', 'liveliness_lease_duration_ns')
#: Keys a topic's QoS must give.
QOS_REQUIRED: tuple[str, ...] = ('history', 'reliability')
#: Enumerated policies -> their values (as rmw names them).
QOS_ENUMS: dict[str, tuple[str, ...]] = {
    'history': ('KEEP_LAST', 'KEEP_ALL', 'SYSTEM_DEFAULT'),
    'reliability': ('RELIABLE', 'BEST_EFFORT', 'SYSTEM_DEFAULT', 'BEST_AVAILABLE'),
    'durability': ('TRANSIENT_LOCAL', 'VOLATILE', 'SYSTEM_DEFAULT', 'BEST_AVAILABLE'),
    'liveliness': ('AUTOMATIC', 'MANUAL_BY_TOPIC', 'SYSTEM_DEFAULT', 'BEST_AVAILABLE'),
}
#: Duration keys (nanoseconds) -> the policy's name without the unit (rclpy, legacy XML).
QOS_DURATIONS: dict[str, str] = {
    'deadline_ns': 'deadline',
    'lifespan_ns': 'lifespan',
    'liveliness_lease_duration_ns': 'liveliness_lease_duration',
}
#: The value that claims nothing about a policy.
QOS_DEFAULT_VALUE = 'SYSTEM_DEFAULT'


# --------------------------------------------------------------------------
# Client libraries

#: The client libraries a built-in base has a variant for; the first is the default.
CLIENT_LIBRARIES: tuple[str, ...] = ('rclpy', 'rclcpp')
#: Package build type (``<export><build_type>``) -> the client library its nodes use.
BUILD_TYPE_LIBRARIES: dict[str, str] = {'ament_python': 'rclpy', 'ament_cmake': 'rclcpp'}


# --------------------------------------------------------------------------
# ROS names

#: The substitutions rcl expands in a topic or service name (``{node}``, ``{ns}``,
#: ``{namespace}``), without their braces; :mod:`nodl.naming` expands them.
NAME_SUBSTITUTIONS: tuple[str, ...] = ('node', 'ns', 'namespace')


# --------------------------------------------------------------------------
# Launch-file code (nodl.launch.sandbox runs it under these limits)

#: Seconds the Python code of one launch may run in all (``--launch-timeout``).
LAUNCH_CODE_TIMEOUT = 30.0
#: MiB of memory the Python code of a launch may take (``--launch-memory``).
LAUNCH_CODE_MEMORY_MIB = 2048.0
