"""The $(...) grammar of the launch frontends: structure, quoting, escapes, nesting, and
coded errors with the character position (nodl.launch.substitution_grammar)."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl.launch import load_launch
from nodl.launch.errors import LaunchProblem
from nodl.launch.substitution_grammar import SUBSTITUTIONS, parse_substitution
from nodl.launch.substitutions import (
    EnvironmentVariable,
    LaunchConfiguration,
    PythonExpression,
    TextSubstitution,
    ThisLaunchFileDir,
)


def test_text_and_substitutions_alternate() -> None:
    parts = parse_substitution('a$(dirname)/b')
    assert [type(p) for p in parts] == [TextSubstitution, ThisLaunchFileDir, TextSubstitution]
    assert (parts[0].text, parts[2].text) == ('a', '/b')  # type: ignore[attr-defined]


def test_quoted_arguments_keep_spaces_and_nest() -> None:
    (text, env) = parse_substitution('x $(env "A B" d)')
    assert isinstance(env, EnvironmentVariable) and text.text == 'x '  # type: ignore[attr-defined]
    assert [s.text for s in env.name] == ['A B']  # type: ignore[attr-defined]
    (outer,) = parse_substitution('$(var $(var n))')
    assert isinstance(outer, LaunchConfiguration) and isinstance(outer.variable_name[0], LaunchConfiguration)
    (expression,) = parse_substitution('$(eval "1 + 2")')
    assert isinstance(expression, PythonExpression)


def test_an_escaped_dollar_is_text() -> None:
    assert [p.text for p in parse_substitution('\\$(var a)')] == ['$(var a)']  # type: ignore[attr-defined]
    assert [p.text for p in parse_substitution('plain')] == ['plain']  # type: ignore[attr-defined]


@pytest.mark.parametrize('text, code, words', [
    ('$(var a', 'NODL510', "at character 1: '$(var' is not closed with ')'"),
    ('$( var a)', 'NODL510', "at character 3: expected a substitution name after '$('"),
    ("$(var 'a", 'NODL510', "at character 7: unterminated '-quoted argument"),
    ('$(var)', 'NODL510', '$(var) takes 1 to 2 argument(s), got 0'),
    ('$(var a b c)', 'NODL510', 'got 3'),
    ('$(not)', 'NODL510', '$(not) takes 1 argument(s)'),
    ('$(vra a)', 'NODL509', "unknown substitution '$(vra)'; did you mean 'var'?"),
    ('$(var ' * 60 + 'a' + ')' * 60, 'NODL510', 'nest deeper than 50'),
])
def test_bad_syntax_is_coded_with_its_position(text: str, code: str, words: str) -> None:
    with pytest.raises(LaunchProblem) as caught:
        parse_substitution(text)
    assert caught.value.code == code and words in caught.value.message


def test_a_bad_substitution_is_placed_at_its_attribute(tmp_path: Path) -> None:
    main = tmp_path / 'm.launch.xml'
    main.write_text('<launch>\n  <node pkg="p"\n        exec="$(var a"/>\n</launch>\n')
    (problem,) = load_launch(main, {}).diagnostics
    assert (problem.code, problem.file, problem.line, problem.column) == ('NODL510', str(main), 3, 9)


def test_the_table_holds_every_frontend_substitution() -> None:
    for name in ('var', 'env', 'find-pkg-share', 'find-pkg-prefix', 'eval', 'dirname', 'anon', 'not',
                 'and', 'or', 'equals', 'if', 'command', 'param'):
        assert name in SUBSTITUTIONS
