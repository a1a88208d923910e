"""`ros2 nodl ...`: the ros2cli command extension, loaded through its entry point.

ros2cli is not published on the Python registry, so this drives the
extension exactly as ros2cli does: load the `ros2cli.command` entry point,
instantiate it, let it add its arguments to a parser, then call main().
"""

from __future__ import annotations

import argparse

import pytest

from conftest import FIXTURES
from nodl.plugins import iter_entry_points


def _command() -> object:
    (spec,) = [e for e in iter_entry_points('ros2cli.command') if e.name == 'nodl']
    return spec.load()()


def _parser(command: object) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog='ros2 nodl')
    command.add_arguments(parser, 'ros2 nodl')  # type: ignore[attr-defined]
    return parser


def test_extension_follows_the_ros2cli_protocol() -> None:
    command = _command()
    assert command.EXTENSION_POINT_VERSION == '0.1'  # type: ignore[attr-defined]
    assert 'NoDL' in type(command).__doc__


def test_same_verbs_as_nodl() -> None:
    from nodl.plugins import load_plugins

    command = _command()
    parser = _parser(command)
    subparsers = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    assert set(subparsers.choices) == set(load_plugins('nodl.verbs'))


def test_validate_through_ros2cli(capsys: pytest.CaptureFixture[str]) -> None:
    command = _command()
    parser = _parser(command)
    good = str(FIXTURES / 'cli' / 'valid_interface.nodl.yaml')
    args = parser.parse_args(['validate', good])
    assert command.main(parser=parser, args=args) == 0  # type: ignore[attr-defined]
    assert 'valid interface definition' in capsys.readouterr().out
    bad = str(FIXTURES / 'cli' / 'invalid_node.nodl.json')
    args = parser.parse_args(['validate', bad])
    assert command.main(parser=parser, args=args) == 1  # type: ignore[attr-defined]
    assert "did you mean 'node'?" in capsys.readouterr().out


def test_no_verb_prints_help(capsys: pytest.CaptureFixture[str]) -> None:
    command = _command()
    parser = _parser(command)
    assert command.main(parser=parser, args=parser.parse_args([])) == 2  # type: ignore[attr-defined]
    assert 'validate' in capsys.readouterr().out
