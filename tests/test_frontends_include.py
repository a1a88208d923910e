"""The reference implementation's include dialect, read as a NoDL v2 node definition."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

import nodl
from conftest import FIXTURES, REPO
from nodl import compose
from nodl.dialects import INCLUDE, recognise
from nodl.frontends.include import read_include
from nodl.loading import check_source
from nodl.model import Base, Node
from nodl.show import show_file
from nodl.validation.kinds import Kind

PKG = FIXTURES / 'dialects' / 'include' / 'arm_driver' / 'nodl'
PREFIX = FIXTURES / 'dialects' / 'include' / 'prefix'


@pytest.fixture
def prefix(monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(PREFIX))
    return PREFIX


def test_an_include_document_loads_as_a_node_definition() -> None:
    node = nodl.load_nodl(PKG / 'arm_driver.nodl.yaml')
    assert isinstance(node, Node)
    assert node.base is Base.NODE  # nodl://rclcpp/node is the built-in base description
    assert node.mixins == ['nodl://arm_common/heartbeat', 'shared/joint_limits.nodl.yaml']
    assert set(node.main.parameters) == {'joint_count'}
    assert [p.name for p in node.main.publishers] == ['~/joint_states']
    assert node.main.description.startswith('Commands the joints')


def test_one_warning_names_the_dialect_at_the_include_key() -> None:
    report = check_source(PKG / 'arm_driver.nodl.yaml', file='arm_driver.nodl.yaml')
    assert report.kind is Kind.NODE
    assert not report.errors
    [warning] = report.warnings
    assert warning.code == 'NODL851'
    assert (warning.line, warning.column) == (5, 1)
    assert "'include' dialect" in warning.message and 'codegen kept' in warning.message
    assert warning.path == ('include',)


CODEGEN = {'cpp': {'class': 'ArmDriverBase', 'header': 'arm_driver/arm_driver_base.hpp'}}


def test_the_codegen_block_is_kept_as_the_nodes_codegen() -> None:
    import yaml

    data = yaml.safe_load((PKG / 'arm_driver.nodl.yaml').read_text())
    reading = read_include(data)
    assert reading.codegen == CODEGEN
    assert reading.data['codegen'] == CODEGEN and 'codegen' not in reading.data['main']


def test_codegen_survives_load_and_dump() -> None:
    node = nodl.load_node(PKG / 'arm_driver.nodl.yaml')
    assert node.codegen == CODEGEN
    again = nodl.load_node(nodl.dump_nodl(node))
    assert again.codegen == CODEGEN and again == node
    assert nodl.load_node(nodl.dump_nodl(node, 'json')).codegen == CODEGEN


@pytest.mark.parametrize(('ref', 'line', 'wording'), [
    ('nodl:/x', 3, "is not a URI: a scheme is followed by '://' (did you mean 'nodl://x'?)"),
    ('://x', 3, "has no scheme before '://'"),
    ('common/limits.nodl.yaml', 3, 'is a path, not a URI (write local://common/limits.nodl.yaml)'),
    ('./limits.nodl.yaml', 3, 'is a path, not a URI (write local://limits.nodl.yaml)'),
    ('/opt/limits.nodl.yaml', 3, 'is a path, not a URI (an absolute path'),
    ('nodl:///name', 3, 'has an empty authority'),
    ('local://', 3, 'has nothing after the scheme'),
    ('NODL://pkg/name', 3, "has an invalid scheme 'NODL'"),
    ('has space://pkg/name', 3, "has an invalid scheme 'has space'"),
    ('local://a b.yaml', 3, 'holds white space'),
])
def test_an_include_reference_that_is_not_a_uri_is_an_error_at_its_value(
        ref: str, line: int, wording: str) -> None:
    text = f'nodl_version: 2\ninclude:\n  - ref: "{ref}"\n  - ref: nodl://pkg/fine\n'
    report = check_source(text, file='node.nodl.yaml')
    [error] = report.errors
    assert (error.code, error.path_text, error.line, error.column) == (
        'NODL818', 'include[0].ref', line, 10)
    assert error.message == f"'{ref}' {wording}" or error.message.startswith(f"'{ref}' {wording}")


@pytest.mark.parametrize('ref', ['nodl://pkg/name', 'local://shared/limits.nodl.yaml',
                                 'local://../common/x.nodl.yaml', 'test://in_memory/doc',
                                 'https://example.com/x.nodl.yaml', 'git+ssh://host/repo'])
def test_uris_of_any_scheme_are_include_references(ref: str) -> None:
    from nodl.frontends.include import uri_problem

    assert uri_problem(ref) is None
    report = check_source(f'nodl_version: 2\ninclude:\n  - ref: {ref}\n')
    assert not report.errors, report.errors


def test_includes_spelling_and_the_lifecycle_base_description() -> None:
    node = nodl.load_node(PKG / 'gripper_lifecycle.nodl.yaml')
    # Both base descriptions are included: lifecycle_node's holds node's, so it is the base.
    assert node.base is Base.LIFECYCLE_NODE
    assert not node.mixins
    assert [s.name for s in node.main.service_servers] == ['~/grip']


def test_include_and_includes_together_is_an_error() -> None:
    text = ('nodl_version: 2\ninclude:\n  - ref: nodl://a_pkg/one\n'
            'includes:\n  - ref: nodl://a_pkg/two\n')
    report = check_source(text)
    [error] = report.errors
    assert error.code == 'NODL853' and (error.line, error.column) == (4, 1)


def test_diagnostics_land_on_the_original_lines_and_paths() -> None:
    report = check_source(PKG / 'broken.nodl.yaml', file='broken.nodl.yaml')
    found = {(d.line, d.column, d.path_text, d.code) for d in report.errors}
    assert (4, 5, 'include[1]', 'NODL852') in found          # a bare string, not {ref: ...}
    assert (6, 5, 'include[2].prefix', 'NODL852') in found   # an unknown key in an entry
    # An error in the flat interface (main, once converted) is reported at its own line.
    type_errors = [d for d in report.errors if d.path_text == 'publishers[0].type']
    assert [(d.line, d.column) for d in type_errors] == [(9, 11)]


def test_a_reference_error_points_at_the_ref(tmp_path: Path) -> None:
    report = check_source('nodl_version: 2\ninclude:\n  - ref: local://\n')
    assert any(d.path_text == 'include[0].ref' and d.line == 3 for d in report.errors), \
        report.diagnostics


def test_compose_resolves_nodl_and_local_includes(prefix: Path) -> None:
    composed = compose(PKG / 'arm_driver.nodl.yaml')
    params = composed.interface.parameters
    assert {'use_sim_time', 'heartbeat.period', 'limits.max_velocity', 'joint_count'} <= set(params)
    assert [layer.label for layer in composed.layers][1:] == [
        'nodl://arm_common/heartbeat', 'shared/joint_limits.nodl.yaml', 'main']
    assert any(p.name == '/heartbeat' for p in composed.interface.publishers)


def test_an_unresolvable_local_include_is_placed_at_its_ref(prefix: Path) -> None:
    with pytest.raises(nodl.ValidationError) as caught:
        compose(PKG / 'missing_local.nodl.yaml', file='missing_local.nodl.yaml')
    [error] = caught.value.errors
    assert (error.line, error.column) == (3, 10)
    assert 'no_such_file.nodl.yaml' in error.message


def test_show_composes_an_include_document(prefix: Path) -> None:
    shown = show_file(str(PKG / 'arm_driver.nodl.yaml'))
    assert shown.interface is not None
    assert 'limits.max_velocity' in shown.interface.parameters


def test_recognise() -> None:
    assert recognise({'nodl_version': 2, 'include': []}) == INCLUDE
    assert recognise({'nodl_version': 2, 'includes': []}) == INCLUDE
    # A v2 node with a stray include key stays a v2 node (and gets 'unknown key').
    assert recognise({'nodl_version': 2, 'main': {}, 'include': []}) is None
    assert recognise({'nodl_version': 2, 'publishers': []}) is None


def test_validate_resolve_accepts_the_dialect_in_a_real_process() -> None:
    env = dict(os.environ, AMENT_PREFIX_PATH=str(PREFIX))
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--resolve',
                             os.path.relpath(PKG / 'arm_driver.nodl.yaml', REPO)],
                            cwd=REPO, text=True, capture_output=True, timeout=60, env=env)
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.count('warning:') == 1
    assert "arm_driver.nodl.yaml:5:1: warning: this file is written in the reference " \
        "implementation's 'include' dialect" in result.stdout


# -- nested includes: the reference resolves includes recursively ---------------------------

CAMERA = FIXTURES / 'dialects' / 'include' / 'camera_driver' / 'nodl'


def test_an_included_document_that_includes_others_is_flattened(prefix: Path) -> None:
    composed = compose(CAMERA / 'wrist_camera.nodl.yaml')
    # What an included document includes comes before it; local:// is relative to its holder.
    assert [layer.label for layer in composed.layers] == [
        'base:lifecycle_node', 'nodl://arm_common/heartbeat',
        'shared/camera_common.nodl.yaml > sensor_health.nodl.yaml',
        'shared/camera_common.nodl.yaml', 'main']
    # The lifecycle base description, included by the included document, is the node's base.
    assert composed.node.base is Base.LIFECYCLE_NODE
    origins = {p.name: p.origin for p in composed.interface.publishers}
    assert origins['~/health'] == 'shared/camera_common.nodl.yaml > sensor_health.nodl.yaml'
    assert origins['~/image_raw'] == 'shared/camera_common.nodl.yaml'
    assert '~/transition_event' in origins and '/heartbeat' in origins
    assert not [d for d in composed.diagnostics if d.severity.value == 'error']


def test_a_cycle_of_includes_is_an_error_where_it_closes(prefix: Path) -> None:
    with pytest.raises(nodl.ValidationError) as caught:
        compose(CAMERA / 'looping.nodl.yaml')
    [error] = caught.value.errors
    assert error.code == 'NODL311' and 'includes itself' in error.message
    assert error.file.endswith('loop_b.nodl.yaml') and (error.line, error.column) == (3, 10)
    # The node's own include entry that leads there is named as a related place.
    [(file, line, column, _)] = error.related
    assert file.endswith('looping.nodl.yaml') and line == 3


def test_a_document_included_twice_is_an_error(prefix: Path) -> None:
    with pytest.raises(nodl.ValidationError) as caught:
        compose(CAMERA / 'twice.nodl.yaml')
    [error] = caught.value.errors
    assert error.code == 'NODL311' and 'included twice' in error.message
    assert error.file.endswith('twice.nodl.yaml') and error.line == 5
    assert 'shared/camera_common.nodl.yaml > sensor_health.nodl.yaml' in error.message


def test_an_unresolvable_nested_include_is_placed_in_the_file_that_holds_it(prefix: Path) -> None:
    with pytest.raises(nodl.ValidationError) as caught:
        compose(CAMERA / 'bad_inner.nodl.yaml')
    [error] = caught.value.errors
    assert error.code == 'NODL301' and 'no_such_part.nodl.yaml' in error.message
    assert error.file.endswith('broken_inner.nodl.yaml') and error.line == 3
    assert error.related and error.related[0][0].endswith('bad_inner.nodl.yaml')


def test_a_v2_node_definition_as_a_mixin_is_still_refused(tmp_path: Path) -> None:
    (tmp_path / 'package.xml').write_text('<package/>')
    (tmp_path / 'inner.nodl.yaml').write_text('nodl_version: 2\nmain: {nodl_version: 2}\n')
    (tmp_path / 'outer.nodl.yaml').write_text(
        'nodl_version: 2\nmixins: [inner.nodl.yaml]\nmain: {nodl_version: 2}\n')
    with pytest.raises(nodl.ValidationError) as caught:
        compose(tmp_path / 'outer.nodl.yaml')
    [error] = caught.value.errors
    assert error.code == 'NODL303' and 'single-level' in error.message


def test_deps_lists_nested_local_includes_for_installation() -> None:
    from nodl.packaging import relative_mixins

    assert relative_mixins(CAMERA / 'wrist_camera.nodl.yaml') == [
        'shared/camera_common.nodl.yaml', 'shared/sensor_health.nodl.yaml']
    assert relative_mixins(CAMERA / 'looping.nodl.yaml') == [
        'shared/loop_a.nodl.yaml', 'shared/loop_b.nodl.yaml']  # and it terminates


def test_validate_resolve_and_show_nested_includes_in_a_real_process() -> None:
    env = dict(os.environ, AMENT_PREFIX_PATH=str(PREFIX))
    node = os.path.relpath(CAMERA / 'wrist_camera.nodl.yaml', REPO)
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--resolve', node],
                            cwd=REPO, text=True, capture_output=True, timeout=60, env=env)
    assert result.returncode == 0, result.stdout + result.stderr
    result = subprocess.run([sys.executable, '-m', 'nodl', 'show', '--layers', node],
                            cwd=REPO, text=True, capture_output=True, timeout=60, env=env)
    assert result.returncode == 0, result.stderr
    assert '# layer: shared/camera_common.nodl.yaml > sensor_health.nodl.yaml\n  - name: ~/health' \
        in result.stdout
    assert '# layer: base:lifecycle_node' in result.stdout
