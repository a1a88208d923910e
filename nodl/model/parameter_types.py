"""Parameter types: the names a parameter definition may use, and what they mean.

The types are those of generate_parameter_library plus ``byte_array`` (a
ROS 2 parameter type): scalars, arrays, and fixed-size forms
``<base>_fixed_<N>`` where N is the maximum length.
"""

from __future__ import annotations

import re
from collections import namedtuple
from typing import TYPE_CHECKING

from nodl.vocabulary import ALL_TYPE_WORDS, ARRAY_TYPES, FIXED_BASES, SCALAR_TYPES

if TYPE_CHECKING:
    from typing import Any

__all__ = ['SCALAR_TYPES', 'ARRAY_TYPES', 'FIXED_BASES', 'ALL_TYPE_WORDS', 'TypeSpec',
           'parse_type', 'value_fits']

_FIXED = re.compile(f'({"|".join(FIXED_BASES)})_fixed_([1-9][0-9]*)')


class TypeSpec(namedtuple('TypeSpec', ['name', 'base', 'size'], defaults=[None])):
    """A parsed parameter type."""

    __slots__ = ()

    @property
    def is_array(self) -> bool:
        """True for every array type (including ``byte_array`` and fixed arrays)."""
        return bool(self.base.endswith('_array'))

    @property
    def element(self) -> str:
        """The scalar kind of the value or of each element: bool, int, double, string, byte, none."""
        if self.base == 'byte_array':
            return 'byte'
        return str(self.base[:-len('_array')] if self.is_array else self.base)

    @property
    def numeric(self) -> bool:
        """True if values (or elements) are numbers."""
        return self.element in ('int', 'double', 'byte')

    @property
    def category(self) -> str:
        """Words for messages: 'int', 'string', 'double array', ..."""
        return str(self.base).replace('_', ' ')


def parse_type(name: Any) -> TypeSpec | None:
    """Parse a type name; None if it is not a supported parameter type."""
    if not isinstance(name, str):
        return None
    if name in SCALAR_TYPES or name in ARRAY_TYPES:
        return TypeSpec(name, name)
    match = _FIXED.fullmatch(name)
    if match:
        return TypeSpec(name, match.group(1), int(match.group(2)))
    return None


def element_fits(value: Any, element: str) -> bool:
    """True if one scalar ``value`` has the kind ``element``."""
    if element == 'bool':
        return isinstance(value, bool)
    if element == 'int':
        return isinstance(value, int) and not isinstance(value, bool)
    if element == 'double':
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    if element == 'string':
        return isinstance(value, str)
    if element == 'byte':
        return isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= 255
    return False


def value_fits(value: Any, spec: TypeSpec) -> bool:
    """True if ``value`` is a valid value of ``spec`` (ignoring validators)."""
    if spec.is_array:
        if not isinstance(value, list):
            return False
        if spec.size is not None and len(value) > spec.size:
            return False
        return all(element_fits(v, spec.element) for v in value)
    if spec.size is not None and isinstance(value, str) and len(value) > spec.size:
        return False
    return element_fits(value, spec.element)
