"""Arguments checked at once, before any ROS start-up (nodl.cli.arguments)."""

from __future__ import annotations

import argparse
import subprocess
import sys
import time

import pytest

from conftest import FIXTURES, REPO
from nodl.cli.arguments import definition_problem, launch_arguments, node_name, seconds, usage_error

SCAN = FIXTURES / 'scan'


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                          capture_output=True, timeout=60)


def test_seconds() -> None:
    assert seconds('0') == 0.0 and seconds('2.5') == 2.5
    for bad in ('-1', 'nan', 'inf', 'soon'):
        with pytest.raises(argparse.ArgumentTypeError):
            seconds(bad)


def test_node_names() -> None:
    assert node_name('/robot/driver') == '/robot/driver' and node_name('talker') == 'talker'
    for bad in ('/robot/1driver', '/a b', '~/x', '/', '/a/', ''):
        with pytest.raises(argparse.ArgumentTypeError):
            node_name(bad)


def test_definition_targets() -> None:
    assert definition_problem(['a.nodl.yaml']) is None
    assert definition_problem(['my_pkg', 'my_node']) is None
    assert 'is a file' in (definition_problem(['a.nodl.yaml', 'b.nodl.yaml']) or '')
    assert 'got 3 arguments' in (definition_problem(['a', 'b', 'c']) or '')


@pytest.mark.parametrize('args, message', [
    (['describe', '/robot/1driver'], "is not a node name: token '1driver' starts with a digit"),
    (['describe', '--timeout', '-1', '/robot/driver'], 'expected a number of seconds, 0 or more'),
    (['check', '/a b', str(SCAN / 'valid.nodl.yaml')], "'/a b' is not a node name"),
    (['check', '--timeout', '-3', '/x', str(SCAN / 'valid.nodl.yaml')], 'number of seconds'),
])
def test_bad_names_and_timeouts_exit_2_at_once(args: list[str], message: str) -> None:
    start = time.monotonic()
    result = nodl(*args)
    assert result.returncode == 2 and message in result.stderr, result.stderr
    assert time.monotonic() - start < 15  # rejected before any ROS start-up or waiting


@pytest.mark.parametrize('verb', [['show'], ['check', '/x']])
def test_two_files_say_what_is_accepted(verb: list[str]) -> None:
    result = nodl(*verb, str(SCAN / 'valid.nodl.yaml'), str(SCAN / 'invalid.nodl.yaml'))
    assert result.returncode == 2
    assert 'is a file, so one is expected: give FILE, or PACKAGE EXECUTABLE' in result.stderr
    assert 'not registered' not in result.stderr


def test_launch_limits_are_positive_numbers() -> None:
    from nodl.cli.arguments import mebibytes, positive_seconds

    assert positive_seconds('0.5') == 0.5 and mebibytes('512') == 512.0
    for bad in ('0', '-1', 'nan', 'inf', 'soon'):
        for check in (positive_seconds, mebibytes):
            with pytest.raises(argparse.ArgumentTypeError):
                check(bad)


@pytest.mark.parametrize('verb', [['analyse', 'x.launch.py'], ['policy', 'x.launch.py'],
                                  ['params', 'check', 'p.yaml', '--launch', 'x.launch.py']])
@pytest.mark.parametrize('option, message', [
    (['--launch-timeout', '0'], "argument --launch-timeout: '0': expected a number of seconds greater than 0"),
    (['--launch-memory', 'lots'], "argument --launch-memory: 'lots' is not a number of MiB"),
])
def test_bad_launch_limits_exit_2_in_one_line(verb: list[str], option: list[str], message: str) -> None:
    result = nodl(*verb, *option)
    assert result.returncode == 2 and result.stderr.rstrip().splitlines()[-1].endswith(message), result.stderr
    assert 'Traceback' not in result.stderr


def test_launch_arguments_are_a_mapping_once_the_file_is_read(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    launch = tmp_path / 'a.launch.xml'
    launch.write_text('<launch/>\n')
    assert launch_arguments(str(launch), ['robot:=r1', 'x:=a:=b', 'empty:='], 'nodl x') == {
        'robot': 'r1', 'x': 'a:=b', 'empty': ''}
    assert launch_arguments(str(launch), ['robot=r1'], 'nodl x') == 2
    assert capsys.readouterr().err == "nodl x: error: launch argument 'robot=r1' is not NAME:=VALUE\n"
    assert launch_arguments(str(tmp_path), [':=v'], 'nodl x') == 2  # the argument is said first
    assert 'is not NAME:=VALUE' in capsys.readouterr().err
    assert launch_arguments(str(tmp_path), [], 'nodl x') == 2
    assert capsys.readouterr().err == f'{tmp_path}: error: cannot read the launch file: is a directory [NODL020]\n'


def test_usage_error_says_what_was_refused_in_words(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    assert usage_error('nodl x', ValueError('give a definition FILE')) == 2
    assert capsys.readouterr().err == 'nodl x: error: give a definition FILE\n'
    missing = FileNotFoundError(2, 'No such file or directory', str(tmp_path / 'missing.yaml'))
    assert usage_error('nodl x', missing) == 2
    assert capsys.readouterr().err == 'nodl x: error: No such file or directory\n'  # no [Errno 2]
