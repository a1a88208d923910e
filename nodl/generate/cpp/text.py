"""C++ spelling: literals, comments and names, escaped so that no definition text can break out.

Everything a definition writes (names, descriptions, default values, file
names) reaches generated C++ through this module:

* :func:`string_literal` writes a ``"..."`` literal of the text's UTF-8 bytes;
  anything but printable ASCII becomes a three-digit octal escape (never
  ``\\x``, which would swallow the hexadecimal digits that follow);
* :func:`comment_lines` writes ``//`` or ``///`` comment lines: one line per
  line of text, control characters replaced, and a backslash spelled as the
  entity ``&#92;`` (a ``\\`` at the end of a line comment would continue the
  comment onto the next line of code; Doxygen renders the entity as ``\\``),
  together with ``&``, ``<``, ``>`` and ``@`` that Doxygen would interpret;
* :func:`cpp_value` writes a parameter value as a C++ expression of a type;
* :func:`interface_cpp` and :func:`interface_header` give the C++ type and
  header of a ROS interface type, as rosidl names them.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from functools import lru_cache
from typing import Any

from nodl.text_safety import escape_character

__all__ = ['string_literal', 'comment_lines', 'comment_text', 'cpp_value', 'CPP_TYPES',
           'cpp_type', 'interface_cpp', 'interface_header', 'rosidl_file_stem']

_PLAIN = frozenset(range(0x20, 0x7f)) - {ord('"'), ord('\\'), ord('?')}
_QUOTED = {ord('"'): '\\"', ord('\\'): '\\\\', ord('?'): '\\?', ord('\n'): '\\n', ord('\t'): '\\t'}


@lru_cache(maxsize=4096)
def string_literal(text: str) -> str:
    """A C++ narrow string literal holding ``text`` encoded as UTF-8."""
    if text.isascii() and text.isprintable() and not any(c in text for c in '"\\?'):
        return '"' + text + '"'
    out = []
    for byte in text.encode('utf-8', 'surrogatepass'):
        if byte in _PLAIN:
            out.append(chr(byte))
        else:
            out.append(_QUOTED.get(byte, f'\\{byte:03o}'))
    return '"' + ''.join(out) + '"'


# C0, DEL, C1 and the bidi controls (nodl.text_safety), written as visible escapes
_CONTROL = re.compile('[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]')
# '??' starts a trigraph before C++17 ('??/' is a backslash, which could continue the comment)
_TRIGRAPH = re.compile(r'\?(?=\?)')
_COMMENT_ENTITIES = {'&': '&amp;', '<': '&lt;', '>': '&gt;', '\\': '&#92;', '@': '&#64;'}
_ENTITY_CHARS = re.compile('[&<>\\\\@]')


def comment_text(text: str) -> list[str]:
    """The lines of ``text`` made safe inside a C++ line comment (see the module docstring)."""
    lines = []
    for line in str(text).splitlines() or ['']:
        line = _ENTITY_CHARS.sub(lambda m: _COMMENT_ENTITIES[m.group(0)], line)
        line = _CONTROL.sub(lambda m: escape_character(m.group(0)).replace('\\', '&#92;'), line)
        line = _TRIGRAPH.sub('&#63;', line)
        lines.append(line.rstrip())
    return lines


def comment_lines(text: str | None, indent: str = '', marker: str = '///') -> list[str]:
    """``text`` as comment lines (none for empty text)."""
    if not text:
        return []
    return [f'{indent}{marker} {line}'.rstrip() for line in comment_text(text)]


# --------------------------------------------------------------------------
# Parameter types and values

#: Element kind (:attr:`TypeSpec.element`) -> the C++ type of a scalar.
_ELEMENT_TYPES = {'bool': 'bool', 'int': 'int64_t', 'double': 'double', 'string': 'std::string',
                  'byte': 'uint8_t'}
#: Parameter type (without fixed size) -> the C++ type of the field holding it.
CPP_TYPES: dict[str, str] = {
    'bool': 'bool', 'int': 'int64_t', 'double': 'double', 'string': 'std::string',
    'bool_array': 'std::vector<bool>', 'int_array': 'std::vector<int64_t>',
    'double_array': 'std::vector<double>', 'string_array': 'std::vector<std::string>',
    'byte_array': 'std::vector<uint8_t>',
}


def cpp_type(base: str) -> str:
    """The C++ type of a parameter of (unsized) type ``base``."""
    return CPP_TYPES[base]


def _int_literal(value: int) -> str:
    if value == -2 ** 63:
        return '(-INT64_C(9223372036854775807) - 1)'
    return f'INT64_C({value})'


def _double_literal(value: float) -> str:
    if math.isnan(value):
        return 'std::numeric_limits<double>::quiet_NaN()'
    if math.isinf(value):
        return ('' if value > 0 else '-') + 'std::numeric_limits<double>::infinity()'
    text = repr(float(value))
    return text if any(c in text for c in '.en') else text + '.0'


def element_value(value: Any, element: str) -> str:
    """One scalar value as a C++ expression of the element type."""
    if element == 'bool':
        return 'true' if value else 'false'
    if element == 'int':
        return _int_literal(int(value))
    if element == 'byte':
        return f'static_cast<uint8_t>({int(value)})'
    if element == 'double':
        return _double_literal(float(value))
    text = str(value)
    if '\0' in text:  # a literal stops at its first NUL: give the length
        return f"std::string({string_literal(text)}, {len(text.encode('utf-8', 'surrogatepass'))})"
    return f'std::string({string_literal(text)})'


def cpp_value(value: Any, base: str) -> str:
    """A parameter value of (unsized) type ``base`` as a C++ expression of :func:`cpp_type`."""
    if base.endswith('_array'):
        element = 'byte' if base == 'byte_array' else base[:-len('_array')]
        items = ', '.join(element_value(v, element) for v in value)
        return f'{cpp_type(base)}{{{items}}}'
    return element_value(value, base)


# --------------------------------------------------------------------------
# ROS interface types

_WORD_START = re.compile(r'(.)([A-Z][a-z]+)')
_AFTER_LOWER = re.compile(r'([a-z0-9])([A-Z])')


def rosidl_file_stem(name: str) -> str:
    """The file stem rosidl gives an interface (``LaserScan`` -> ``laser_scan``).

    An underscore goes before each capital that starts a lowercase word, and
    before each capital that follows a lowercase letter or a digit.
    """
    return _AFTER_LOWER.sub(r'\1_\2', _WORD_START.sub(r'\1_\2', name)).lower()


def interface_cpp(package: str, namespace: str, name: str) -> str:
    """``sensor_msgs::msg::LaserScan``."""
    return f'{package}::{namespace}::{name}'


def interface_header(package: str, namespace: str, name: str) -> str:
    """``sensor_msgs/msg/laser_scan.hpp``."""
    return f'{package}/{namespace}/{rosidl_file_stem(name)}.hpp'


def join_args(items: Iterable[str]) -> str:
    """Comma-separated."""
    return ', '.join(items)
