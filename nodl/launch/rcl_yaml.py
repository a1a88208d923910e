"""rcl's rules for a parameter file's YAML: which node keys apply to a node, and how a value is typed.

rcl files every parameter under a node key (``/**``, ``/*/name``, ``/ns/name``); a node takes
the keys that match its full name (``/*`` one name token, ``/**`` any number, a missing
leading ``/`` added), see :func:`match_parameter_file_nodes`; launch_ros, loading a
composable node, takes ``/**`` and its exact ``namespace/name`` only
(:func:`match_composable_parameter_keys`).  rcl types a scalar by its own YAML rules
(:func:`rcl_scalar`): ``y``/``on``/``yes`` are booleans, ``1e5`` and ``inf`` doubles, ``010``
octal, a quoted value a string.

Both the reader of parameter files (:mod:`nodl.launch.params`) and the resolution of what a
launched node receives (:mod:`nodl.launch.parameter_values`) use these rules; this module
imports neither.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from functools import lru_cache
from typing import Any

import yaml
from yaml.nodes import ScalarNode, SequenceNode
from yaml.resolver import Resolver

from nodl.naming import join_name

__all__ = ['match_parameter_file_nodes', 'match_composable_parameter_keys', 'node_key_applies',
           'composable_key', 'rcl_scalar', 'rcl_node_value', 'rcl_yaml_value']


# -- matching ----------------------------------------------------------------------------------

_PATTERNS: dict[str, re.Pattern[str]] = {}


def _pattern(key: str) -> re.Pattern[str]:
    pattern = _PATTERNS.get(key)
    if pattern is None:
        name = key if key.startswith('/') else '/' + key
        # rclcpp and rclpy: every "/*" becomes "(/\w+)" (so "/**" is "(/\w+)*"); the rest is literal.
        regex = r'(/\w+)'.join(re.escape(p).replace(r'\*', '*') for p in name.split('/*'))
        try:
            pattern = re.compile(regex, re.ASCII)
        except re.error:
            pattern = re.compile(re.escape(name))
        if len(_PATTERNS) > 4096:
            _PATTERNS.clear()
        _PATTERNS[key] = pattern
    return pattern


def match_parameter_file_nodes(keys: Iterable[str], node_fqn: str) -> list[str]:
    """The node keys that apply to a node started as a process called ``node_fqn``, in order.

    A key applies when the full name matches it entirely, ``/*`` standing for one name token
    and ``/**`` for any number of them (``/**``, ``/*``, ``/**/name``, ``/ns/*``); a key
    without a leading ``/`` gets one.  Which value wins among matching keys is decided by
    the order of rcl's merged table: see :func:`process_overrides`.
    """
    return [key for key in keys if node_key_applies(key, node_fqn)]


def node_key_applies(key: str, node_fqn: str) -> bool:
    """True if the node key ``key`` applies to the node called ``node_fqn``."""
    # A key without a wildcard names one node (each node's inline parameters carry its own
    # name, so a launched system has as many such keys as nodes): compared, not compiled.
    if '*' not in key:
        return (key if key[:1] == '/' else _absolute_key(key)) == node_fqn
    return _pattern(key).fullmatch(node_fqn) is not None


def _absolute_key(key: str) -> str:
    """A node key as rcl compares it: with a leading ``/``."""
    name = key if key.startswith('/') else '/' + key
    return name


def composable_key(key: str) -> str:
    """A parameter file's node key as launch_ros compares it for a composable node (the
    leading slashes of every part dropped)."""
    return '/'.join(part.lstrip('/') for part in key.split('/') if part)


def match_composable_parameter_keys(keys: Iterable[str], node_name: str | None,
                                    namespace: str) -> list[str]:
    """The keys launch_ros applies to a composable node: ``/**`` first, then its exact name.

    launch_ros reads the file itself (``to_parameters_list``): nested keys joined with ``/``,
    leading slashes dropped, and only ``**`` and ``namespace/name`` taken; a node loaded
    without a name (``node_name`` None) gets ``**`` only.
    """
    keys = list(keys)
    normalized = {k: composable_key(k) for k in keys}
    out = [k for k in keys if normalized[k] == '**']
    if node_name:
        # launch_ros's keys have no leading '/'
        wanted = join_name(namespace or '/', node_name.lstrip('/')).lstrip('/')
        out += [k for k in keys if normalized[k] == wanted and wanted != '**']
    return out


# -- rcl's typing ----------------------------------------------------------------------------

_STR_TAG = 'tag:yaml.org,2002:str'
_TRUE = frozenset({'Y', 'y', 'yes', 'Yes', 'YES', 'true', 'True', 'TRUE', 'on', 'On', 'ON'})
_FALSE = frozenset({'N', 'n', 'no', 'No', 'NO', 'false', 'False', 'FALSE', 'off', 'Off', 'OFF'})
_INT = re.compile(r'\s*([+-]?)(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)')
_FLOAT = re.compile(r'\s*[+-]?(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?'
                    r'|0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)(?:[pP][+-]?[0-9]+)?'
                    r'|(?i:inf(?:inity)?|nan(?:\([0-9A-Za-z_]*\))?))')
_SPECIAL = frozenset({'.nan', '.NaN', '.NAN', '.inf', '.Inf', '.INF', '+.inf', '+.Inf', '+.INF',
                      '-.inf', '-.Inf', '-.INF'})
_INT64 = 2 ** 63


def _rcl_number(text: str) -> Any:
    match = _INT.fullmatch(text)
    if match:
        sign, digits = match.groups()
        base = 16 if digits[:2] in ('0x', '0X') else 8 if digits.startswith('0') and digits != '0' else 10
        # More than 24 significant digits is out of int64's range in any base (and int() of a
        # long decimal text raises past Python's 4,300-digit limit).
        if len(digits[2 if base == 16 else 0:].lstrip('0')) <= 24:
            value = int(digits, base) * (-1 if sign == '-' else 1)
            if -_INT64 <= value < _INT64:
                return value
    if text in _SPECIAL:
        special = math.inf if 'inf' in text.lower() else math.nan
        return -special if text.startswith('-') else special
    if _FLOAT.fullmatch(text):
        body = text.strip()
        try:
            number = float.fromhex(body) if 'x' in body.lower() else float(body.split('(')[0])
        except (ValueError, OverflowError):  # fromhex: too large for a double (strtod: ERANGE)
            return None
        if math.isinf(number) and 'inf' not in body.lower():
            return None  # strtod: out of range (ERANGE), not a double
        return number
    return None


def rcl_scalar(text: str, *, quoted: bool = False, tagged_str: bool = False) -> Any:
    """A YAML scalar as rcl's parameter parser types it (``rcl_yaml_param_parser`` ``get_value``).

    ``!!str`` or quoted: a string; else ``Y``/``yes``/``true``/``on``... a bool, what
    ``strtoll`` reads entirely (base 0: ``0x1F``, octal ``010``) an int, what ``strtod``
    reads entirely (``1e5``, ``inf``, ``.nan``) a double, anything else a string.
    """
    if tagged_str or quoted:
        return text
    return _plain_scalar(text) if len(text) <= _SHORT else _rcl_plain(text)


def _rcl_plain(text: str) -> Any:
    if text in _TRUE:
        return True
    if text in _FALSE:
        return False
    number = _rcl_number(text)
    return text if number is None else number


#: Values at most this long are typed once each (parameter files repeat true, 0.0, odom...).
_SHORT = 64
_plain_scalar = lru_cache(maxsize=4096)(_rcl_plain)


def _implicit_tag(kind: Any, value: str) -> Any:
    """The tag PyYAML's resolver gives a plain scalar ``value`` of node class ``kind``."""
    if len(value) <= _SHORT:
        return _short_implicit_tag(kind, value)
    return _RESOLVER.resolve(kind, value, (True, False))


@lru_cache(maxsize=4096)
def _short_implicit_tag(kind: Any, value: str) -> Any:
    return _RESOLVER.resolve(kind, value, (True, False))


#: PyYAML's resolver (its resolve() keeps no state between calls).
_RESOLVER: Any = Resolver()


def _scalar_node(node: Any) -> Any:
    quoted = node.style in ("'", '"')
    explicit = (node.tag == _STR_TAG and not node.style
                and _implicit_tag(type(node), node.value) != _STR_TAG)
    return rcl_scalar(node.value, quoted=quoted, tagged_str=explicit)


def rcl_node_value(node: Any) -> Any:
    """A composed YAML node (scalar or sequence of scalars) as rcl types it."""
    if isinstance(node, ScalarNode):
        return _scalar_node(node)
    if isinstance(node, SequenceNode):
        return [_scalar_node(item) if isinstance(item, ScalarNode) else None for item in node.value]
    return None


def rcl_yaml_value(text: str) -> Any:
    """The value of ``-p NAME:=TEXT`` as rcl types it (the text read as one YAML value)."""
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError:
        return text
    if node is None:
        return text
    value = rcl_node_value(node)
    return text if value is None else value
