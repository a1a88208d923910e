"""IDL -> C++ and Python types (interface_types.mapping), checked against the real generated code."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from nodl.interface_types import InterfaceIndex
from nodl.interface_types.mapping import PARAMETER_CPP, PARAMETER_PY, cpp_type, python_type, spec_note, spec_notes
from nodl.interface_types.tree import FieldType, MessageType, load_type

VENV = str(Path(sys.prefix))


@pytest.mark.parametrize('field_type, cpp, python', [
    (FieldType('octet'), 'unsigned char', 'bytes'),
    (FieldType('boolean'), 'bool', 'bool'),
    (FieldType('int32'), 'int32_t', 'int'),
    (FieldType('string', string_bound=5), 'std::string', 'str'),
    (FieldType('wstring'), 'std::u16string', 'str'),
    (FieldType('float', 'sequence'), 'std::vector<float>', "array.array('f')"),
    (FieldType('int32', 'bounded_sequence', 3), 'rosidl_runtime_cpp::BoundedVector<int32_t, 3>',
     "array.array('i')"),
    (FieldType('double', 'array', 9), 'std::array<double, 9>', 'numpy.ndarray[float64]'),
    (FieldType('octet', 'sequence'), 'std::vector<unsigned char>', 'list[bytes]'),
    (FieldType('std_msgs/msg/Header', 'sequence', nested=True), 'std::vector<std_msgs::msg::Header>',
     'list[Header]'),
])
def test_mapping(field_type: FieldType, cpp: str, python: str) -> None:
    assert cpp_type(field_type) == cpp
    assert python_type(field_type) == python


def test_python_mapping_matches_the_generated_classes() -> None:
    """Each field of test_msgs' Arrays and BoundedSequences, as rclpy's generated class holds it."""
    import array

    import numpy
    from test_msgs.msg import Arrays, BoundedSequences

    index = InterfaceIndex([VENV])
    for message, instance in (('test_msgs/msg/Arrays', Arrays()),
                              ('test_msgs/msg/BoundedSequences', BoundedSequences())):
        tree = load_type(index, message)
        assert isinstance(tree, MessageType)
        for field in tree.fields:
            value = getattr(instance, field.name)
            mapped = python_type(field.type)
            if mapped.startswith('numpy.ndarray'):
                assert isinstance(value, numpy.ndarray) and mapped == f'numpy.ndarray[{value.dtype}]', field
            elif mapped.startswith('array.array'):
                assert isinstance(value, array.array) and mapped == f"array.array('{value.typecode}')", field
            elif field.type.container is None:
                assert type(value).__name__ == mapped, field
            else:
                assert isinstance(value, list), field
                for item in value:
                    assert type(item).__name__ == mapped[5:-1], field


def test_notes_where_spec_003_differs() -> None:
    assert 'std::byte' in spec_notes()['octet'] and 'unsigned char' in spec_notes()['octet']
    assert "array.array('l')" in spec_notes()['sequence<int32>']
    assert 'BoundedVector' in (spec_note(FieldType('float', 'bounded_sequence', 2)) or '')
    assert spec_note(FieldType('float')) is None


def test_parameter_types_as_rclcpp_and_rclpy_map_them() -> None:
    from rclpy.parameter import Parameter

    assert PARAMETER_CPP['int'] == 'int64_t' and PARAMETER_CPP['byte_array'] == 'std::vector<uint8_t>'
    values = {'bool': True, 'int': 1, 'double': 1.5, 'string': 's', 'bool_array': [True],
              'int_array': [1], 'double_array': [1.5], 'string_array': ['s'], 'byte_array': [b'a']}
    for name, value in values.items():
        parameter = Parameter('p', value=value)
        assert parameter.type_.name.lower().replace('integer', 'int') == name
        got = parameter.value
        if isinstance(got, list):
            assert f'list[{type(got[0]).__name__}]' == PARAMETER_PY[name]
        else:
            assert type(got).__name__ == PARAMETER_PY[name]
