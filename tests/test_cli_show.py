"""`nodl show`: run as a real process, as users run it."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from conftest import FIXTURES, REPO
from nodl import load_interface

INDEX = FIXTURES / 'index'
BOTH = os.pathsep.join([str(INDEX / 'first'), str(INDEX / 'second')])
GOLDEN = FIXTURES / 'show'


def nodl(*args: str, prefixes: str | None = BOTH) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ)
    if prefixes is None:
        env.pop('AMENT_PREFIX_PATH', None)
    else:
        env['AMENT_PREFIX_PATH'] = prefixes
    return subprocess.run([sys.executable, '-m', 'nodl', 'show', *args], cwd=REPO,
                          env=env, text=True, capture_output=True, timeout=60)


def test_show_file_prints_the_resolved_interface() -> None:
    result = nodl('examples/laser_driver.nodl.yaml')
    assert result.returncode == 0, result.stderr
    assert result.stderr == ''  # override notes are informational: not printed
    assert result.stdout == (GOLDEN / 'laser_driver.yaml').read_text(encoding='utf-8')


def test_show_file_with_layers() -> None:
    result = nodl('examples/camera_lifecycle.nodl.yaml', '--layers')
    assert result.returncode == 0, result.stderr
    assert result.stdout == (GOLDEN / 'camera_lifecycle.layers.yaml').read_text(encoding='utf-8')
    load_interface(result.stdout, strict=True)


def test_show_file_as_json() -> None:
    result = nodl('examples/camera_lifecycle.nodl.yaml', '--format', 'json', '--layers')
    assert result.returncode == 0, result.stderr
    assert result.stdout == (GOLDEN / 'camera_lifecycle.layers.json').read_text(encoding='utf-8')
    plain = nodl('examples/camera_lifecycle.nodl.yaml', '--format', 'json')
    assert json.loads(plain.stdout) == json.loads(result.stdout)['interface']


def test_show_interface_file() -> None:
    result = nodl('examples/diagnostics.nodl.yaml', '--layers')
    assert result.returncode == 0, result.stderr
    assert result.stdout.count('# layer: diagnostics.nodl.yaml') == 3


def test_missing_file_is_a_usage_error() -> None:
    result = nodl('no/such/file.nodl.yaml')
    assert result.returncode == 2
    assert result.stdout == ''
    assert result.stderr == ('nodl show: error: no/such/file.nodl.yaml: no such file (to look up '
                             'an installed node, give PACKAGE EXECUTABLE)\n')


def test_wrong_number_of_targets_is_a_usage_error() -> None:
    result = nodl('a', 'b', 'c')
    assert result.returncode == 2
    assert 'expected FILE or PACKAGE EXECUTABLE' in result.stderr
    assert nodl().returncode == 2
    assert nodl('examples/laser_driver.nodl.yaml', '--format', 'toml').returncode == 2


def test_invalid_file_exits_1_with_positions() -> None:
    result = nodl('examples/mistakes/typos.yaml')
    assert result.returncode == 1
    assert result.stdout == ''
    lines = result.stderr.splitlines()
    assert lines[0].startswith('examples/mistakes/typos.yaml:4:7: error: ')
    assert sum(': error: ' in line for line in lines) == 7
    assert 'Traceback' not in result.stderr


def test_parameter_definition_exits_1() -> None:
    result = nodl('examples/max_speed.nodl.yaml')
    assert result.returncode == 1
    assert result.stderr.startswith('examples/max_speed.nodl.yaml:1:1: error: a parameter '
                                    'definition has no interface to show')


def test_unresolvable_mixins_exit_1_at_the_mixin_entries() -> None:
    result = nodl('tests/fixtures/composition/errors/pkg/all_errors.nodl.yaml',
                  prefixes=str(FIXTURES / 'composition' / 'prefix'))
    assert result.returncode == 1
    assert result.stdout == ''
    errors = [line for line in result.stderr.splitlines() if ': error: ' in line]
    assert len(errors) == 12
    node = 'tests/fixtures/composition/errors/pkg/all_errors.nodl.yaml'
    assert [line.split(': error: ')[0] for line in errors if line.startswith(node)] == [
        f'{node}:{4 + i}:5' for i in range(10)]


def test_warnings_are_printed_and_the_interface_still_shown(tmp_path) -> None:
    node = tmp_path / 'warn.nodl.yaml'
    node.write_text('nodl_version: 2\nmain:\n  nodl_version: 2\n  publishers:\n'
                    '    - {name: x, type: std_msgs/msg/String, qos: {history: KEEP_ALL, '
                    'reliability: RELIABLE}}\n')
    result = nodl(str(node))
    assert result.returncode == 0, result.stderr
    assert f'{node}:5:7: warning: ' in result.stderr
    assert load_interface(result.stdout).publishers[0].name == 'x'


def test_package_executable_is_looked_up_in_the_index() -> None:
    result = nodl('beta', 'node', '--layers')
    assert result.returncode == 0, result.stderr
    layers = {line.strip() for line in result.stdout.splitlines() if '# layer:' in line}
    assert layers == {'# layer: base:lifecycle_node', '# layer: nodl://beta/status',
                      '# layer: nodl://alpha/chatter'}
    assert "description: Beta's node" in result.stdout


def test_package_executable_first_prefix_wins() -> None:
    assert 'The talker of the FIRST prefix.' in nodl('alpha', 'talker').stdout
    swapped = os.pathsep.join([str(INDEX / 'second'), str(INDEX / 'first')])
    assert 'The talker of the SECOND prefix' in nodl('alpha', 'talker', prefixes=swapped).stdout


def test_package_executable_not_found() -> None:
    result = nodl('alpha', 'nope')
    assert result.returncode == 2  # not found, as a missing file (and as in check)
    assert result.stdout == ''
    assert result.stderr == ("alpha/nope: error: package 'alpha' registers no node definition "
                             "for 'nope' (it has: inline, listener, talker) [NODL306]\n")
    result = nodl('zeta', 'x')
    assert (result.returncode, result.stderr) == (
        2, "zeta/x: error: package 'zeta' is not in the ament index [NODL306]\n")


def test_package_executable_without_ament_prefix_path() -> None:
    result = nodl('alpha', 'talker', prefixes=None)
    assert result.returncode == 2
    assert 'AMENT_PREFIX_PATH is empty; source the workspace' in result.stderr


def test_package_executable_with_a_dangling_entry() -> None:
    result = nodl('delta', 'dangling')
    assert result.returncode == 2
    assert result.stderr.startswith('delta/dangling: error: the index entry ')
    assert 'gone.nodl.yaml, which does not exist' in result.stderr


# --- client libraries ---------------------------------------------------------------------------

SYSTEM_PREFIX = str(FIXTURES / 'system' / 'prefix')


def test_a_registered_node_takes_the_client_library_of_its_package_build_type() -> None:
    cpp = nodl('cpp_pkg', 'driver', prefixes=SYSTEM_PREFIX)
    assert cpp.returncode == 0, cpp.stderr
    assert cpp.stdout.splitlines()[0] == (
        "# client library: rclcpp (package 'cpp_pkg' is built with ament_cmake)")
    assert 'subscriptions:\n- name: /parameter_events\n' in cpp.stdout  # rclcpp's time source
    py = nodl('py_pkg', 'driver', prefixes=SYSTEM_PREFIX)
    assert py.stdout.splitlines()[0] == (
        "# client library: rclpy (package 'py_pkg' is built with ament_python)")
    assert 'subscriptions:' not in py.stdout
    plain = nodl('plain_pkg', 'driver', prefixes=SYSTEM_PREFIX)
    assert plain.stdout.splitlines()[0] == (
        "# client library: rclpy (package 'plain_pkg' has no build type; rclpy by default)")


def test_client_library_option_wins_and_is_stated_in_json() -> None:
    result = nodl('cpp_pkg', 'driver', '--client-library', 'rclpy', '--layers', '--format', 'json',
                  prefixes=SYSTEM_PREFIX)
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data['client_library'] == {'name': 'rclpy', 'reason': 'as requested'}
    assert 'subscriptions' not in data['interface']
    plain = nodl('examples/laser_driver.nodl.yaml', '--format', 'json', '--client-library', 'rclcpp')
    assert plain.returncode == 0, plain.stderr
    assert plain.stderr == 'nodl show: note: client library rclcpp (as requested)\n'
    assert json.loads(plain.stdout)['subscriptions'][0]['name'] == '/parameter_events'
    bad = nodl('examples/laser_driver.nodl.yaml', '--client-library', 'rclc')
    assert bad.returncode == 2 and 'Traceback' not in bad.stderr


def test_a_node_that_redefines_its_base_cannot_be_shown() -> None:
    result = nodl('tests/fixtures/composition/overrides/base_redefined.nodl.yaml')
    assert result.returncode == 1
    assert result.stdout == ''
    assert 'NODL307' in result.stderr and 'Traceback' not in result.stderr


def test_show_a_node_the_references_ament_nodl_register_installed() -> None:
    reference = str(FIXTURES / 'index' / 'reference')
    result = nodl('ref_robot', 'lidar', '--layers', prefixes=reference)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("# client library: rclcpp (package 'ref_robot' is built with "
                                    'ament_cmake)\n')
    assert '# layer: nodl://ref_robot/sensor_common\n  frame_id:' in result.stdout
    shown = load_interface(nodl('ref_robot', 'talker', prefixes=reference).stdout)
    assert shown.codegen == {'cpp': {'role': 'base_class', 'header': 'ref_robot/talker_base.hpp'}}
    assert set(shown.parameters) == {'greeting'}
    included = load_interface(nodl('nodl://ref_robot/sensor_common', prefixes=reference).stdout)
    assert set(included.parameters) == {'frame_id'}


def test_definitions_folders_serve_nodes_and_references() -> None:
    overlays = FIXTURES / 'overlays'
    defs = str(overlays / 'defs')
    shown = nodl('upstream_drv', 'driver', '--definitions', defs, prefixes=None)
    assert shown.returncode == 0, shown.stderr
    assert 'name: status' in shown.stdout  # the nodl:// mixin from the folder's interfaces/
    assert f'note: {defs}/upstream_drv/driver.nodl.yaml (overlay {defs})' in shown.stderr
    assert 'description: The driver' in nodl('nodl://upstream_drv/status', '--definitions', defs,
                                            prefixes=None).stdout
    assert nodl('upstream_drv', 'driver', prefixes=None).returncode == 2  # not without it
    bad = nodl('my_pkg', 'node', '--definitions', str(overlays / 'bad'), prefixes=None)
    assert bad.returncode == 1 and '[NODL240]' in bad.stderr and 'nodl_version: 2' in bad.stdout
