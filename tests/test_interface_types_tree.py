"""The typed tree of installed and source types, read with rosidl's parsers (interface_types.tree)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl_schema.interface_types import InterfaceIndex
from nodl_schema.interface_types.tree import (ActionType, InterfaceFileError, MessageType, ServiceType,
                                              UnknownTypeError, load_type)

VENV = str(Path(sys.prefix))
SOURCE = FIXTURES / 'interface_types' / 'types_pkg'


@pytest.fixture(scope='module')
def index() -> InterfaceIndex:
    return InterfaceIndex([VENV], [str(SOURCE)])


def test_message_fields_bounds_comments_and_nesting(index: InterfaceIndex) -> None:
    scan = load_type(index, 'sensor_msgs/msg/LaserScan')
    assert isinstance(scan, MessageType)
    assert [f.name for f in scan.fields][:3] == ['header', 'angle_min', 'angle_max']
    ranges = scan.field('ranges')
    assert ranges is not None and ranges.type.idl == 'sequence<float>' and ranges.unit == 'm'
    assert 'start angle' in scan.fields[1].comment
    header = scan.field('header')
    assert header is not None and header.message is not None
    assert header.message.name == 'std_msgs/msg/Header'
    assert header.message.field('stamp').message.name == 'builtin_interfaces/msg/Time'  # type: ignore[union-attr]


def test_bounds_defaults_and_constants(index: InterfaceIndex) -> None:
    bounded = load_type(index, 'test_msgs/msg/BoundedSequences')
    assert isinstance(bounded, MessageType)
    field = bounded.field('string_values')
    assert field is not None and (field.type.container, field.type.size) == ('bounded_sequence', 3)
    strings = load_type(index, 'test_msgs/msg/Strings')
    assert isinstance(strings, MessageType)
    bounded_string = strings.field('bounded_string_value')
    assert bounded_string is not None and bounded_string.type.idl == 'string<22>'
    defaults = load_type(index, 'test_msgs/msg/Defaults')
    assert isinstance(defaults, MessageType)
    assert defaults.field('int32_value').default == -30000  # type: ignore[union-attr]
    constants = load_type(index, 'test_msgs/msg/Constants')
    assert isinstance(constants, MessageType)
    assert [(c.name, c.type.idl, c.value) for c in constants.constants][:2] == [
        ('BOOL_CONST', 'boolean', True), ('BYTE_CONST', 'octet', 50)]


def test_service_and_action_parts(index: InterfaceIndex) -> None:
    trigger = load_type(index, 'std_srvs/srv/Trigger')
    assert isinstance(trigger, ServiceType)
    assert trigger.request.name == 'std_srvs/srv/Trigger_Request'
    assert [f.name for f in trigger.response.fields] == ['success', 'message']
    fibonacci = load_type(index, 'test_msgs/action/Fibonacci')
    assert isinstance(fibonacci, ActionType)
    assert [f.name for f in fibonacci.goal.fields] == ['order']
    assert [f.name for f in fibonacci.feedback.fields] == ['sequence']
    assert load_type(index, 'test_msgs/action/Fibonacci_Result') is fibonacci.result


def test_source_msg_and_srv_are_read_through_rosidl_adapter(index: InterfaceIndex) -> None:
    status = load_type(index, 'types_pkg/msg/Status')
    assert isinstance(status, MessageType)
    assert [(f.name, f.type.idl) for f in status.fields] == [
        ('level', 'uint8'), ('message', 'string<32>'), ('header', 'std_msgs::msg::Header')]
    assert [c.name for c in status.constants] == ['OK', 'FAILED']
    assert status.field('message').comment == 'what happened'  # type: ignore[union-attr]
    reset = load_type(index, 'types_pkg/srv/Reset')
    assert isinstance(reset, ServiceType) and reset.response.fields[0].name == 'done'


def test_a_malformed_file_is_one_located_error(index: InterfaceIndex, capfd: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(InterfaceFileError) as raised:
        load_type(index, 'types_pkg/msg/Broken')
    assert raised.value.file == str(SOURCE / 'msg' / 'Broken.msg')
    assert raised.value.line == 3
    assert capfd.readouterr() == ('', '')  # the library prints nothing (rosidl_adapter would)


def test_a_malformed_installed_idl_is_located(tmp_path: Path) -> None:
    share = tmp_path / 'share'
    (share / 'ament_index' / 'resource_index' / 'rosidl_interfaces').mkdir(parents=True)
    (share / 'ament_index' / 'resource_index' / 'rosidl_interfaces' / 'bad_msgs').write_text(
        'msg/Bad.idl\n', encoding='utf-8')
    (share / 'bad_msgs' / 'msg').mkdir(parents=True)
    (share / 'bad_msgs' / 'msg' / 'Bad.idl').write_text(
        'module bad_msgs {\n  module msg {\n    struct Bad {\n      int32 x\n    };\n  };\n};\n',
        encoding='utf-8')
    index = InterfaceIndex([str(tmp_path)])
    with pytest.raises(InterfaceFileError) as raised:
        load_type(index, 'bad_msgs/msg/Bad')
    assert raised.value.line == 5 and raised.value.column > 0
    with pytest.raises(UnknownTypeError):
        load_type(index, 'bad_msgs/msg/Other')
