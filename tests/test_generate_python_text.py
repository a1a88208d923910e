"""generate.python_text: the long-line marking finds multi-line strings exactly as tokenize does."""

from __future__ import annotations

import io
import tokenize
from pathlib import Path

import pytest

from nodl.generate.python_text import LINE_LENGTH, comment, docstring, literal, mark_long_lines, multiline_string_lines

REPO = Path(__file__).resolve().parent.parent


def tokenized(text: str) -> set[int]:
    inside: set[int] = set()
    for token in tokenize.generate_tokens(io.StringIO(text).readline):
        if token.type == tokenize.STRING and token.end[0] > token.start[0]:
            inside.update(range(token.start[0], token.end[0]))
    return inside


TRICKY = [
    'x = """a\nb\n"""\n',
    "x = '''a\\'''\nb'''\n",                       # an escaped quote does not close it
    'x = "\\"\\"\\""\ny = """\n"""\n',              # three escaped quotes in a one-line string
    "x = 'a\"\"\"b'\ny = 1\n",                      # a triple quote inside a one-line string
    '# a comment with """ in it\ny = """\nz\n"""\n',
    'x = r"""\\"""\n"""\n',                        # raw: backslash-quote still does not close
    'def f():\n    """Doc\n\n    more.\n    """\n',
    'x = b"""\n""" + f"{1}"\n',
]


@pytest.mark.parametrize('text', TRICKY)
def test_multiline_strings_as_tokenize_finds_them(text: str) -> None:
    assert multiline_string_lines(text) == tokenized(text)


def test_generated_modules_and_the_library_agree_with_tokenize() -> None:
    files = sorted((REPO / 'tests' / 'fixtures' / 'generate' / 'python').glob('*.py'))
    files += sorted((REPO / 'nodl' / 'generate').glob('*.py'))
    assert files
    for path in files:
        text = path.read_text(encoding='utf-8')
        assert multiline_string_lines(text) == tokenized(text), path


def test_long_lines_are_marked_outside_strings_only() -> None:
    long = 'x' * (LINE_LENGTH + 1)
    text = f'a = "{long}"\nb = """\n{long}\n"""\nc = 1\n'
    lines = mark_long_lines(text).split('\n')
    assert lines[0].endswith('  # noqa: E501')
    assert lines[2] == long  # inside a string: left as it is
    assert mark_long_lines('a = 1\n') == 'a = 1\n'


HOSTILE = 'Gain \u202e txt.exe \x1b[2J\x00 end\u2028next \x85 "quoted" \\ done'


def test_hostile_text_in_docstrings_and_comments_is_escaped_and_compiles() -> None:
    from nodl.text_safety import first_unsafe

    source = docstring(HOSTILE, '    ') + comment(HOSTILE, '    ') + '    pass\n'
    code = 'def f():\n' + source
    assert first_unsafe(code) == -1 and '\u2028' not in code
    namespace: dict[str, object] = {}
    exec(compile(code, '<generated>', 'exec'), namespace)
    assert namespace['f'].__doc__ == HOSTILE  # type: ignore[attr-defined]
    assert literal(HOSTILE).isascii() and eval(literal(HOSTILE)) == HOSTILE
