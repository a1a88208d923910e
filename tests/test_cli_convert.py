"""`nodl convert`: run as a real process, as users run it."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from conftest import FIXTURES, REPO
from nodl.writing import unmark

LEGACY = FIXTURES / 'legacy'


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                          capture_output=True, timeout=60)


def rel(path: Path) -> str:
    return os.path.relpath(path, REPO)


def test_converts_and_exits_0_with_warnings(tmp_path: Path, golden) -> None:
    result = nodl('convert', rel(LEGACY / 'qos_child.nodl.xml'), '-o', str(tmp_path))
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stderr == ''
    assert sorted(p.name for p in tmp_path.iterdir()) == ['first.nodl.yaml', 'second.nodl.yaml']
    golden.check(result.stdout.replace(str(tmp_path), 'OUT'),
                 LEGACY / 'expected' / 'cli' / 'qos_child.stdout')
    for name in ('first.nodl.yaml', 'second.nodl.yaml'):
        assert (tmp_path / name).read_text(encoding='utf-8') == \
            (LEGACY / 'expected' / 'qos_child' / name).read_text(encoding='utf-8')


def test_diagnostics_are_file_line_col_lines(tmp_path: Path) -> None:
    result = nodl('convert', rel(LEGACY / 'qos_child.nodl.xml'), '-o', str(tmp_path))
    lines = [line for line in result.stdout.splitlines() if ': warning: ' in line]
    assert lines[0].startswith(f'{rel(LEGACY / "qos_child.nodl.xml")}:2:9: warning: node name')
    assert f'{rel(LEGACY / "qos_child.nodl.xml")}:27:7: warning: <qos> of action' in result.stdout


def test_written_files_are_listed_and_valid(tmp_path: Path) -> None:
    result = nodl('convert', rel(LEGACY / 'role_both.nodl.xml'), rel(LEGACY / 'warnings.nodl.xml'),
                  '-o', str(tmp_path / 'new' / 'dir'))
    assert result.returncode == 0, result.stdout
    assert f'wrote {tmp_path / "new" / "dir" / "relay.nodl.yaml"}' in result.stdout
    assert f'wrote {tmp_path / "new" / "dir" / "talker.nodl.yaml"}' in result.stdout
    assert result.stdout.rstrip().splitlines()[-1] == \
        '2 files read, 2 node definitions written, 0 errors, 8 warnings'
    # The written files pass even --strict: their header silences 'has no description'
    # (legacy NoDL has no descriptions), see docs/diagnostics.md.
    check = nodl('validate', '--strict', str(tmp_path / 'new' / 'dir'))
    assert check.returncode == 0, check.stdout
    assert ' 0 errors, 0 warnings' in check.stdout


def test_structural_errors_exit_1_and_write_nothing(tmp_path: Path) -> None:
    path = rel(LEGACY / 'errors' / 'structural.nodl.xml')
    result = nodl('convert', path, '-o', str(tmp_path / 'out'))
    assert result.returncode == 1
    assert 'Traceback' not in result.stdout + result.stderr
    assert f"{path}:3:5: error: <parameter> has no 'type' attribute" in result.stdout
    assert f'{path}:10:49: error: role="publisher" conflicts with subscription="true"' in result.stdout
    assert f'{path}: not converted (nothing written)' in result.stdout
    assert not (tmp_path / 'out').exists()
    assert result.stdout.rstrip().endswith('1 file read, 0 node definitions written, 21 errors, '
                                           '1 warning')


def test_v2_errors_exit_1(tmp_path: Path) -> None:
    path = rel(LEGACY / 'invalid_v2.nodl.xml')
    result = nodl('convert', path, '-o', str(tmp_path))
    assert result.returncode == 1
    assert f"{path}:3:12: error: not valid in NoDL v2: invalid ROS name 'bad name'" in result.stdout
    assert list(tmp_path.iterdir()) == []


def test_xml_bomb_is_rejected_quickly(tmp_path: Path) -> None:
    path = rel(LEGACY / 'errors' / 'billion_laughs.nodl.xml')
    result = nodl('convert', path, '-o', str(tmp_path))
    assert result.returncode == 1
    assert f'{path}:2:1: error: document type declarations (<!DOCTYPE ...>) are not allowed' \
        in result.stdout


def test_not_utf8_is_an_invalid_document(tmp_path: Path) -> None:
    path = rel(LEGACY / 'errors' / 'latin1.nodl.xml')
    result = nodl('convert', path, '-o', str(tmp_path))
    assert result.returncode == 1
    assert f'{path}:2:18: error: document is not valid UTF-8' in result.stdout


def test_package_xml(tmp_path: Path) -> None:
    result = nodl('convert', rel(LEGACY / 'package' / 'package.xml'), '-o', str(tmp_path))
    assert result.returncode == 0, result.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ['listener.nodl.yaml', 'talker.nodl.yaml']
    talker = unmark((tmp_path / 'talker.nodl.yaml').read_text(encoding='utf-8'))
    assert talker.startswith(f'# Converted from {rel(LEGACY / "package" / "interfaces" / "talker.nodl.xml")}')


def test_package_xml_without_export_exits_1(tmp_path: Path) -> None:
    path = rel(LEGACY / 'package_no_export' / 'package.xml')
    result = nodl('convert', path, '-o', str(tmp_path))
    assert result.returncode == 1
    assert f'{path}:8:3: error: package.xml exports no interface file' in result.stdout


def test_unreadable_input_exits_2_but_the_others_are_converted(tmp_path: Path) -> None:
    result = nodl('convert', 'does/not/exist.nodl.xml', rel(LEGACY / 'role_both.nodl.xml'),
                  '-o', str(tmp_path))
    assert result.returncode == 2
    assert 'does/not/exist.nodl.xml: error: no such file or directory' in result.stderr
    assert (tmp_path / 'relay.nodl.yaml').is_file()
    assert 'Traceback' not in result.stderr


def test_unwritable_output_exits_2(tmp_path: Path) -> None:
    blocker = tmp_path / 'blocker'
    blocker.write_text('a file, not a directory')
    result = nodl('convert', rel(LEGACY / 'role_both.nodl.xml'), '-o', str(blocker))
    assert result.returncode == 2
    assert 'cannot write' in result.stderr
    assert 'Traceback' not in result.stderr


def test_missing_output_dir_is_a_usage_error() -> None:
    result = nodl('convert', rel(LEGACY / 'role_both.nodl.xml'))
    assert result.returncode == 2
    assert 'the following arguments are required: -o/--output-dir' in result.stderr
    assert 'Traceback' not in result.stderr


def test_two_inputs_converting_to_the_same_file_exit_1(tmp_path: Path) -> None:
    result = nodl('convert', rel(LEGACY / 'boolean_attributes.nodl.xml'),
                  rel(LEGACY / 'role_attributes.nodl.xml'), '-o', str(tmp_path))
    assert result.returncode == 1
    assert 'would be written twice' in result.stdout
    assert f'{rel(LEGACY / "role_attributes.nodl.xml")}: not converted' in result.stdout


def test_convert_is_a_registered_verb() -> None:
    result = nodl('--help')
    assert result.returncode == 0
    assert 'convert' in result.stdout
    assert 'Convert legacy NoDL XML' in result.stdout


# -- dialects: the include dialect and generate_parameter_library ---------------------------

DIALECTS = FIXTURES / 'dialects'


def test_converts_an_include_document_to_base_mixins_and_main(tmp_path: Path) -> None:
    import shutil

    import yaml

    package = tmp_path / 'arm_driver'
    shutil.copytree(DIALECTS / 'include' / 'arm_driver', package)
    out_dir = package / 'nodl' / 'v2'
    result = nodl('convert', str(package / 'nodl' / 'arm_driver.nodl.yaml'), '-o', str(out_dir))
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.rstrip().endswith('1 file read, 1 node definition written, 0 errors, '
                                           '0 warnings')
    data = yaml.safe_load((out_dir / 'arm_driver.nodl.yaml').read_text())
    assert data['base'] == 'node'
    # local:// paths stay correct relative to where the file is written.
    assert data['mixins'] == ['nodl://arm_common/heartbeat', '../shared/joint_limits.nodl.yaml']
    assert 'include' not in data
    # The codegen block is kept, as the node's codegen.
    assert data['codegen'] == {'cpp': {'class': 'ArmDriverBase',
                                       'header': 'arm_driver/arm_driver_base.hpp'}}
    env = dict(os.environ, AMENT_PREFIX_PATH=str(DIALECTS / 'include' / 'prefix'))
    again = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--resolve',
                            str(out_dir / 'arm_driver.nodl.yaml')], cwd=REPO, text=True,
                           capture_output=True, timeout=60, env=env)
    assert again.returncode == 0, again.stdout + again.stderr
    assert 'warning:' not in again.stdout  # no dialect warning any more


def test_converts_a_genparamlib_file_by_content_and_with_from(tmp_path: Path) -> None:
    source = rel(DIALECTS / 'genparamlib' / 'gripper_controller.yaml')
    for extra in ((), ('--from', 'genparamlib')):
        result = nodl('convert', source, '-o', str(tmp_path), *extra)
        assert result.returncode == 0, result.stdout + result.stderr
        assert 'warning: 2 parameter(s) under __map_ segments' in result.stdout
        assert result.stdout.count('warning:') == 1
        assert '1 interface definition written' in result.stdout
    text = (tmp_path / 'gripper_controller.nodl.yaml').read_text()
    assert text.startswith('# nodl: generated; sha256=')
    assert unmark(text).startswith('# Converted by nodl convert from gripper_controller.yaml')
    assert 'malformed XML' not in text


def test_convert_with_a_wrong_from_says_what_the_file_is(tmp_path: Path) -> None:
    result = nodl('convert', rel(DIALECTS / 'genparamlib' / 'gripper_controller.yaml'),
                  '--from', 'include', '-o', str(tmp_path))
    assert result.returncode == 1
    assert 'looks like a generate_parameter_library parameter file' in result.stdout
    assert list(tmp_path.iterdir()) == []


def test_convert_refuses_a_v2_file_politely(tmp_path: Path) -> None:
    result = nodl('convert', 'examples/laser_driver.nodl.yaml', '-o', str(tmp_path))
    assert result.returncode == 1
    assert 'already a NoDL v2 node definition' in result.stdout


def test_converting_an_include_document_out_of_its_package_warns_at_the_local_include(
        tmp_path: Path) -> None:
    source = DIALECTS / 'include' / 'arm_driver' / 'nodl' / 'arm_driver.nodl.yaml'
    result = nodl('convert', str(source), '-o', str(tmp_path / 'elsewhere'))
    assert result.returncode == 0, result.stdout + result.stderr  # written, with a warning
    [warning] = [line for line in result.stdout.splitlines() if ': warning: ' in line]
    # at the local:// include (line 8), not at nodl://arm_common/heartbeat
    assert warning.startswith(f'{source}:8:') and warning.endswith('[NODL854]')
    assert 'cannot use this local include' in warning


def test_a_users_file_is_never_replaced_without_force(tmp_path: Path) -> None:
    mine = tmp_path / 'first.nodl.yaml'
    mine.write_text('# my own definition\n', encoding='utf-8')
    refused = nodl('convert', rel(LEGACY / 'qos_child.nodl.xml'), '-o', str(tmp_path))
    assert refused.returncode == 2 and 'Traceback' not in refused.stderr
    assert refused.stderr == (f'{mine}: error: the file was not written by nodl (it has no nodl '
                              'marker): not replaced; give another output path, or --force to '
                              'replace it [NODL031]\n')
    assert mine.read_text(encoding='utf-8') == '# my own definition\n'
    assert not (tmp_path / 'second.nodl.yaml').exists()  # nothing of that input is written
    forced = nodl('convert', rel(LEGACY / 'qos_child.nodl.xml'), '-o', str(tmp_path), '--force')
    assert forced.returncode == 0, forced.stdout + forced.stderr
    assert (tmp_path / 'second.nodl.yaml').is_file()
    assert mine.read_text(encoding='utf-8') == (
        LEGACY / 'expected' / 'qos_child' / 'first.nodl.yaml').read_text(encoding='utf-8')


def test_an_input_is_never_an_output(tmp_path: Path) -> None:
    source = FIXTURES / 'dialects' / 'genparamlib' / 'gripper_controller.yaml'
    inputs = tmp_path / 'in'
    inputs.mkdir()
    include = tmp_path / 'gripper_controller.nodl.yaml'  # what the genparamlib input converts to
    include.write_text('# nodl: generated; sha256=' + '0' * 64 + '\n', encoding='utf-8')
    copy = inputs / 'gripper_controller.yaml'
    copy.write_bytes(source.read_bytes())
    result = nodl('convert', str(copy), str(include), '-o', str(tmp_path), '--force')
    assert result.returncode == 2
    assert f'{include}: error: -o names an input of the command ({include})' in result.stderr
    assert '[NODL033]' in result.stderr and 'Traceback' not in result.stderr
    assert include.read_text(encoding='utf-8') == '# nodl: generated; sha256=' + '0' * 64 + '\n'


def test_json_and_junit_report_each_input_through_the_reporters(tmp_path: Path) -> None:
    import json
    import xml.etree.ElementTree as ET

    bad = rel(LEGACY / 'errors' / 'structural.nodl.xml')
    good = rel(LEGACY / 'role_both.nodl.xml')
    result = nodl('convert', good, bad, '-o', str(tmp_path), '--format', 'json')
    assert result.returncode == 1
    inputs = json.loads(result.stdout)  # nothing else on standard output: no 'wrote' lines
    assert [(i['file'], i['converted'], i['written']) for i in inputs] == [
        (good, True, [str(tmp_path / 'relay.nodl.yaml')]), (bad, False, [])]
    assert any(d['severity'] == 'error' for d in inputs[1]['diagnostics'])
    assert result.stderr.startswith('2 files read, 1 node definition written, ')  # apart
    junit = nodl('convert', good, bad, '-o', str(tmp_path / 'again'), '--format', 'junit')
    suite = ET.fromstring(junit.stdout)
    assert [(c.get('name'), c.find('failure') is not None) for c in suite.iter('testcase')] == [
        (good, False), (bad, True)]
