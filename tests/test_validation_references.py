"""Mixin references: nodl.validation.references."""

from __future__ import annotations

from typing import Any

import pytest

from nodl.diagnostics import Diagnostic, Severity
from nodl.validation import Kind, validate_data
from nodl.validation.references import NODL_SCHEME, check_reference, parse_nodl_uri, reference_problem


@pytest.mark.parametrize(('text', 'parsed'), [
    ('nodl://pkg/name', ('pkg', 'name')),
    ('nodl://my_pkg/diagnostics', ('my_pkg', 'diagnostics')),
    ('nodl://pkg2/Camera-Info.v2', ('pkg2', 'Camera-Info.v2')),
    ('nodl://p/_x', ('p', '_x')),
])
def test_parse_valid_nodl_uris(text: str, parsed: tuple[str, str]) -> None:
    assert parse_nodl_uri(text) == parsed
    assert reference_problem(text) is None


@pytest.mark.parametrize('text', [
    'nodl://Bad', 'nodl://pkg', 'nodl://pkg/', 'nodl://Bad/name', 'nodl://1pkg/name',
    'nodl:///name', 'nodl://pkg/a/b', 'nodl://pkg/.hidden', 'nodl://pkg/a b', 'nodl://',
])
def test_malformed_nodl_uris(text: str) -> None:
    assert parse_nodl_uri(text) is None
    assert reference_problem(text) == (
        f"'{text}' is not a valid nodl:// reference; expected nodl://<package>/<name>, for "
        'example nodl://my_pkg/diagnostics')


@pytest.mark.parametrize('text', ['http://pkg/name', 'package://pkg/name', 'pkg/name',
                                  'diag.nodl.yaml'])
def test_parse_nodl_uri_only_parses_the_nodl_scheme(text: str) -> None:
    assert NODL_SCHEME == 'nodl'
    assert parse_nodl_uri(text) is None


@pytest.mark.parametrize('text', [
    'diagnostics.nodl.yaml', './diagnostics.nodl.yaml', '../shared/diagnostics.nodl.yaml',
    'sub/dir/x.nodl.json', 'x',
])
def test_relative_paths_are_accepted(text: str) -> None:
    assert reference_problem(text) is None


@pytest.mark.parametrize('text', [
    'package://my_pkg/nodl/diag.nodl.yaml', 'file:///opt/x.nodl.yaml',
    'https://example.com/x.nodl.yaml', 'git+ssh://host/repo',
])
def test_other_schemes_are_accepted_syntactically(text: str) -> None:
    # Whether they resolve is up to the resolver plugins.
    assert reference_problem(text) is None


@pytest.mark.parametrize('text', ['/abs/diagnostics.nodl.yaml', '/x'])
def test_absolute_paths_are_errors(text: str) -> None:
    assert reference_problem(text) == (
        f"'{text}' is an absolute path; a mixin path is relative to the node file (or use "
        'nodl://<package>/<name>)')


@pytest.mark.parametrize('text', ['', '   ', '\t'])
def test_empty_references(text: str) -> None:
    assert reference_problem(text) == 'a mixin reference must not be empty'


@pytest.mark.parametrize(('value', 'shown'), [(3, 'an integer (3)'), (None, 'null'),
                                              (True, 'a boolean (true)')])
def test_check_reference_of_a_non_string(value: Any, shown: str) -> None:
    out: list[Diagnostic] = []
    check_reference(value, ('mixins', 0), out)
    assert [(d.severity, d.path, d.message) for d in out] == [
        (Severity.ERROR, ('mixins', 0),
         f'a mixin must be a reference or an interface definition, not {shown}')]


def test_check_reference_reports_at_the_item() -> None:
    out: list[Diagnostic] = []
    check_reference('nodl://pkg', ('mixins', 4), out)
    assert [(d.severity, d.path, d.anchor) for d in out] == [(Severity.ERROR, ('mixins', 4),
                                                              'value')]
    out = []
    check_reference('nodl://pkg/name', ('mixins', 4), out)
    assert out == []


def _node(mixins: list) -> dict:
    return {'nodl_version': 2, 'main': {'nodl_version': 2}, 'mixins': mixins}


def test_references_in_a_node() -> None:
    found = validate_data(_node(['nodl://pkg/a', 'x.nodl.yaml', 'nodl://Bad', '/abs', '']),
                          Kind.NODE)
    assert [(d.severity, d.path) for d in found] == [
        (Severity.ERROR, ('mixins', 2)), (Severity.ERROR, ('mixins', 3)),
        (Severity.ERROR, ('mixins', 4))]


def test_a_reference_listed_twice_is_a_warning() -> None:
    found = validate_data(_node(['a.nodl.yaml', 'nodl://p/b', 'a.nodl.yaml', 'a.nodl.yaml']),
                          Kind.NODE)
    assert [(d.severity, d.path, d.message) for d in found] == [
        (Severity.WARNING, ('mixins', 2),
         "mixin 'a.nodl.yaml' is listed twice (first as mixins[0])"),
        (Severity.WARNING, ('mixins', 3),
         "mixin 'a.nodl.yaml' is listed twice (first as mixins[0])")]
