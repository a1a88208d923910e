"""Escaping for the text files of a scaffolded package: Markdown, XML, Python strings."""

from __future__ import annotations

import re

from nodl.text_safety import visible, xml_escape

__all__ = ['markdown', 'markdown_code', 'xml_text', 'xml_attribute', 'python_string', 'one_line']

_MARKDOWN_SPECIAL = re.compile(r"([\\`*_\[\]<>|~&])")


def one_line(text: str | None) -> str:
    """``text`` on one line (runs of whitespace, newlines included, become one space)."""
    return ' '.join(str(text or '').split())


def markdown(text: str | None) -> str:
    """``text`` as literal Markdown inline text (also safe in a table cell); control and bidi
    characters are shown as escapes, never rendered."""
    return _MARKDOWN_SPECIAL.sub(r'\\\1', visible(one_line(text)))


def markdown_code(text: str) -> str:
    """``text`` as an inline code span (backticks and ``|`` cannot end it or the table cell)."""
    body = visible(one_line(text)).replace('|', '\\|')
    fence = '`'
    while fence in body:
        fence += '`'
    pad = ' ' if body.startswith('`') or body.endswith('`') else ''
    return f'{fence}{pad}{body}{pad}{fence}'


def xml_text(text: str | None) -> str:
    """``text`` as XML character data on one line (control and bidi characters as character
    references, or visible escapes where XML 1.0 allows none: :mod:`nodl.text_safety`)."""
    return xml_escape(one_line(text))


def xml_attribute(text: str) -> str:
    """``text`` for a double-quoted XML attribute."""
    return xml_escape(one_line(text), quote=True)


def python_string(text: str) -> str:
    """A Python string literal of ``text`` (ASCII only: anything else escaped)."""
    return ascii(str(text))
