"""Checking many files at once (nodl.checking)."""

from __future__ import annotations

from conftest import FIXTURES
from nodl.checking import check_paths, failed
from nodl.validation.kinds import Kind

CLI = FIXTURES / 'cli'


def test_each_path_gets_a_result_with_placed_diagnostics() -> None:
    results = check_paths([str(CLI / 'invalid_node.nodl.json'), 'missing.yaml'])
    invalid, missing = results
    assert invalid.readable and not missing.readable
    assert missing.problem == 'no such file or directory'
    assert all(d.line > 0 for d in invalid.diagnostics)
    assert failed(invalid, strict=False)


def test_strict_counts_warnings() -> None:
    (result,) = check_paths([str(CLI / 'warning_only.nodl.yaml')])
    assert not failed(result, strict=False)
    assert failed(result, strict=True)


def test_kind_is_enforced() -> None:
    (result,) = check_paths([str(CLI / 'valid_interface.nodl.yaml')], Kind.PARAMETER)
    assert [d.message for d in result.diagnostics] == [
        'expected a parameter definition, but this is an interface definition '
        '(it has nodl_version and no base, main or mixins)']
