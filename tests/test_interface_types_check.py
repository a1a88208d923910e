"""Endpoint types checked against the installed interfaces (interface_types.check)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl.interface_types import InterfaceIndex
from nodl.interface_types.check import check_types, manifest_for, type_entries
from nodl.interface_types.manifest import read_manifest
from nodl.loading import check_source

VENV = str(Path(sys.prefix))
TYPES = FIXTURES / 'interface_types'
PACKAGE = TYPES / 'types_pkg'


def _codes(diagnostics: list) -> list[tuple[int, str]]:  # type: ignore[type-arg]
    return [(d.line, d.code) for d in diagnostics]


def test_wrong_types_each_located_at_the_type_value() -> None:
    report = check_source(TYPES / 'wrong_types.nodl.yaml')
    found = check_types(report, InterfaceIndex([VENV]))
    assert _codes(found) == [(4, 'NODL251'), (8, 'NODL253'), (12, 'NODL250'), (16, 'NODL254'),
                             (25, 'NODL252')]
    assert all(d.column == 11 and d.file.endswith('wrong_types.nodl.yaml') for d in found)
    assert "did you mean 'sensor_msgs/msg/LaserScan'?" in found[0].message
    assert "resolves to 'std_msgs/msg/String'" in found[1].message
    assert "'std_msgs/msg/String' is a message" in found[4].message


def test_package_dependencies_and_own_source_types() -> None:
    report = check_source(PACKAGE / 'nodl' / 'device.nodl.yaml')
    index = InterfaceIndex([VENV], [str(PACKAGE)])
    found = check_types(report, index, read_manifest(str(PACKAGE)))
    assert _codes(found) == [(19, 'NODL256'), (23, 'NODL255'), (27, 'NODL250'), (3, 'NODL258')]
    # the malformed source file, at its line, related to the type: that names it
    assert found[3].file.endswith('Broken.msg') and found[3].related[0][1:3] == (11, 13)
    assert '<depend>geometry_msgs</depend>' in found[1].message
    assert found[0].related[0][1] == 10  # the <build_depend> line of package.xml


def test_at_build_time_a_declared_uninstalled_package_is_a_warning() -> None:
    report = check_source(PACKAGE / 'nodl' / 'device.nodl.yaml')
    index = InterfaceIndex([VENV], [str(PACKAGE)])
    found = check_types(report, index, read_manifest(str(PACKAGE)), build=True)
    assert (27, 'NODL257') in _codes(found) and (27, 'NODL250') not in _codes(found)
    assert (23, 'NODL255') in _codes(found)  # not declared: still an error


def test_without_the_source_the_own_types_are_unknown() -> None:
    report = check_source(PACKAGE / 'nodl' / 'device.nodl.yaml')
    found = check_types(report, InterfaceIndex([VENV]))
    assert (7, 'NODL250') in _codes(found)


def test_a_registered_definition_uses_its_installed_manifest(tmp_path: Path) -> None:
    share = tmp_path / 'share'
    (share / 'ament_index' / 'resource_index' / 'packages').mkdir(parents=True)
    (share / 'ament_index' / 'resource_index' / 'packages' / 'types_pkg').write_text('')
    shutil.copytree(PACKAGE, share / 'types_pkg')
    manifest = manifest_for(str(share / 'types_pkg' / 'nodl' / 'device.nodl.yaml'))
    assert manifest is not None and manifest.name == 'types_pkg'
    assert manifest_for(str(PACKAGE / 'nodl' / 'device.nodl.yaml')) is None


def test_entries_of_a_node_are_under_main() -> None:
    report = check_source(PACKAGE / 'nodl' / 'device.nodl.yaml')
    first = next(type_entries(report))
    assert first == (('main', 'publishers', 0, 'type'), 'types_pkg/msg/Status', 'msg')


@pytest.mark.parametrize('content, problem', [
    ('<package><name>x</name>', 'is not well-formed XML'),
    ('<!DOCTYPE package><package/>', 'holds a DTD'),
    ('<manifest/>', 'has the root element <manifest>'),
])
def test_unreadable_manifests_are_one_error(tmp_path: Path, content: str, problem: str) -> None:
    (tmp_path / 'package.xml').write_text(content, encoding='utf-8')
    manifest = read_manifest(str(tmp_path))
    assert manifest.problem is not None and problem in manifest.problem
    report = check_source(TYPES / 'wrong_types.nodl.yaml')
    found = check_types(report, InterfaceIndex([VENV]), manifest)
    assert [d.code for d in found].count('NODL259') == 1


def test_a_malformed_installed_file_is_one_diagnostic_at_its_line() -> None:
    """An installed .msg that does not parse: one NODL258 at its line, related to every
    type: that names it (directly or by a type that nests it); the sound types pass."""
    prefix = str(TYPES / 'bad_prefix')
    report = check_source(TYPES / 'bad_installed.nodl.yaml')
    found = check_types(report, InterfaceIndex([prefix, VENV]))
    [problem] = found
    assert problem.code == 'NODL258'
    assert (problem.file, problem.line, problem.column) == (
        str(TYPES / 'bad_prefix' / 'share' / 'bad_msgs' / 'msg' / 'Reading.msg'), 3, 1)
    assert "'bad_msgs/msg/Reading' cannot be read: is not a valid interface definition" in problem.message
    assert [(r[1], r[2]) for r in problem.related] == [(7, 13), (11, 13), (20, 13)]
    assert all(r[0] == report.file for r in problem.related)
    assert problem.related[1][3] == "'bad_msgs/msg/Outer' named here, as main.publishers[1].type"
    # a nested type that is not installed is the nesting file's problem, at its field
    index = InterfaceIndex([prefix])  # no std_msgs: Outer's header cannot be found
    from nodl.interface_types.check import interface_problem

    missing = interface_problem(index, 'bad_msgs/msg/Outer')
    assert missing.file.endswith('Outer.msg') and missing.line == 2
    assert "field 'header' is of type 'std_msgs/msg/Header', which cannot be found" in missing.message
