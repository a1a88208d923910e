"""Converting legacy NoDL XML to NoDL v2 node definitions."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

import nodl
from conftest import FIXTURES, REPO
from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.legacy_xml import parse_legacy_xml
from nodl.legacy import Converted, convert_file, convert_files, convert_legacy, render_converted, seconds_to_ns
from nodl.reporting import format_text
from nodl.writing import WriteError, marker_state, unmark

LEGACY = FIXTURES / 'legacy'
EXPECTED = LEGACY / 'expected'
SHARED = ['boolean_attributes', 'qos_child', 'role_attributes']


def rel(path: Path) -> str:
    return os.path.relpath(path, REPO)


def convert(name: str) -> list[Converted]:
    doc = parse_legacy_xml(LEGACY / name)
    assert doc.ok, format_text(doc.diagnostics)
    return convert_legacy(doc)


def only(name: str) -> Converted:
    converted = convert(name)
    assert len(converted) == 1
    return converted[0]


def main(converted: Converted) -> dict[str, Any]:
    return converted.data['main']


def warnings(diagnostics: list[Diagnostic]) -> list[str]:
    return [d.message for d in diagnostics if d.severity is Severity.WARNING]


# --------------------------------------------------------------------------
# Golden files for the shared fixtures


@pytest.mark.parametrize('fixture', SHARED)
def test_shared_fixture_converts_to_the_expected_files(fixture: str, golden, tmp_path: Path,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(REPO)  # file names in the output are relative, as a user would type them
    written, diagnostics = convert_file(rel(LEGACY / f'{fixture}.nodl.xml'), tmp_path)
    assert [p.name for p in written] == ['first.nodl.yaml', 'second.nodl.yaml']
    for path in written:
        golden.check(path.read_text(encoding='utf-8'), EXPECTED / fixture / path.name)
    golden.check(format_text(diagnostics), EXPECTED / fixture / 'diagnostics.txt')
    expected = sorted(p.name for p in (EXPECTED / fixture).glob('*.nodl.yaml'))
    assert sorted(p.name for p in written) == expected


@pytest.mark.parametrize('fixture', SHARED)
def test_expected_files_are_valid_node_definitions(fixture: str) -> None:
    for path in sorted((EXPECTED / fixture).glob('*.nodl.yaml')):
        node = nodl.load_node(path)
        assert node.base == nodl.Base.NODE


@pytest.mark.parametrize('fixture', SHARED + ['role_both', 'qos_full', 'warnings'])
def test_converted_output_validates_with_load_node(fixture: str, tmp_path: Path) -> None:
    written, diagnostics = convert_file(LEGACY / f'{fixture}.nodl.xml', tmp_path)
    assert written
    assert not [d for d in diagnostics if d.severity is Severity.ERROR]
    for path in written:
        text = path.read_text(encoding='utf-8')
        assert marker_state(text) == 'valid'  # the marker first, then the header
        assert unmark(text).startswith(f'# Converted from {LEGACY / fixture}.nodl.xml by `nodl convert`\n')
        node = nodl.load_node(path)
        assert node.nodl_version == 2 and node.main.nodl_version == 2


def test_every_converted_dict_passes_validate_node() -> None:
    for name in ('boolean_attributes.nodl.xml', 'qos_child.nodl.xml', 'role_attributes.nodl.xml',
                 'role_both.nodl.xml', 'qos_full.nodl.xml', 'warnings.nodl.xml'):
        for converted in convert(name):
            assert converted.ok, format_text(converted.diagnostics)
            nodl.validate_node(converted.data)  # raises if invalid


# --------------------------------------------------------------------------
# Roles


def test_shape_of_a_converted_node() -> None:
    first = convert('boolean_attributes.nodl.xml')[0]
    assert first.file_name == 'first.nodl.yaml'
    assert first.data == {
        'nodl_version': 2,
        'base': 'node',
        'main': {
            'nodl_version': 2,
            'parameters': {'verbose': {'type': 'bool'}},
            'publishers': [{'name': 'chatter', 'type': 'std_msgs/msg/String',
                            'qos': {'history': 'SYSTEM_DEFAULT', 'reliability': 'SYSTEM_DEFAULT'}}],
        },
    }


def test_both_lands_in_both_sections() -> None:
    converted = only('role_both.nodl.xml')
    sections = main(converted)
    names = {section: [e['name'] for e in sections[section]]
             for section in ('publishers', 'subscriptions', 'service_servers', 'service_clients',
                             'action_servers', 'action_clients')}
    assert names == {
        'publishers': ['chatter', 'echo'],
        'subscriptions': ['chatter', 'echo'],
        'service_servers': ['reset', 'trigger'],
        'service_clients': ['reset', 'trigger'],
        'action_servers': ['fibonacci'],
        'action_clients': ['fibonacci'],
    }
    # the same QoS on both sides
    assert sections['publishers'][0]['qos'] == sections['subscriptions'][0]['qos'] == {
        'history': 'KEEP_LAST', 'reliability': 'BEST_EFFORT', 'depth': 5,
        'durability': 'TRANSIENT_LOCAL'}


def test_role_attribute_both_for_an_action_in_the_shared_fixture() -> None:
    second = convert('role_attributes.nodl.xml')[1]
    assert [a['name'] for a in main(second)['action_servers']] == ['/example_action']
    assert [a['name'] for a in main(second)['action_clients']] == ['/example_action']


def test_an_endpoint_with_both_roles_is_reported_once() -> None:
    doc = parse_legacy_xml('<interface version="1"><node executable="x">\n'
                           '<topic name="t" type="p/T" role="both"><qos depth="1"/></topic>\n'
                           '</node></interface>')
    converted = convert_legacy(doc)[0]
    assert len(warnings(converted.diagnostics)) == 2  # short type; reliability unset
    assert [e['type'] for e in main(converted)['publishers'] + main(converted)['subscriptions']] \
        == ['p/msg/T', 'p/msg/T']


# --------------------------------------------------------------------------
# QoS


def test_qos_carries_over() -> None:
    converted = only('qos_full.nodl.xml')
    sections = main(converted)
    scan, status, plain = sections['publishers']
    assert scan['qos'] == {
        'history': 'KEEP_LAST', 'reliability': 'BEST_EFFORT', 'depth': 5, 'durability': 'VOLATILE',
        'deadline_ns': 100_000_000, 'lifespan_ns': 2_000_000_000, 'liveliness': 'AUTOMATIC',
        'liveliness_lease_duration_ns': 1_500_000_000}
    assert sections['subscriptions'][0]['qos'] == {
        'history': 'KEEP_ALL', 'reliability': 'RELIABLE', 'durability': 'TRANSIENT_LOCAL',
        'deadline_ns': 1, 'liveliness': 'MANUAL_BY_TOPIC'}
    assert status['qos'] == {'history': 'SYSTEM_DEFAULT', 'reliability': 'SYSTEM_DEFAULT',
                             'durability': 'SYSTEM_DEFAULT'}
    assert plain['qos'] == {'history': 'SYSTEM_DEFAULT', 'reliability': 'RELIABLE'}
    assert sections['service_servers'][0]['qos'] == {
        'history': 'KEEP_LAST', 'reliability': 'RELIABLE', 'depth': 1}


def test_shared_qos_fixture() -> None:
    first, second = convert('qos_child.nodl.xml')
    assert main(first)['publishers'][0]['qos'] == {
        'history': 'KEEP_LAST', 'reliability': 'SYSTEM_DEFAULT', 'depth': 10}
    assert main(second)['subscriptions'][0]['qos'] == {
        'history': 'KEEP_LAST', 'reliability': 'SYSTEM_DEFAULT', 'depth': 10,
        'deadline_ns': 500_000_000, 'lifespan_ns': 500_000_000,
        'liveliness_lease_duration_ns': 500_000_000}
    assert main(second)['service_clients'][0]['qos'] == {
        'history': 'KEEP_LAST', 'reliability': 'SYSTEM_DEFAULT', 'depth': 10}
    assert main(second)['action_clients'][0] == {
        'name': '/example_action', 'type': 'example_interfaces/action/Fibonacci'}


def test_topic_without_qos_gets_system_default_and_a_warning() -> None:
    first = convert('role_attributes.nodl.xml')[0]
    assert main(first)['publishers'][0]['qos'] == {
        'history': 'SYSTEM_DEFAULT', 'reliability': 'SYSTEM_DEFAULT'}
    assert [(d.line, d.column) for d in first.diagnostics
            if 'has no <qos>' in d.message] == [(4, 5)]


def test_service_without_qos_has_none() -> None:
    second = convert('boolean_attributes.nodl.xml')[1]
    assert 'qos' not in main(second)['service_clients'][0]


@pytest.mark.parametrize('text, ns', [('.5', 500_000_000), ('2', 2_000_000_000), ('1.', 1_000_000_000),
                                      ('0.000000001', 1), ('0.0000000019', 1), (' 3.25 ', 3_250_000_000),
                                      ('0', 0)])
def test_seconds_to_ns(text: str, ns: int) -> None:
    assert seconds_to_ns(text) == ns


@pytest.mark.parametrize('text', ['', '.', '-1', '1e3', 'abc', '1.2.3', '\u0661'])
def test_seconds_to_ns_rejects_what_is_not_seconds(text: str) -> None:
    with pytest.raises(ValueError):
        seconds_to_ns(text)


def test_duration_beyond_int64_nanoseconds_is_an_error() -> None:
    doc = parse_legacy_xml('<interface version="1"><node executable="x">'
                           '<topic name="t" type="p/msg/T" publisher="true">'
                           '<qos history="keep_all" reliability="reliable" lifespan="99999999999"/>'
                           '</topic></node></interface>')
    converted = convert_legacy(doc)[0]
    assert not converted.ok
    assert 'too large' in converted.errors[0].message


# --------------------------------------------------------------------------
# Warnings for what has no v2 meaning


def test_node_name_is_a_warning_at_the_name_attribute() -> None:
    first = convert('boolean_attributes.nodl.xml')[0]
    name_warnings = [d for d in first.diagnostics if "node name 'node_1'" in d.message]
    assert [(d.line, d.column, d.severity) for d in name_warnings] == [(2, 9, Severity.WARNING)]


def test_qos_values_without_v2_meaning_are_warnings() -> None:
    messages = warnings(only('qos_full.nodl.xml').diagnostics)
    assert any("liveliness 'manual_by_node'" in m and 'dropped' in m for m in messages)
    assert sum('avoid_ros_namespace_conventions' in m for m in messages) == 1  # only the "true" one
    assert any('finer than a nanosecond' in m for m in messages)
    assert any('sets neither history nor depth' in m for m in messages)


def test_qos_on_an_action_is_dropped_with_a_warning() -> None:
    second = convert('qos_child.nodl.xml')[1]
    action = [d for d in second.diagnostics if '<qos> of action' in d.message]
    assert [(d.line, d.column, d.severity) for d in action] == [(27, 7, Severity.WARNING)]


def test_unset_reliability_is_a_warning_at_the_attribute_or_element() -> None:
    second = convert('qos_child.nodl.xml')[1]
    positions = [(d.line, d.column) for d in second.diagnostics
                 if 'does not set reliability' in d.message]
    assert positions == [(14, 9), (24, 7)]  # reliability="" on line 14; no attribute on line 24


def test_parameter_types() -> None:
    converted = only('warnings.nodl.xml')
    assert main(converted)['parameters'] == {
        'ints': {'type': 'int_array'},
        'count': {'type': 'int'},
        'blob': {'type': 'byte_array'},
        'gains': {'type': 'double_array'},
        'names': {'type': 'string_array'},
        'flags': {'type': 'bool_array'},
        'label': {'type': 'string'},
        'anything': {'type': 'none'},
        'ratio': {'type': 'none'},
        'frame': {'type': 'string_fixed_16'},
    }
    unknown = [d for d in converted.diagnostics if "type 'float'" in d.message]
    assert [(d.line, d.column, d.severity) for d in unknown] == [(12, 29, Severity.WARNING)]
    assert "written as 'none'" in unknown[0].message


def test_short_interface_types_get_their_namespace_with_a_warning() -> None:
    converted = only('warnings.nodl.xml')
    assert main(converted)['publishers'][0]['type'] == 'std_msgs/msg/String'
    assert main(converted)['service_servers'][0]['type'] == 'example_interfaces/srv/AddTwoInts'
    assert main(converted)['action_clients'][0]['type'] == 'example_interfaces/action/Fibonacci'
    assert sum('omits the interface namespace' in m for m in warnings(converted.diagnostics)) == 3


def test_a_node_without_executable_is_named_after_its_name() -> None:
    converted = only('warnings.nodl.xml')
    assert converted.file_name == 'talker.nodl.yaml'
    assert any("node name 'talker' is not carried over (it only names the converted file)" in m
               for m in warnings(converted.diagnostics))


def test_missing_descriptions_are_not_reported_by_the_converter() -> None:
    for converted in convert('qos_child.nodl.xml'):
        assert not any('description' in d.message for d in converted.diagnostics)


# --------------------------------------------------------------------------
# Errors


def test_v2_errors_are_placed_at_the_legacy_element() -> None:
    doc = parse_legacy_xml(LEGACY / 'invalid_v2.nodl.xml')
    converted = convert_legacy(doc)[0]
    errors = [(d.line, d.column, d.message) for d in converted.errors]
    assert [e[:2] for e in errors] == [(3, 12), (4, 12), (6, 22), (7, 12), (10, 12)]
    assert "invalid ROS name 'bad name'" in errors[0][2]
    assert 'history keep_last but no depth' in errors[1][2]
    assert "'std_srvs/srv/Empty' is a service type" in errors[2][2]
    assert 'depth 0 with history keep_last' in errors[3][2]
    assert "duplicate publisher 'twice'" in errors[4][2]
    assert all(e[2].startswith('not valid in NoDL v2: ') for e in errors if e[:2] != (4, 12)
               and e[:2] != (7, 12))


def test_errors_write_nothing(tmp_path: Path) -> None:
    for name in ('invalid_v2.nodl.xml', 'errors/structural.nodl.xml', 'errors/malformed.nodl.xml',
                 'errors/billion_laughs.nodl.xml', 'errors/latin1.nodl.xml',
                 'several_nodes_one_executable.nodl.xml'):
        written, diagnostics = convert_file(LEGACY / name, tmp_path / 'out')
        assert written == [], name
        assert any(d.severity is Severity.ERROR for d in diagnostics), name
    assert not (tmp_path / 'out').exists()


def test_malformed_xml_is_not_half_converted(tmp_path: Path) -> None:
    _, diagnostics = convert_file(LEGACY / 'errors' / 'malformed.nodl.xml', tmp_path)
    assert [d.message for d in diagnostics] == ['malformed XML: mismatched tag']


def test_several_nodes_in_one_executable_and_unsafe_names() -> None:
    doc = parse_legacy_xml(LEGACY / 'several_nodes_one_executable.nodl.xml')
    camera, rectifier, evil = convert_legacy(doc)
    assert (camera.file_name, rectifier.file_name) == ('container.camera.nodl.yaml',
                                                       'container.rectifier.nodl.yaml')
    assert camera.ok and rectifier.ok
    assert any('holds several nodes' in m for m in warnings(camera.diagnostics))
    assert [(d.line, d.column) for d in evil.errors] == [(8, 9)]
    assert "name '../evil' cannot be used as a file name" in evil.errors[0].message


def test_missing_file_raises_os_error(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        convert_file(LEGACY / 'nope.nodl.xml', tmp_path)


# --------------------------------------------------------------------------
# package.xml and several inputs


def test_package_xml_converts_every_exported_file(tmp_path: Path) -> None:
    written, diagnostics = convert_file(LEGACY / 'package' / 'package.xml', tmp_path)
    assert [p.name for p in written] == ['talker.nodl.yaml', 'listener.nodl.yaml']
    assert not [d for d in diagnostics if d.severity is Severity.ERROR]
    assert {d.file for d in diagnostics} == {
        str(LEGACY / 'package' / 'interfaces' / 'talker.nodl.xml'),
        str(LEGACY / 'package' / 'interfaces' / 'listener.nodl.xml')}
    talker = nodl.load_node(tmp_path / 'talker.nodl.yaml')
    assert talker.main.publishers[0].qos.depth == 10  # type: ignore[index]
    header = unmark((tmp_path / 'listener.nodl.yaml').read_text(encoding='utf-8')).splitlines()[0]
    assert header == (f'# Converted from {LEGACY / "package" / "interfaces" / "listener.nodl.xml"}'
                      ' by `nodl convert`')


def test_package_xml_with_a_missing_exported_file(tmp_path: Path) -> None:
    written, diagnostics = convert_file(LEGACY / 'package_bad_export' / 'package.xml', tmp_path)
    assert written == []
    missing = [d for d in diagnostics if 'cannot read exported interface file' in d.message]
    assert [(d.line, d.column) for d in missing] == [(9, 16)]
    assert missing[0].file == str(LEGACY / 'package_bad_export' / 'package.xml')


def test_package_xml_without_export(tmp_path: Path) -> None:
    written, diagnostics = convert_file(LEGACY / 'package_no_export' / 'package.xml', tmp_path)
    assert written == []
    assert 'exports no interface file' in diagnostics[0].message


def test_convert_files_refuses_to_overwrite_what_it_wrote_in_the_same_run(tmp_path: Path) -> None:
    results = convert_files([LEGACY / 'qos_child.nodl.xml', LEGACY / 'role_attributes.nodl.xml',
                             LEGACY / 'nope.nodl.xml'], tmp_path)
    first, second, missing = results
    assert [os.path.basename(p) for p in first.written] == ['first.nodl.yaml', 'second.nodl.yaml']
    assert second.written == []
    assert [(d.line, d.column) for d in second.errors] == [(2, 3), (7, 3)]
    assert 'would be written twice' in second.errors[0].message
    assert not missing.readable and missing.problem == 'no such file or directory'
    # the first conversion is what is on disk
    assert 'qos_child.nodl.xml' in (tmp_path / 'first.nodl.yaml').read_text(encoding='utf-8')


def test_unwritable_output_is_a_problem_not_an_exception(tmp_path: Path) -> None:
    blocker = tmp_path / 'file'
    blocker.write_text('not a directory')
    [result] = convert_files([LEGACY / 'role_both.nodl.xml'], blocker)
    assert not result.readable
    assert result.problem == ''  # the reason is the last diagnostic, coded, at the output
    last = result.diagnostics[-1]
    assert last.code == 'NODL030' and last.file.startswith(str(blocker) + os.sep)
    assert blocker.read_text() == 'not a directory'


def test_render_converted_has_a_header() -> None:
    converted = convert('role_attributes.nodl.xml')[1]
    text = render_converted(converted)
    assert text.splitlines()[:2] == [
        f'# Converted from {LEGACY / "role_attributes.nodl.xml"} by `nodl convert`',
        "# (legacy NoDL XML: node 'node_2', executable 'second', line 7)."]
    assert nodl.load_node(text).main.action_servers[0].name == '/example_action'  # type: ignore[index]
    # Legacy files have no descriptions: the header silences that warning, even with strict,
    # but not the warnings that remain (a file without the directive has them).
    assert text.splitlines()[2].startswith('# nodl: ignore=NODL216 ')
    assert nodl.check_source(text).diagnostics == []
    assert any(d.code == 'NODL216' for d in nodl.check_source(
        text.replace('# nodl: ignore=NODL216', '# no directive')).diagnostics)


def test_an_output_that_cannot_be_replaced_names_it_and_writes_none(tmp_path: Path) -> None:
    (tmp_path / 'second.nodl.yaml').mkdir()  # the second node's output cannot be written
    [result] = convert_files([LEGACY / 'role_attributes.nodl.xml'], tmp_path)
    assert result.problem == ''
    assert (result.diagnostics[-1].code, result.diagnostics[-1].file) == (
        'NODL034', str(tmp_path / 'second.nodl.yaml'))
    assert result.written == [] and not (tmp_path / 'first.nodl.yaml').exists()  # checked first


def test_converted_files_are_marked_and_a_users_file_is_kept(tmp_path: Path) -> None:
    [result] = convert_files([LEGACY / 'role_attributes.nodl.xml'], tmp_path)
    first = tmp_path / 'first.nodl.yaml'
    assert marker_state(first.read_text(encoding='utf-8')) == 'valid'
    [again] = convert_files([LEGACY / 'role_attributes.nodl.xml'], tmp_path)  # nodl's: replaced
    assert again.readable and again.written == result.written
    first.write_text(first.read_text(encoding='utf-8') + '# my note\n', encoding='utf-8')
    [edited] = convert_files([LEGACY / 'role_attributes.nodl.xml'], tmp_path)
    assert edited.diagnostics[-1].code == 'NODL032' and edited.written == []
    assert first.read_text(encoding='utf-8').endswith('# my note\n')
    [forced] = convert_files([LEGACY / 'role_attributes.nodl.xml'], tmp_path, force=True)
    assert forced.readable and marker_state(first.read_text(encoding='utf-8')) == 'valid'
    assert convert_files([LEGACY / 'role_attributes.nodl.xml'], tmp_path,
                         inputs=[str(first)])[0].diagnostics[-1].code == 'NODL033'


def test_convert_file_raises_the_documented_write_error_when_it_cannot_write(tmp_path: Path) -> None:
    blocker = tmp_path / 'a_file'
    blocker.write_text('not a directory', encoding='utf-8')
    with pytest.raises(WriteError) as info:  # not a private exception type
        convert_file(LEGACY / 'role_attributes.nodl.xml', blocker / 'out')
    assert info.value.diagnostic.code == 'NODL030'
    assert info.value.diagnostic.file == str(blocker / 'out' / 'first.nodl.yaml')


def test_a_valid_conversion_is_written_from_the_typed_model() -> None:
    from nodl.frontends.legacy_xml import parse_legacy_xml
    from nodl.legacy.convert import convert_legacy
    from nodl.model import Node

    checked = 0
    for path in sorted((FIXTURES / 'legacy').rglob('*.xml')):
        for converted in convert_legacy(parse_legacy_xml(path.read_bytes(), str(path))):
            document = converted.document
            if not converted.ok:
                assert document is None
                continue
            assert isinstance(document, Node)
            assert document.to_dict() == converted.data  # the same document, typed
            checked += 1
    assert checked >= 5
