"""The legacy XML frontend: nodes, roles, QoS, positions, structural errors, package.xml exports.

The XML reader under it (positions, attribute placement, hostile input) is tested in
test_frontends_xml_reader.py.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import FIXTURES, REPO
from nodl.diagnostics import Severity
from nodl.frontends.legacy_xml import (
    LegacyDocument,
    LegacyEndpoint,
    LegacyQoS,
    interface_files_from_package_xml,
    package_exports,
    parse_legacy_xml,
)
from nodl.reporting import format_text

LEGACY = FIXTURES / 'legacy'
ERRORS = LEGACY / 'errors'


def rel(path: Path) -> str:
    return os.path.relpath(path, REPO)


def parse(name: str) -> LegacyDocument:
    return parse_legacy_xml(LEGACY / name)


# --------------------------------------------------------------------------
# The shared fixtures


@pytest.mark.parametrize('name', ['boolean_attributes.nodl.xml', 'qos_child.nodl.xml',
                                  'role_attributes.nodl.xml'])
def test_shared_fixtures_parse_without_diagnostics(name: str) -> None:
    doc = parse(name)
    assert doc.diagnostics == []
    assert doc.ok
    assert doc.version == '1'
    assert [(n.name, n.executable) for n in doc.nodes] == [('node_1', 'first'), ('node_2', 'second')]


def test_boolean_attributes_spec_001() -> None:
    doc = parse('boolean_attributes.nodl.xml')
    first, second = doc.nodes
    assert [(p.name, p.type) for p in first.parameters] == [('verbose', 'bool')]
    assert [(t.name, t.type, t.roles) for t in first.topics] == [
        ('chatter', 'std_msgs/msg/String', ('publisher',))]
    assert [(t.name, t.roles) for t in second.topics] == [('/foo/bar', ('subscription',))]
    assert [(s.name, s.type, s.roles) for s in second.services] == [
        ('/example_service', 'std_srvs/srv/Empty', ('client',))]
    assert [(a.name, a.type, a.roles) for a in second.actions] == [
        ('/example_action', 'example_interfaces/action/Fibonacci', ('client',))]


def test_role_attribute_spec_002() -> None:
    doc = parse('role_attributes.nodl.xml')
    second = doc.nodes[1]
    assert [(s.name, s.roles) for s in second.services] == [
        ('/example_service', ('client',)), ('/example_service_2', ('server',))]
    assert [(a.name, a.roles) for a in second.actions] == [('/example_action', ('server', 'client'))]


def test_both_role_styles_mean_the_same() -> None:
    booleans = parse('boolean_attributes.nodl.xml').nodes
    roles = parse('role_attributes.nodl.xml').nodes
    assert [(t.name, t.roles) for n in booleans for t in n.topics] == \
        [(t.name, t.roles) for n in roles for t in n.topics]


def test_role_both_and_two_true_booleans_give_both_roles() -> None:
    node = parse('role_both.nodl.xml').nodes[0]
    assert [(t.name, t.roles) for t in node.topics] == [
        ('chatter', ('publisher', 'subscription')), ('echo', ('publisher', 'subscription'))]
    assert [(s.name, s.roles) for s in node.services] == [
        ('reset', ('server', 'client')), ('trigger', ('server', 'client'))]
    assert [(a.name, a.roles) for a in node.actions] == [('fibonacci', ('server', 'client'))]


def test_qos_child_element() -> None:
    doc = parse('qos_child.nodl.xml')
    chatter = doc.nodes[0].topics[0]
    assert chatter.qos == LegacyQoS(depth=10, line=5, column=7, positions={'depth': (5, 12)})
    qos = doc.nodes[1].topics[0].qos
    assert qos is not None
    # empty strings mean unset
    assert (qos.history, qos.reliability, qos.durability, qos.liveliness) == (
        'keep_last', None, None, None)
    assert qos.depth == 10
    assert (qos.deadline, qos.lifespan, qos.liveliness_lease_duration) == ('.5', '.5', '.5')
    assert qos.avoid_ros_namespace_conventions is False
    assert doc.nodes[1].services[0].qos.depth == 10  # type: ignore[union-attr]
    assert doc.nodes[1].actions[0].qos.depth == 10  # type: ignore[union-attr]


def test_qos_policy_values_are_case_insensitive_short_keys() -> None:
    qos = parse('qos_full.nodl.xml').nodes[0].topics[0].qos
    assert qos is not None
    assert (qos.history, qos.reliability, qos.durability, qos.liveliness) == (
        'keep_last', 'best_effort', 'volatile', 'automatic')


# --------------------------------------------------------------------------
# Positions


def test_every_element_carries_its_line_and_column() -> None:
    doc = parse('qos_child.nodl.xml')
    assert (doc.line, doc.column) == (1, 1)
    second = doc.nodes[1]
    assert (second.line, second.column) == (9, 3)
    assert (second.parameters[0].line, second.parameters[0].column) == (10, 5)
    assert (second.topics[0].line, second.topics[0].column) == (11, 5)
    assert (second.topics[0].qos.line, second.topics[0].qos.column) == (12, 7)  # type: ignore[union-attr]
    assert (second.services[0].line, second.actions[0].line) == (23, 26)


def test_attributes_written_over_several_lines_have_their_own_position() -> None:
    qos = parse('qos_child.nodl.xml').nodes[1].topics[0].qos
    assert qos is not None
    assert qos.positions['history'] == (13, 9)
    assert qos.positions['avoid_ros_namespace_conventions'] == (21, 9)


# --------------------------------------------------------------------------
# Structural errors


def test_structural_errors_are_all_reported_with_positions(golden) -> None:
    doc = parse_legacy_xml(ERRORS / 'structural.nodl.xml', rel(ERRORS / 'structural.nodl.xml'))
    golden.check(format_text(doc.diagnostics), LEGACY / 'expected' / 'errors' / 'structural.txt')


def test_structural_error_lines() -> None:
    doc = parse_legacy_xml(ERRORS / 'structural.nodl.xml')
    by_line = {d.line: d.message for d in doc.errors}
    assert "unknown attribute 'author' on <interface>" in by_line[1]
    assert "<parameter> has no 'type' attribute" in by_line[3]
    assert "<parameter> has no 'name' attribute" in by_line[4]
    assert "parameter 'rate' is declared twice in this node (first at line 5)" in by_line[6]
    assert "<topic> 't1' has no role" in by_line[7]
    assert "invalid value 'yes' for 'publisher'; expected true or false" in by_line[8]
    assert "invalid role 'publish'" in by_line[9] and "did you mean 'publisher'?" in by_line[9]
    assert 'role="publisher" conflicts with subscription="true"' in by_line[10]
    assert "<topic> 't5' has no role" in by_line[11]
    assert "'publisher' is not a role of a service" in by_line[12]
    assert "unknown attribute 'timeout' on <service>" in by_line[13]
    assert "<action> has no 'name' attribute" in by_line[14]
    assert "<topic> has more than one <qos> (the first is at line 16)" in by_line[17]
    assert 'unknown element <subscriber> inside <node>' in by_line[19]
    assert "<node> has neither an 'executable' nor a 'name' attribute" in by_line[21]
    assert 'unexpected text inside <parameter>' in by_line[22]
    assert "'executable' of <node> is empty" in by_line[24]


def test_bad_qos_values_point_at_the_attribute() -> None:
    doc = parse_legacy_xml(ERRORS / 'structural.nodl.xml')
    line16 = [(d.column, d.message) for d in doc.errors if d.line == 16]
    assert [c for c, _ in line16] == [12, 34, 46, 60]
    assert "invalid history 'keep_latest'" in line16[0][1]
    assert "invalid depth 'ten'" in line16[1][1]
    assert "invalid deadline '-1'" in line16[2][1]
    assert "unknown attribute 'bogus' on <qos>" in line16[3][1]


def test_elements_with_errors_are_left_out_but_the_rest_is_read() -> None:
    doc = parse_legacy_xml(ERRORS / 'structural.nodl.xml')
    assert not doc.ok
    first = doc.nodes[0]
    assert [p.name for p in first.parameters] == ['rate']
    assert first.topics == [] and first.services == [] and first.actions == []


def test_redundant_role_styles_that_agree_are_a_warning() -> None:
    doc = parse_legacy_xml('<interface version="1"><node executable="x">'
                           '<topic name="t" type="a/msg/B" role="publisher" publisher="true"/>'
                           '</node></interface>')
    assert doc.ok
    assert [d.severity for d in doc.diagnostics] == [Severity.WARNING]
    assert 'gives its role twice' in doc.diagnostics[0].message
    assert doc.nodes[0].topics[0].roles == ('publisher',)


def test_role_both_conflicts_with_a_single_boolean() -> None:
    doc = parse_legacy_xml('<interface version="1"><node executable="x">'
                           '<service name="s" type="a/srv/B" role="both" client="true"/>'
                           '</node></interface>')
    assert [d.message for d in doc.errors] == [
        'role="both" conflicts with client="true" on <service>; use only the role attribute']


def test_booleans_accept_xsd_spellings() -> None:
    doc = parse_legacy_xml('<interface version="1"><node executable="x">'
                           '<topic name="a" type="p/msg/T" publisher="1" subscription="FALSE"/>'
                           '</node></interface>')
    assert doc.ok
    assert doc.nodes[0].topics[0].roles == ('publisher',)


def test_wrong_root() -> None:
    doc = parse_legacy_xml(ERRORS / 'wrong_root.nodl.xml')
    assert [(d.line, d.column) for d in doc.errors] == [(1, 1)]
    assert 'the root element is <nodl>' in doc.errors[0].message
    assert doc.nodes == []


def test_package_xml_given_as_an_interface_file_says_what_it_is() -> None:
    doc = parse(os.path.join('package', 'package.xml'))
    assert 'this is a package manifest' in doc.errors[0].message


def test_unsupported_version_and_missing_version() -> None:
    doc = parse_legacy_xml('<interface version="2"><node executable="x"/></interface>')
    assert "unsupported legacy NoDL version '2'" in doc.errors[0].message
    doc = parse_legacy_xml('<interface><node executable="x"/></interface>')
    assert doc.ok
    assert "has no 'version' attribute" in doc.diagnostics[0].message


def test_schema_instance_attributes_are_allowed() -> None:
    doc = parse_legacy_xml(
        '<interface version="1" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
        'xsi:noNamespaceSchemaLocation="nodl.xsd"><node executable="x"/></interface>')
    assert doc.diagnostics == []


def test_empty_document() -> None:
    doc = parse_legacy_xml('')
    assert [d.message for d in doc.errors] == ['malformed XML: no element found']


# --------------------------------------------------------------------------
# Arbitrary text (hostile input to the XML reader: test_frontends_xml_reader.py)


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet=st.sampled_from(list('<>/="\' !?&;[]-\nabcnodeinterfacetopicrole')),
               max_size=120))
def test_arbitrary_text_never_raises(text: str) -> None:
    doc = parse_legacy_xml(text)
    assert isinstance(doc, LegacyDocument)
    for d in doc.diagnostics:
        assert d.line >= 0 and d.column >= 0


# --------------------------------------------------------------------------
# package.xml exports (spec 000)


def test_package_xml_exports_are_resolved_against_its_directory() -> None:
    paths, diagnostics = interface_files_from_package_xml(LEGACY / 'package' / 'package.xml')
    assert diagnostics == []
    assert paths == [LEGACY / 'package' / 'interfaces' / 'talker.nodl.xml',
                     LEGACY / 'package' / 'interfaces' / 'listener.nodl.xml']
    assert all(p.is_file() for p in paths)


def test_package_exports_carry_positions() -> None:
    exports, _ = package_exports(LEGACY / 'package' / 'package.xml')
    assert [(e.line, e.column) for e in exports] == [(10, 16), (11, 16)]


def test_package_without_interface_export() -> None:
    paths, diagnostics = interface_files_from_package_xml(LEGACY / 'package_no_export' / 'package.xml')
    assert paths == []
    assert [(d.line, d.column, d.severity) for d in diagnostics] == [(8, 3, Severity.ERROR)]
    assert 'exports no interface file' in diagnostics[0].message


def test_package_with_bad_exports() -> None:
    paths, diagnostics = interface_files_from_package_xml(LEGACY / 'package_bad_export' / 'package.xml')
    assert [(d.line, d.column) for d in diagnostics] == [(5, 5), (6, 16), (7, 16), (8, 16), (10, 37)]
    assert "no 'path' attribute" in diagnostics[0].message
    assert 'is empty' in diagnostics[1].message
    assert 'leaves the package' in diagnostics[2].message
    assert 'leaves the package' in diagnostics[3].message
    assert "unknown attribute 'kind'" in diagnostics[4].message
    # existence is the converter's business; the well-formed paths are returned
    assert [p.name for p in paths] == ['missing.nodl.xml', 'self.nodl.xml']


def test_an_interface_file_is_not_a_package_xml() -> None:
    paths, diagnostics = interface_files_from_package_xml(LEGACY / 'qos_child.nodl.xml')
    assert paths == []
    assert 'a package manifest has root <package>' in diagnostics[0].message


# --------------------------------------------------------------------------
# The records and the module


def test_records_compare_by_value_and_print_their_fields() -> None:
    a = LegacyEndpoint(kind='topic', name='t', type='a/msg/B', roles=('publisher',), qos=None,
                       line=1, column=1, positions={})
    b = LegacyEndpoint(kind='topic', name='t', type='a/msg/B', roles=('publisher',), qos=None,
                       line=1, column=1, positions={})
    assert a == b
    assert repr(a).startswith("LegacyEndpoint(kind='topic', name='t'")
    with pytest.raises(TypeError):
        LegacyEndpoint(colour='red')


def test_module_imports_neither_dataclasses_nor_pathlib() -> None:
    code = ('import sys; import nodl.frontends.legacy_xml; '
            "print('dataclasses' in sys.modules, 'pathlib' in sys.modules)")
    result = subprocess.run([sys.executable, '-S', '-c', code], cwd=REPO, text=True,
                            capture_output=True, timeout=60,
                            env={**os.environ, 'PYTHONPATH': str(REPO)})
    assert result.stdout.split() == ['False', 'False'], result.stderr


def test_many_errors_are_collected_in_linear_time() -> None:
    # Counting the errors so far for every element used to make this quadratic (5,000: 28 s).
    import time

    xml = ('<interface version="1"><node name="n" executable="e">' + '<parameter/>' * 5000
           + '</node></interface>')
    start = time.perf_counter()
    document = parse_legacy_xml(xml)
    assert time.perf_counter() - start < 2.0
    assert len(document.diagnostics) == 10000  # name and type missing, for each one
