"""Parameter values: read from text as launch types them, written so that launch reads them back.

A value given on the command line (``nodl system set FILE NODE NAME VALUE``) is typed as
``ros2 launch`` types a ``<param value=...>``: YAML rules (``0.4`` a double, ``3`` an integer,
``true`` a bool, ``[1, 2]`` a list, anything else a string).  Each writer spells a value so
that the launch reader reads it back as the same typed value, adding ``type="str"`` where
the bare text would be read as something else (a string ``'3'``).
"""

from __future__ import annotations

import math
from typing import Any

import yaml

from nodl.launch.errors import LaunchProblem
from nodl.launch.params import get_typed_value

__all__ = ['python_value', 'same_value', 'typed_value', 'xml_value', 'yaml_value_text']


def typed_value(text: str) -> Any:
    """``text`` typed as launch types a parameter's ``value`` attribute (ValueError when launch
    would refuse it: a mapping, a list that mixes types)."""
    try:
        return get_typed_value(text, None)
    except LaunchProblem as exc:
        raise ValueError(exc.message) from None


def same_value(first: Any, second: Any) -> bool:
    """True for the same value of the same type (``1 != 1.0``, ``True != 1``)."""
    if type(first) is not type(second):
        return False
    if isinstance(first, list):
        return len(first) == len(second) and all(same_value(a, b) for a, b in zip(first, second, strict=True))
    if isinstance(first, float) and math.isnan(first):
        return math.isnan(second)
    return bool(first == second)


def _scalar_text(value: Any) -> str:
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, float):
        if math.isnan(value):
            return '.nan'
        if math.isinf(value):
            return '.inf' if value > 0 else '-.inf'
        text = repr(value)
        if 'e' in text:
            mantissa, _, exponent = text.partition('e')
            if '.' not in mantissa:
                mantissa += '.0'
            if exponent[0] not in '+-':
                exponent = '+' + exponent
            text = f'{mantissa}e{exponent}'
        return text
    return str(value)


def _flow_text(value: Any) -> str:
    """YAML flow text of a value (strings quoted when needed)."""
    if isinstance(value, list):
        return '[' + ', '.join(_flow_text(v) for v in value) + ']'
    if isinstance(value, str):
        text = str(yaml.safe_dump(value, default_flow_style=True, width=1 << 30)).strip() \
            .removesuffix('\n...').removesuffix('...').strip()
        if '\n' in text:  # one line always: a double-quoted scalar with escapes
            text = str(yaml.safe_dump(value, default_style='"', width=1 << 30)).strip()
        return text
    return _scalar_text(value)


def xml_value(value: Any) -> tuple[str, str | None]:
    """``(value attribute text, type attribute or None)`` that launch's XML frontend reads back as
    ``value``."""
    text = value if isinstance(value, str) else _flow_text(value)
    if _reads_back(get_typed_value, text, value):
        return text, None
    if isinstance(value, str):
        return value, 'str'
    if isinstance(value, list) and value:
        names = {bool: 'bool', int: 'int', float: 'float', str: 'str'}
        return _flow_text(value), f'list_of_{names[type(value[0])]}'
    return text, None


def yaml_value_text(value: Any) -> str:
    """The YAML text of ``value`` in a launch YAML ``param`` entry (launch_yaml types a string
    value again: a string that would be read as another type is given ``type: str`` by the
    caller, see :func:`yaml_needs_type`)."""
    return _flow_text(value)


def yaml_needs_type(value: Any) -> str | None:
    """The ``type`` a YAML ``param`` entry needs to be read back as ``value`` (None: none)."""
    if isinstance(value, str):
        return None if _reads_back(get_typed_value, value, value) else 'str'
    if isinstance(value, list) and any(isinstance(v, str) for v in value):
        return 'list_of_str'
    return None


def _reads_back(typing: Any, text: str, value: Any) -> bool:
    """True when launch types ``text`` (no type given) as ``value``."""
    try:
        return same_value(typing(text, None), value)
    except LaunchProblem:
        return False


def python_value(value: Any) -> str:
    """A Python literal of ``value``."""
    if isinstance(value, float) and (math.isnan(value) or math.isinf(value)):
        return f"float('{value}')"
    if isinstance(value, list):
        return '[' + ', '.join(python_value(v) for v in value) + ']'
    return repr(value)
