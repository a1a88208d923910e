"""IDL types as C++ and Python types, as the installed rosidl generators write them.

The basic C++ types come from rosidl_generator_cpp's own table and the
Python element types and array kinds from rosidl_generator_py's, so the
mapping follows the installed generators.  Containers are shown with the
default allocator (``std::vector<float>``, not the allocator template the
headers spell out).  Where spec 003's tables say otherwise, :func:`spec_note`
says how (for example ``octet``: ``unsigned char`` in
rosidl_generator_cpp 4.9.5, ``std::byte`` in the spec).

Parameter types are mapped as rclcpp (``rclcpp::Parameter::as_*``) and rclpy
(``Parameter.value``) give them: :data:`PARAMETER_CPP`, :data:`PARAMETER_PY`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nodl.interface_types.tree import FieldType

if TYPE_CHECKING:
    from nodl.interface_types.tree import FieldType

__all__ = ['cpp_type', 'python_type', 'spec_note', 'spec_notes', 'PARAMETER_CPP', 'PARAMETER_PY']

#: What spec 003 writes for a C++ basic type where the installed generator writes another.
_SPEC_CPP = {'octet': 'std::byte'}
#: Spec 003's array typecodes for Python sequences of numbers (``array.array(typecode)``).
_SPEC_TYPECODES = {'float': 'f', 'double': 'd', 'int8': 'b', 'uint8': 'B', 'int16': 'h',
                   'uint16': 'H', 'int32': 'l', 'uint32': 'L', 'int64': 'q', 'uint64': 'Q'}

#: Parameter type -> the C++ type rclcpp gives (``as_bool()``, ``as_integer_array()``...).
PARAMETER_CPP: dict[str, str] = {
    'bool': 'bool', 'int': 'int64_t', 'double': 'double', 'string': 'std::string',
    'byte_array': 'std::vector<uint8_t>', 'bool_array': 'std::vector<bool>',
    'int_array': 'std::vector<int64_t>', 'double_array': 'std::vector<double>',
    'string_array': 'std::vector<std::string>',
}
#: Parameter type -> the Python type of rclpy's ``Parameter.value`` for it.
PARAMETER_PY: dict[str, str] = {
    'bool': 'bool', 'int': 'int', 'double': 'float', 'string': 'str',
    'byte_array': 'list[bytes]', 'bool_array': 'list[bool]', 'int_array': 'list[int]',
    'double_array': 'list[float]', 'string_array': 'list[str]',
}


def _cpp_table() -> dict[str, str]:
    from rosidl_generator_cpp import MSG_TYPE_TO_CPP

    table = dict(MSG_TYPE_TO_CPP)
    # The headers' allocator-aware spellings, with the default allocator: the typedefs users write.
    table['string'], table['wstring'] = 'std::string', 'std::u16string'
    return table


def cpp_type(field_type: FieldType) -> str:
    """The C++ type rosidl_generator_cpp gives a field: ``float``, ``std::vector<float>``,
    ``std::array<double, 9>``, ``rosidl_runtime_cpp::BoundedVector<int32_t, 5>``,
    ``std_msgs::msg::Header``."""
    element = field_type.base.replace('/', '::') if field_type.nested else _cpp_table()[field_type.base]
    if field_type.container == 'array':
        return f'std::array<{element}, {field_type.size}>'
    if field_type.container == 'sequence':
        return f'std::vector<{element}>'
    if field_type.container == 'bounded_sequence':
        return f'rosidl_runtime_cpp::BoundedVector<{element}, {field_type.size}>'
    return element


def _python_element(field_type: FieldType) -> str:
    from rosidl_generator_py.generate_py_impl import get_python_type
    from rosidl_parser import definition as d

    if field_type.nested:
        return field_type.base.rsplit('/', 1)[1]
    if field_type.base in ('string', 'wstring'):
        return 'str'
    return str(get_python_type(d.BasicType(field_type.base)))  # type: ignore[arg-type]


def python_type(field_type: FieldType) -> str:
    """The Python type rosidl_generator_py gives a field: ``float``, ``numpy.ndarray[float64]``
    (fixed arrays of numbers), ``array.array('f')`` (sequences of numbers), ``list[bytes]``
    (octets), ``list[Header]``."""
    element = _python_element(field_type)
    if field_type.container is None:
        return element
    from rosidl_generator_py.generate_py_impl import SPECIAL_NESTED_BASIC_TYPES

    special = None if field_type.nested else SPECIAL_NESTED_BASIC_TYPES.get(field_type.base)
    if special is not None:
        if field_type.container == 'array':
            return f"numpy.ndarray[{special['dtype'].split('.')[-1]}]"
        return f"array.array('{special['type_code']}')"
    return f'list[{element}]'


def spec_note(field_type: FieldType) -> str | None:
    """How spec 003 maps this type differently from the installed generators, or None."""
    notes = []
    if field_type.base in _SPEC_CPP and not field_type.nested:
        notes.append(f"C++: spec 003 says {_SPEC_CPP[field_type.base]}, the installed "
                     f"rosidl_generator_cpp writes {_cpp_table()[field_type.base]}")
    if field_type.container == 'bounded_sequence':
        notes.append('C++: spec 003 says std::vector<T>, rosidl_generator_cpp writes '
                     'rosidl_runtime_cpp::BoundedVector<T, N>')
    if field_type.container is not None and field_type.base == 'octet':
        notes.append(f"Python: spec 003 says bytes, rosidl_generator_py gives {python_type(field_type)} "
                     '(one bytes of length 1 per element)')
    if field_type.container in ('sequence', 'bounded_sequence') and field_type.base in _SPEC_TYPECODES:
        actual = python_type(field_type)
        spec = f"array.array('{_SPEC_TYPECODES[field_type.base]}')"
        if actual != spec:
            notes.append(f'Python: spec 003 says {spec}, rosidl_generator_py gives {actual}')
    return '; '.join(notes) or None


def spec_notes() -> dict[str, str]:
    """IDL type -> where spec 003 and the installed generators disagree, for the types the
    rules of :func:`spec_note` concern (``octet``, sequences of ``int32``/``uint32``...)."""
    out: dict[str, str] = {}
    for base in ('octet', 'int32', 'uint32'):
        for container, size in ((None, None), ('sequence', None), ('bounded_sequence', 3)):
            ftype = FieldType(base, container, size)
            note = spec_note(ftype)
            if note:
                out[ftype.idl] = note
    return out
