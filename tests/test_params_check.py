"""nodl params: defaults written as a parameter file, and parameter files checked without ROS."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import yaml

from nodl.params import check_parameter_files, defaults_yaml
from nodl.targets import resolve_target

FIXTURES = Path(__file__).parent / 'fixtures'
EVERYTHING = str(FIXTURES / 'generate' / 'everything.nodl.yaml')
REPO = Path(__file__).resolve().parent.parent


def _node(path: str = EVERYTHING):  # type: ignore[no-untyped-def]
    node = resolve_target(path).node
    assert node is not None
    return node


def _codes(diagnostics):  # type: ignore[no-untyped-def]
    return [(d.code, d.line, d.column) for d in diagnostics]


def test_bad_file_every_problem_at_its_place() -> None:
    bad = str(FIXTURES / 'params' / 'bad.params.yaml')
    found = check_parameter_files([bad], _node(), '/everything')
    by_line = {d.line: d for d in found if d.file == bad}
    assert by_line[4].code == 'NODL701' and by_line[4].severity.value == 'warning'  # under /**
    assert by_line[7].code == 'NODL703' and 'must be between 0 and 10' in by_line[7].message
    assert by_line[8].code == 'NODL702' and 'expected double, got integer' in by_line[8].message
    assert by_line[9].code == 'NODL703' and "must be one of 'fast' or 'slow'" in by_line[9].message
    assert by_line[10].code == 'NODL701' and "did you mean 'count'?" in by_line[10].message
    assert by_line[11].code == 'NODL703'
    assert (by_line[13].code, by_line[13].column) == ('NODL702', 7)  # nested group.label
    assert by_line[14].code == 'NODL702' and 'at most 3' in by_line[14].message
    assert 18 not in by_line  # /other_node does not apply
    required = [d for d in found if d.code == 'NODL704']
    assert len(required) == 1 and required[0].file == EVERYTHING and 'required_scale' in required[0].message
    assert all(d.related for d in found if d.code in ('NODL702', 'NODL703'))


def test_wildcards_match_as_rcl_matches() -> None:
    good = str(FIXTURES / 'params' / 'good.params.yaml')
    assert check_parameter_files([good], _node(), '/ns/everything') == []
    # /ns/* matches one token only: /ns/deeper/everything gets /** (required_scale) but not count
    deeper = check_parameter_files([good], _node(), '/ns/deeper/everything')
    assert deeper == []
    nothing = check_parameter_files([good], _node(str(FIXTURES / 'generate' / 'talker.nodl.yaml')), '/x')
    # /** applies; talker declares no required_scale: a warning only (the key serves other nodes too)
    assert [(d.code, d.severity.value) for d in nothing] == [('NODL701', 'warning')]
    unmatched = check_parameter_files([str(FIXTURES / 'params' / 'bad.params.yaml')],
                                      _node(str(FIXTURES / 'generate' / 'talker.nodl.yaml')), '/talker')
    assert 'NODL701' in [d.code for d in unmatched]


def test_defaults_file_round_trips_through_the_check(tmp_path: Path) -> None:
    text = defaults_yaml(_node(), '/ns/everything')
    data = yaml.safe_load(text)
    params = data['/ns/everything']['ros__parameters']
    assert params['limit']['lt_eq'] == 1.0 and isinstance(params['limit']['lt_eq'], float)
    assert params['group']['inner']['depth'] == 2
    assert 'required_scale' not in params and '# required_scale: required (double)' in text
    path = tmp_path / 'defaults.yaml'
    path.write_text(text)
    found = check_parameter_files([str(path)], _node(), '/ns/everything')
    assert [d.code for d in found] == ['NODL704']  # only the required parameter is missing


def test_cli(tmp_path: Path) -> None:
    out = tmp_path / 'p.yaml'
    run = subprocess.run([sys.executable, '-m', 'nodl', 'params', EVERYTHING, '--name', '/a/b',
                          '-o', str(out)], capture_output=True, text=True, timeout=60, cwd=REPO)
    assert run.returncode == 0, run.stderr
    assert '/a/b' in yaml.safe_load(out.read_text())
    check = subprocess.run([sys.executable, '-m', 'nodl', 'params', 'check',
                            str(FIXTURES / 'params' / 'bad.params.yaml'), '--definition', EVERYTHING],
                           capture_output=True, text=True, timeout=60, cwd=REPO)
    assert check.returncode == 1
    assert f'{FIXTURES / "params" / "bad.params.yaml"}:8:5: error: ' in check.stdout
    assert '[NODL702]' in check.stdout and 'Traceback' not in check.stderr
    usage = subprocess.run([sys.executable, '-m', 'nodl', 'params', 'check', str(out)],
                           capture_output=True, text=True, timeout=60, cwd=REPO)
    assert usage.returncode == 2 and 'exactly one of --definition and --launch' in usage.stderr


def test_launch_nodes_get_the_files_under_their_final_names(tmp_path: Path) -> None:
    from nodl.params import check_launch_parameters

    launch = FIXTURES / 'analysis' / 'launch' / 'system.launch.xml'
    prefixes = [str(FIXTURES / 'analysis' / 'prefix')]
    params = tmp_path / 'robot.yaml'
    params.write_text('/rover/imu:\n  ros__parameters:\n    gain: 1\n    gian: 0.5\n'
                      '/rover/planner:\n  ros__parameters:\n    speed: 1.0\n')
    found = check_launch_parameters(str(launch), [str(params)], prefixes=prefixes)
    codes = sorted((d.code, d.line) for d in found if d.file == str(params))
    assert ('NODL702', 3) in codes  # an integer for the double gain of /rover/imu
    assert ('NODL701', 4) in codes  # gian: did you mean gain
    assert all(d.code != 'NODL705' for d in found)
    empty = tmp_path / 'empty.launch.xml'
    empty.write_text('<launch/>\n')
    assert [d.code for d in check_launch_parameters(str(empty), [str(params)], prefixes=prefixes)] == ['NODL706']


def test_cli_launch_and_a_file_no_key_of_which_applies(tmp_path: Path) -> None:
    import os

    params = tmp_path / 'robot.yaml'
    params.write_text('/rover/imu:\n  ros__parameters:\n    gain: 1\n    gian: 0.5\n')
    env = {**os.environ, 'AMENT_PREFIX_PATH': str(FIXTURES / 'analysis' / 'prefix')}
    launch = subprocess.run([sys.executable, '-m', 'nodl', 'params', 'check', str(params), '--launch',
                             str(FIXTURES / 'analysis' / 'launch' / 'system.launch.xml')],
                            capture_output=True, text=True, timeout=120, cwd=REPO, env=env)
    assert launch.returncode == 1, launch.stdout + launch.stderr
    assert f'{params}:3:5: error: ' in launch.stdout and '[NODL702]' in launch.stdout
    assert f"{params}:4:5: error: /rover/imu does not declare a parameter 'gian'" in launch.stdout
    other = tmp_path / 'other.yaml'
    other.write_text('/other:\n  ros__parameters:\n    count: 3\n')
    talker = str(FIXTURES / 'generate' / 'talker.nodl.yaml')
    unmatched = subprocess.run([sys.executable, '-m', 'nodl', 'params', 'check', str(other),
                                '--definition', talker, '--name', '/talker'],
                               capture_output=True, text=True, timeout=60, cwd=REPO)
    assert unmatched.returncode == 0  # a warning: the file may be meant for other nodes
    assert f'{other}:1:1: warning: no node key of the parameter file(s) applies to /talker' in unmatched.stdout
    assert '[NODL705]' in unmatched.stdout


def test_an_empty_list_leaves_a_statically_typed_array_unset(tmp_path: Path) -> None:
    # rcl reads '[]' in a parameter file as no value: a real rclpy node declaring the
    # parameter with a default then raises ParameterUninitializedException when it reads it
    # (what the launch analysis reports for the same value, NODL561).
    params = tmp_path / 'empty.params.yaml'
    params.write_text('/**:\n  ros__parameters:\n    required_scale: 1.0\n    doubles: []\n')
    found = check_parameter_files([str(params)], _node(), '/everything')
    assert _codes(found) == [('NODL703', 4, 5)]
    assert 'unset' in found[0].message and found[0].related


def test_no_exec_reads_no_python_launch_file(tmp_path: Path) -> None:
    from nodl.launch.sandbox import LaunchLimits
    from nodl.params import check_launch_parameters

    launch = Path(__file__).parent / 'fixtures' / 'launch' / 'sandbox' / 'good.launch.py'
    params = tmp_path / 'p.yaml'
    params.write_text('/talker:\n  ros__parameters: {}\n')
    found = check_launch_parameters(str(launch), [str(params)], limits=LaunchLimits(execute=False))
    assert [(d.code, d.line) for d in found] == [('NODL525', 1)]


# --- YAML rules of a file rcl reads: no aliases, anchors ignored, no merge keys ----------

#: A real rcl: the parameters a node started with ``--params-file FILE`` gets, or why rcl
#: refuses the file (rclpy's init parses the parameter files with rcl_yaml_param_parser).
RCL_READS = '''
import json, sys
import rclpy
from rclpy.node import Node
context = rclpy.Context()
try:
    rclpy.init(args=['node', '--ros-args', '--params-file', sys.argv[1]], context=context)
except Exception as exc:
    print(json.dumps({'refused': str(exc)}))
    raise SystemExit(0)
node = Node('everything', context=context, allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=True)
values = {name: p.value for name, p in node.get_parameters_by_prefix('').items()}
node.destroy_node()
rclpy.shutdown(context=context)
print(json.dumps({'parameters': values}))
'''


def rcl_reads(path: Path) -> dict[str, object]:
    import json

    run = subprocess.run([sys.executable, '-c', RCL_READS, str(path)], capture_output=True,
                         text=True, timeout=60, cwd=REPO)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.splitlines()[-1])  # type: ignore[no-any-return]


def test_an_alias_is_an_error_at_its_place_as_rcl_refuses_the_file() -> None:
    path = FIXTURES / 'params' / 'aliases.params.yaml'
    assert 'Will not support aliasing at line 7' in str(rcl_reads(path)['refused'])
    found = check_parameter_files([str(path)], _node(), '/everything')
    assert [(d.code, d.severity.value, d.line, d.column) for d in found if d.file == str(path)] == [
        ('NODL711', 'warning', 6, 21), ('NODL710', 'error', 7, 11)]
    assert "rcl refuses aliasing ('Will not support aliasing')" in found[1].message
    # rcl reads no value of the file: count 99 is not checked, required_scale is not given
    assert [d.code for d in found if d.file != str(path)] == ['NODL704']


def test_an_anchor_alone_is_a_warning_as_rcl_ignores_it() -> None:
    path = FIXTURES / 'params' / 'anchor_only.params.yaml'
    assert rcl_reads(path)['parameters'] == {
        'gain': 0.25, 'required_scale': 2.0, 'use_sim_time': False,
        'start_type_description_service': True}
    found = check_parameter_files([str(path)], _node(), '/everything')
    assert _codes(found) == [('NODL711', 5, 11)] and found[0].severity.value == 'warning'


def test_a_merge_key_is_an_error_as_rcl_reads_it_as_a_name() -> None:
    path = FIXTURES / 'params' / 'merge_key.params.yaml'
    assert rcl_reads(path)['parameters'] == {
        '<<.count': 7, 'required_scale': 2.0, 'use_sim_time': False,
        'start_type_description_service': True}
    found = check_parameter_files([str(path)], _node(), '/everything')
    assert _codes(found) == [('NODL712', 6, 5), ('NODL701', 6, 10)]
    assert "rcl has no merge keys (it reads '<<' as a parameter name)" in found[0].message


def test_cli_an_alias_fails_the_check(tmp_path: Path) -> None:
    path = FIXTURES / 'params' / 'aliases.params.yaml'
    check = subprocess.run([sys.executable, '-m', 'nodl', 'params', 'check', str(path),
                            '--definition', EVERYTHING], capture_output=True, text=True,
                           timeout=60, cwd=REPO)
    assert check.returncode == 1, check.stdout + check.stderr
    assert f'{path}:7:11: error: YAML alias in a parameter file: rcl refuses aliasing' in check.stdout
    assert '[NODL710]' in check.stdout and 'Traceback' not in check.stderr


FIXED = FIXTURES / 'params' / 'fixed_size'
ARM = str(FIXED / 'prefix' / 'share' / 'robot' / 'nodl' / 'arm.nodl.yaml')


def _check_cli(*args: str) -> subprocess.CompletedProcess[str]:
    done = subprocess.run([sys.executable, '-m', 'nodl', 'params', 'check', *args],
                          capture_output=True, text=True, timeout=60, cwd=REPO)
    assert 'Traceback' not in done.stderr and '[Errno' not in done.stdout + done.stderr
    return done


def test_cli_a_missing_file_is_a_usage_error_said_once() -> None:
    for path, why in ((FIXED / 'no_such.yaml', 'no such file'), (FIXED, 'is a directory')):
        done = _check_cli(str(path), '--definition', ARM, '--name', '/arm')
        assert done.returncode == 2, done.stderr
        assert f'{path}: error: cannot read the parameter file: {why}' in done.stderr
        assert 'NODL705' not in done.stdout + done.stderr  # no "no key applies" on top


def test_cli_an_empty_or_scalar_file_is_said_about_parameter_files() -> None:
    for name, what in (('empty.yaml', 'the parameter file is empty'),
                       ('scalar.yaml', 'the parameter file is a number, not a mapping')):
        done = _check_cli(str(FIXED / name), '--definition', ARM, '--name', '/arm')
        assert done.returncode == 1
        (line,) = done.stdout.splitlines()  # the one problem, no NODL705 on top of it
        assert f'{what}; a parameter file is a mapping NODE: {{ros__parameters: {{NAME: VALUE}}}}' in line
        assert 'NoDL document' not in line and '[NODL517]' in line


def test_cli_success_says_so_in_one_line() -> None:
    done = _check_cli(str(FIXED / 'good.yaml'), '--definition', ARM, '--name', '/arm')
    assert done.returncode == 0, done.stdout
    assert done.stdout == 'nodl params check: 1 parameter file checked: no errors\n'


def test_a_fixed_size_array_with_too_many_elements_says_how_many_fit() -> None:
    (problem,) = check_parameter_files([str(FIXED / 'gains.yaml')], _node(ARM), '/arm')
    assert 'holds 3 elements; at most 2 fit double_array_fixed_2' in problem.message


def test_cli_unsafe_text_fails_the_check() -> None:
    """nodl params check: control and bidi characters in a parameter file are errors at the
    character (exit 1), shown as escapes on the terminal."""
    hostile = FIXTURES / 'launch' / 'text_safety' / 'hostile.params.yaml'
    check = subprocess.run([sys.executable, '-m', 'nodl', 'params', 'check', str(hostile),
                            '--definition', EVERYTHING, '--name', '/listener'],
                           capture_output=True, text=True, timeout=60, cwd=REPO)
    assert check.returncode == 1, check.stderr
    assert f"{hostile}:4:8: error: the parameter name 'la\\u202ebel' holds U+202E" in check.stdout
    assert f'{hostile}:5:14: error: ' in check.stdout and '[NODL221]' in check.stdout
    assert '\u202e' not in check.stdout and '\x1b' not in check.stdout


def _time_check(tmp_path: Path, count: int) -> float:
    import time

    path = tmp_path / f'gains{count}.yaml'
    path.write_text('/gains:\n  ros__parameters:\n    gains: [' + ', '.join(f'{i}.5' for i in range(count))
                    + ']\n    name: x\n')
    node = _node(str(FIXTURES / 'params' / 'gains.nodl.yaml'))
    start = time.perf_counter()
    assert check_parameter_files([str(path)], node, '/gains') == []
    return time.perf_counter() - start


def test_a_long_list_is_checked_in_linear_time(tmp_path: Path) -> None:
    """10 times the elements take about 10 times as long (a quadratic step would take 100
    times): best of two each, a generous bound.  A 1,000,000-element list (9.9 MB, under the
    10 MB file limit) is measured by bench/bench_hostile.py."""
    small = min(_time_check(tmp_path, 5_000) for _ in range(2))
    large = min(_time_check(tmp_path, 50_000) for _ in range(2))
    assert large < 30 * small, (small, large)
