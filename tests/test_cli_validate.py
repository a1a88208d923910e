"""`nodl validate`: run as a real process, as users run it."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from conftest import FIXTURES, REPO

CLI = FIXTURES / 'cli'


def nodl(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                          capture_output=True, input=stdin, timeout=60)


def rel(path: Path) -> str:
    return os.path.relpath(path, REPO)


def test_valid_file_exits_0_and_prints_kind_and_summary() -> None:
    result = nodl('validate', rel(CLI / 'valid_interface.nodl.yaml'))
    assert result.returncode == 0, result.stderr
    assert f'{rel(CLI / "valid_interface.nodl.yaml")}: valid interface definition' in result.stdout
    assert result.stdout.rstrip().endswith('1 file, 0 errors, 0 warnings')


def test_invalid_json_file_reports_file_line_col_and_exits_1(golden) -> None:
    result = nodl('validate', rel(CLI / 'invalid_node.nodl.json'))
    assert result.returncode == 1
    golden.check(result.stdout, CLI / 'invalid_node.expected')


def test_every_error_is_reported_with_position() -> None:
    result = nodl('validate', rel(CLI / 'invalid_node.nodl.json'))
    lines = [line for line in result.stdout.splitlines() if ': error: ' in line]
    assert len(lines) == 2
    assert lines[0].startswith(f'{rel(CLI / "invalid_node.nodl.json")}:3:11: error: ')
    assert "did you mean 'node'?" in lines[0]
    assert ':7:48: error: default_value of an int parameter must be an integer' in lines[1]


def test_any_extension_is_accepted_when_named_explicitly() -> None:
    result = nodl('validate', rel(CLI / 'any_extension.txt'))
    assert result.returncode == 0, result.stdout
    assert 'valid parameter definition' in result.stdout


def test_directory_is_searched_for_nodl_files_only() -> None:
    result = nodl('validate', '-q', rel(CLI))
    # three *.nodl.* files; any_extension.txt is not picked up by the search
    assert result.stdout.rstrip().splitlines()[-1].startswith('3 files, ')
    assert 'any_extension.txt' not in result.stdout
    assert result.returncode == 1


def test_stdin() -> None:
    text = (CLI / 'valid_interface.nodl.yaml').read_text()
    result = nodl('validate', '-', stdin=text)
    assert result.returncode == 0
    assert '<stdin>: valid interface definition' in result.stdout


def test_stdin_errors_are_placed() -> None:
    result = nodl('validate', '-', stdin='nodl_version: 2\npublisher: []\n')
    assert result.returncode == 1
    assert "<stdin>:2:1: error: unknown key 'publisher'; did you mean 'publishers'?" in result.stdout


def test_kind_is_enforced() -> None:
    result = nodl('validate', '--kind', 'node', rel(CLI / 'valid_interface.nodl.yaml'))
    assert result.returncode == 1
    assert 'expected a node definition, but this is an interface definition' in result.stdout


def test_warnings_fail_only_with_strict() -> None:
    path = rel(CLI / 'warning_only.nodl.yaml')
    relaxed = nodl('validate', path)
    strict = nodl('validate', '--strict', path)
    assert relaxed.returncode == 0
    assert strict.returncode == 1
    assert "warning: publisher '~/chatter' has no description" in strict.stdout
    assert strict.stdout.rstrip().endswith('1 file, 0 errors, 1 warning')


def test_json_format_lists_diagnostic_objects() -> None:
    result = nodl('validate', '--format', 'json', rel(CLI / 'invalid_node.nodl.json'))
    assert result.returncode == 1
    diagnostics = json.loads(result.stdout)
    assert [sorted(d) for d in diagnostics] == [
        ['code', 'column', 'file', 'line', 'message', 'path', 'related', 'severity']] * 2
    assert diagnostics[1]['path'] == 'main.parameters.gain.default_value'
    assert (diagnostics[1]['line'], diagnostics[1]['column']) == (7, 48)
    assert diagnostics[0]['severity'] == 'error'
    assert result.stderr.strip() == '1 file, 2 errors, 0 warnings'


def test_missing_file_is_an_io_error_exit_2_but_others_are_still_checked() -> None:
    result = nodl('validate', 'does/not/exist.yaml', rel(CLI / 'valid_interface.nodl.yaml'))
    assert result.returncode == 2
    assert 'does/not/exist.yaml: error: no such file or directory' in result.stderr
    assert 'valid interface definition' in result.stdout


def test_usage_error_exits_2_without_traceback() -> None:
    result = nodl('validate', '--kind', 'robot', 'x')
    assert result.returncode == 2
    assert 'Traceback' not in result.stderr
    assert "invalid choice: 'robot'" in result.stderr


def test_hostile_input_gives_one_line_not_a_traceback() -> None:
    result = nodl('validate', '-', stdin='a: [' + '[' * 5000 + ']' * 5001 + '\n')
    assert result.returncode == 1
    assert 'Traceback' not in result.stdout + result.stderr
    assert 'nests deeper than 100 levels' in result.stdout


def test_examples_are_valid() -> None:
    result = nodl('validate', '--strict', 'examples/')
    assert result.returncode == 0, result.stdout
    # 7 in examples/ and examples/workspace, 16 in the example system (examples/system)
    assert result.stdout.rstrip().endswith('23 files, 0 errors, 0 warnings')


def test_resolve_strict_refuses_a_node_that_redefines_its_base() -> None:
    # The measured defect of issue 7: main redefined use_sim_time as a string and /rosout as
    # std_msgs/msg/String, and validate --resolve --strict printed two info lines and passed.
    fixture = 'tests/fixtures/composition/overrides/base_redefined.nodl.yaml'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--resolve', '--strict',
                             fixture], cwd=REPO, text=True, capture_output=True, timeout=60)
    assert result.returncode == 1, result.stdout + result.stderr
    errors = [line for line in result.stdout.splitlines() if ': error: ' in line]
    assert errors == [
        f"{fixture}:7:5: error: parameter 'use_sim_time' from main changes the type of the one from "
        'base:node (bool -> string); the client library creates it, so a node cannot change it: '
        'only its description may be refined [main.parameters.use_sim_time] [NODL307]',
        f"{fixture}:12:7: error: publisher '/rosout' from main changes the type of the one from "
        'base:node (rcl_interfaces/msg/Log -> std_msgs/msg/String); the client library creates it, '
        'so a node cannot change it: only its description may be refined [main.publishers[0]] '
        '[NODL307]']
    # a mixin's type changed by main is a warning: it fails only with --strict
    mixin = 'tests/fixtures/composition/overrides/mixin_type_changed.nodl.yaml'
    lenient = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--resolve', mixin],
                             cwd=REPO, text=True, capture_output=True, timeout=60)
    strict = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--resolve', '--strict',
                             mixin], cwd=REPO, text=True, capture_output=True, timeout=60)
    assert (lenient.returncode, strict.returncode) == (0, 1), lenient.stdout + strict.stdout
    assert '[NODL310]' in strict.stdout
    # refining a base entity's description is allowed
    refined = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--resolve', '--strict',
                              'tests/fixtures/composition/overrides/base_refined.nodl.yaml'],
                             cwd=REPO, text=True, capture_output=True, timeout=60)
    assert refined.returncode == 0, refined.stdout + refined.stderr


def test_resolve_composes_the_base_of_the_chosen_client_library() -> None:
    # validate --resolve always composed the rclpy base; --client-library chooses (default rclpy)
    fixture = 'tests/fixtures/composition/overrides/rclcpp_base_redefined.nodl.yaml'
    default = nodl('validate', '--resolve', '--strict', fixture)
    rclpy = nodl('validate', '--resolve', '--strict', '--client-library', 'rclpy', fixture)
    rclcpp = nodl('validate', '--resolve', '--client-library', 'rclcpp', fixture)
    assert (default.returncode, rclpy.returncode, rclcpp.returncode) == (0, 0, 1), rclcpp.stdout
    errors = [line for line in rclcpp.stdout.splitlines() if ': error: ' in line]
    assert [line.rsplit(' ', 1)[-1] for line in errors] == ['[NODL307]', '[NODL308]']
    assert errors[0].startswith(f"{fixture}:8:7: error: subscription '/parameter_events' from main "
                                'changes the type of the one from base:node '
                                '(rcl_interfaces/msg/ParameterEvent -> std_msgs/msg/String)')
    unknown = nodl('validate', '--resolve', '--client-library', 'rclcppp', fixture)
    assert unknown.returncode == 2 and 'rclcppp' in unknown.stderr


def test_junit_has_one_test_case_per_file() -> None:
    import xml.etree.ElementTree as ElementTree

    warning_only = rel(CLI / 'warning_only.nodl.yaml')
    paths = ['examples/mistakes/typos.yaml', 'examples/camera_lifecycle.nodl.yaml', warning_only,
             'missing.nodl.yaml']
    lenient, strict = nodl('validate', '--format', 'junit', *paths), \
        nodl('validate', '--format', 'junit', '--strict', *paths)
    assert (lenient.returncode, strict.returncode) == (2, 2)  # the missing path
    assert lenient.stderr.endswith('3 files, 7 errors, 1 warning, 1 unreadable path\n')
    for result, failed in ((lenient, ['examples/mistakes/typos.yaml']),
                           (strict, ['examples/mistakes/typos.yaml', warning_only])):
        suite = ElementTree.fromstring(result.stdout)
        cases = {case.get('name'): case for case in suite.iter('testcase')}
        assert list(cases) == paths
        assert [name for name, case in cases.items() if case.find('failure') is not None] == failed
        assert [name for name, case in cases.items() if case.find('error') is not None] == \
            ['missing.nodl.yaml']
        assert (suite.get('tests'), suite.get('failures'), suite.get('errors')) == \
            ('4', str(len(failed)), '1')
    typos = ElementTree.fromstring(lenient.stdout).find("testcase[@name='examples/mistakes/typos.yaml']")
    assert typos is not None
    failure = typos.find('failure')
    assert failure is not None and failure.text is not None
    assert failure.text.splitlines()[0].startswith('examples/mistakes/typos.yaml:4:7: error: ')
    warned = ElementTree.fromstring(lenient.stdout).find(f"testcase[@name='{warning_only}']")
    assert warned is not None and '[NODL216]' in (warned.findtext('system-out') or '')


# --- --types and --package: endpoint types against the installed interfaces ---------------

TYPES = FIXTURES / 'interface_types'


def _typed(*args: str) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, AMENT_PREFIX_PATH=sys.prefix)
    return subprocess.run([sys.executable, '-m', 'nodl', 'validate', *args], cwd=REPO,
                          text=True, capture_output=True, timeout=60, env=env)


def test_types_reports_wrong_types_at_the_type_value() -> None:
    plain = _typed(rel(TYPES / 'wrong_types.nodl.yaml'))
    assert plain.returncode == 0, plain.stdout  # without --types, names are only well-formed
    result = _typed('--types', rel(TYPES / 'wrong_types.nodl.yaml'))
    assert result.returncode == 1
    file = rel(TYPES / 'wrong_types.nodl.yaml')
    assert (f"{file}:4:11: error: 'sensor_msgs/msg/LaserScn': package 'sensor_msgs' defines no "
            "message 'LaserScn'; did you mean 'sensor_msgs/msg/LaserScan'?") in result.stdout
    assert f'{file}:8:11: warning:' in result.stdout and '[NODL253]' in result.stdout
    assert '[NODL205]' not in result.stdout  # the resolved short name replaces the generic warning
    assert result.stdout.rstrip().endswith('1 file, 4 errors, 1 warning')


def test_package_checks_dependencies_and_own_types() -> None:
    result = _typed('--package', rel(TYPES / 'types_pkg'),
                    rel(TYPES / 'types_pkg' / 'nodl' / 'device.nodl.yaml'))
    assert result.returncode == 1
    assert [c for c in ('NODL255', 'NODL256', 'NODL258', 'NODL250') if f'[{c}]' in result.stdout] == [
        'NODL255', 'NODL256', 'NODL258', 'NODL250']
    assert 'Traceback' not in result.stderr
    at_build = _typed('--types-at-build', '--package', rel(TYPES / 'types_pkg'),
                      rel(TYPES / 'types_pkg' / 'nodl' / 'device.nodl.yaml'))
    assert '[NODL257]' in at_build.stdout and '[NODL250]' not in at_build.stdout


def test_package_without_manifest_is_a_usage_error(tmp_path: Path) -> None:
    result = _typed('--package', str(tmp_path), rel(TYPES / 'wrong_types.nodl.yaml'))
    assert result.returncode == 2
    assert 'no package.xml there' in result.stderr


def test_types_reports_a_malformed_installed_file_once_at_its_line() -> None:
    prefix = TYPES / 'bad_prefix'
    env = dict(os.environ, AMENT_PREFIX_PATH=f'{prefix}{os.pathsep}{sys.prefix}')
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--types',
                             rel(TYPES / 'bad_installed.nodl.yaml')], cwd=REPO, text=True,
                            capture_output=True, timeout=60, env=env)
    assert result.returncode == 1 and 'Traceback' not in result.stderr
    reading = prefix / 'share' / 'bad_msgs' / 'msg' / 'Reading.msg'
    assert result.stdout.count('[NODL258]') == 1, result.stdout
    assert f"{reading}:3:1: error: 'bad_msgs/msg/Reading' cannot be read: " in result.stdout
    # where the definition names it (the other type: values are related locations)
    assert f"(named by {rel(TYPES / 'bad_installed.nodl.yaml')}:7:13 and 2 more)" in result.stdout
