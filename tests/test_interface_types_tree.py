"""The typed tree of installed and source types, read with rosidl's parsers (interface_types.tree)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl.interface_types import InterfaceIndex
from nodl.interface_types.tree import (
    ActionType,
    InterfaceFileError,
    MessageType,
    ServiceType,
    UnknownTypeError,
    load_type,
)

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


def _shape(loaded: object, seen: set[str] | None = None) -> object:
    """Everything a tree says, nested types included (each once), for comparing two readings."""
    seen = set() if seen is None else seen
    if isinstance(loaded, ServiceType):
        return (loaded.name, loaded.file, _shape(loaded.request, seen), _shape(loaded.response, seen))
    if isinstance(loaded, ActionType):
        return (loaded.name, loaded.file, _shape(loaded.goal, seen), _shape(loaded.result, seen),
                _shape(loaded.feedback, seen))
    assert isinstance(loaded, MessageType)
    if loaded.name in seen:
        return loaded.name
    seen.add(loaded.name)
    return (loaded.name, loaded.file,
            [(f.name, f.type.idl, f.type.nested, f.type.container, f.type.size, f.type.string_bound,
              f.default, type(f.default), f.comment, f.unit,
              _shape(f.message, seen) if f.message is not None else None) for f in loaded.fields],
            [(c.name, c.type.idl, c.value, type(c.value), c.comment) for c in loaded.constants])


_READ_BOTH_WAYS = ['test_msgs/msg/Arrays', 'test_msgs/msg/BoundedSequences', 'test_msgs/msg/Strings',
                   'test_msgs/msg/Defaults', 'test_msgs/msg/Constants', 'test_msgs/msg/MultiNested',
                   'test_msgs/msg/WStrings', 'sensor_msgs/msg/LaserScan', 'std_msgs/msg/Empty',
                   'std_srvs/srv/Trigger_Event', 'test_msgs/action/Fibonacci_FeedbackMessage',
                   'test_msgs/action/Fibonacci_Goal']


@pytest.mark.parametrize('name', _READ_BOTH_WAYS)
def test_an_installed_plain_file_reads_as_its_generated_idl(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """An installed .msg/.srv/.action is read by rosidl_adapter alone; the tree is the one its
    generated .idl gives (fields, bounds, defaults and their Python types, constants, comments,
    units, the empty message's placeholder member, the service event and action feedback
    messages rosidl adds)."""
    from nodl.interface_types import tree

    fast = load_type(InterfaceIndex([VENV]), name)
    monkeypatch.setattr(tree, '_plain_spec', lambda *args: None)  # every type through its .idl
    assert _shape(fast) == _shape(load_type(InterfaceIndex([VENV]), name))


def test_installed_plain_files_are_not_parsed_as_idl(monkeypatch: pytest.MonkeyPatch) -> None:
    """The fast path: rosidl_parser's IDL grammar is never run for an installed .msg/.srv/
    .action, and each file is read once per index however many types and pages use it."""
    import rosidl_parser.parser

    from nodl.interface_types import tree

    def refuse(*args: object) -> None:
        raise AssertionError('parsed as IDL')

    monkeypatch.setattr(rosidl_parser.parser, 'parse_idl_string', refuse)
    reads: list[str] = []
    real = tree.read_spec
    monkeypatch.setattr(tree, 'read_spec', lambda path, *rest: reads.append(path) or real(path, *rest))
    index = InterfaceIndex([VENV])
    for name in ('sensor_msgs/msg/LaserScan', 'std_msgs/msg/Header', 'std_srvs/srv/Trigger',
                 'std_srvs/srv/Trigger_Request', 'test_msgs/action/Fibonacci', 'sensor_msgs/msg/LaserScan'):
        load_type(index, name)
    assert len(reads) == len(set(reads))
    assert {Path(p).name for p in reads} == {'LaserScan.msg', 'Header.msg', 'Time.msg', 'Trigger.srv',
                                             'Fibonacci.action'}


def test_a_service_part_keeps_its_comment(index: InterfaceIndex) -> None:
    cancel = load_type(index, 'action_msgs/srv/CancelGoal')
    assert isinstance(cancel, ServiceType)
    assert cancel.request.comment.startswith('Cancel one or more goals')
    assert cancel.response.comment == 'Return codes.'
    assert [f.name for f in load_type(index, 'std_srvs/srv/Trigger').request.fields] == [  # type: ignore[union-attr]
        'structure_needs_at_least_one_member']  # as in every generated message


def test_a_malformed_installed_msg_is_located(tmp_path: Path) -> None:
    share = tmp_path / 'share'
    (share / 'ament_index' / 'resource_index' / 'rosidl_interfaces').mkdir(parents=True)
    (share / 'ament_index' / 'resource_index' / 'rosidl_interfaces' / 'bad_msgs').write_text(
        'msg/Bad.idl\nmsg/Bad.msg\n', encoding='utf-8')
    (share / 'bad_msgs' / 'msg').mkdir(parents=True)
    (share / 'bad_msgs' / 'msg' / 'Bad.idl').write_text('module bad_msgs {};\n', encoding='utf-8')
    (share / 'bad_msgs' / 'msg' / 'Bad.msg').write_text('int32 x\nint32 y z\n', encoding='utf-8')
    index = InterfaceIndex([str(tmp_path)])
    for _ in range(2):  # the error is kept: the same one the second time
        with pytest.raises(InterfaceFileError) as raised:
            load_type(index, 'bad_msgs/msg/Bad')
        assert (Path(raised.value.file).name, raised.value.line, raised.value.column) == ('Bad.msg', 2, 1)
