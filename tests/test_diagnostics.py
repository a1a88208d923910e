"""Diagnostics and ValidationError (nodl.diagnostics)."""

from __future__ import annotations

import pytest

from nodl.diagnostics import Diagnostic, Severity, ValidationError, format_path


def test_paths_are_dotted_with_indices_and_quoted_odd_keys() -> None:
    assert format_path(('main', 'parameters', 'gain', 'default_value')) == \
        'main.parameters.gain.default_value'
    assert format_path(('publishers', 2, 'qos')) == 'publishers[2].qos'
    assert format_path(('parameters', 'pid.kp')) == 'parameters["pid.kp"]'
    assert format_path(('validation', 'bounds<>')) == 'validation.bounds<>'
    assert format_path(()) == ''


def test_str_is_file_line_col_severity_message() -> None:
    d = Diagnostic(Severity.ERROR, 'boom', ('a',), 'f.yaml', 3, 7)
    assert str(d) == 'f.yaml:3:7: error: boom [a]'
    assert str(Diagnostic(Severity.WARNING, 'w', (), 'f.yaml')) == 'f.yaml: warning: w'


def test_diagnostics_are_immutable_values() -> None:
    d = Diagnostic(Severity.INFO, 'x')
    with pytest.raises(AttributeError):
        d.line = 3  # type: ignore[misc]
    assert d.at('f', 1, 2) == Diagnostic(Severity.INFO, 'x', (), 'f', 1, 2)
    assert d.at('f', 1, 2) != d
    assert len({d, d.replace()}) == 1


def test_validation_error_carries_all_diagnostics_and_prints_errors() -> None:
    err = Diagnostic(Severity.ERROR, 'e1', (), 'f', 1, 1)
    warn = Diagnostic(Severity.WARNING, 'w1', (), 'f', 2, 1)
    exc = ValidationError([err, warn])
    assert exc.diagnostics == [err, warn]
    assert exc.errors == [err]
    assert str(exc) == 'f:1:1: error: e1'
    assert isinstance(exc, ValueError)


def test_code_ends_the_line_and_related_locations_are_in_the_dict() -> None:
    d = Diagnostic(Severity.INFO, 'overrides', ('a',), 'f.yaml', 3, 7, code='NODL304',
                   related=[('g.yaml', 1, 2, 'the overridden one')])
    assert str(d) == 'f.yaml:3:7: info: overrides [a] [NODL304]'
    assert d.to_dict()['code'] == 'NODL304'
    assert d.to_dict()['related'] == [{'file': 'g.yaml', 'line': 1, 'column': 2,
                                       'message': 'the overridden one'}]
    assert d.replace(code='NODL101') != d


def test_a_diagnosed_result_says_its_errors_and_whether_it_is_ok() -> None:
    from nodl.diagnostics import Diagnosed, Diagnostic, Severity

    class Result(Diagnosed):
        __slots__ = ('diagnostics',)

        def __init__(self, diagnostics: list[Diagnostic]) -> None:
            self.diagnostics = diagnostics

    warning = Diagnostic(Severity.WARNING, 'w', (), 'f', 1, 1)
    error = Diagnostic(Severity.ERROR, 'e', (), 'f', 2, 1)
    assert Result([warning]).ok and Result([warning]).errors == []
    assert not Result([warning, error]).ok and Result([warning, error]).errors == [error]


def test_a_diagnostic_pickles_to_an_equal_one() -> None:
    """A launch read in the sandbox child sends its diagnostics back pickled."""
    import pickle

    from nodl.diagnostics import Diagnostic, Severity

    diagnostic = Diagnostic(Severity.WARNING, 'm', ('a', 0), 'f.launch.py', 3, 4, anchor='key',
                            code='NODL513', related=(('g', 1, 2, 'there'),))
    assert pickle.loads(pickle.dumps(diagnostic)) == diagnostic
