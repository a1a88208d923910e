"""The files of a documentation run: rendered, marked, written under the output folder.

Each page becomes ``<path>.<ext>`` and each system graph an ``.svg`` file next
to its page.  Every file carries the content marker of
:mod:`nodl.writing` (an HTML comment in Markdown, HTML and SVG; a
comment block in reStructuredText, whose first line is ``..``), so a rerun
replaces it but never a file the user wrote or edited (NODL031, NODL032)
unless ``force``; writes are atomic, and never leave the output folder
(NODL708).
"""

from __future__ import annotations

import hashlib
import os
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic
from nodl.doc import EXTENSIONS
from nodl.doc.blocks import Picture
from nodl.doc.html import render_html
from nodl.doc.markdown import render_markdown
from nodl.doc.rst import render_rst
from nodl.writing import MARKER_TAG, WriteError, marked_text, unmark, write_marked

if TYPE_CHECKING:
    from nodl.doc.blocks import Page
    from nodl.doc.collect import DocSet

__all__ = ['render_page', 'render_files', 'write_files', 'mark_rst']


def render_page(page: Page, format: str) -> str:
    """One page's text (unmarked) in ``md``, ``html`` or ``rst``; ValueError for another."""
    if format == 'md':
        return render_markdown(page)
    if format == 'html':
        return render_html(page)
    if format == 'rst':
        return render_rst(page)
    raise ValueError(f"unknown format {format!r}; expected md, html or rst")


def mark_rst(text: str) -> str:
    """reStructuredText with the content marker inside a leading comment block (``..`` then
    the indented marker line), which Sphinx shows nowhere; :func:`nodl.writing.marker_state`
    reads it as any other marker (its hash covers the text without that line)."""
    body = unmark(text)
    if not body.startswith('..\n'):
        body = '..\n' + body if body.startswith('\n') else '..\n\n' + body
    digest = hashlib.sha256(body.encode('utf-8', 'surrogatepass')).hexdigest()
    return f'..\n   # {MARKER_TAG}{digest}\n{body[3:]}'


def render_files(docs: DocSet, format: str) -> dict[str, str]:
    """Relative path (``/``-separated) -> the text to write, marked: every page, then every
    graph picture (next to its page)."""
    extension = EXTENSIONS[format]
    files: dict[str, str] = {}
    for path, page in sorted(docs.pages.items()):
        name = path + extension
        text = render_page(page, format)
        files[name] = mark_rst(text) if format == 'rst' else marked_text(name, text)
        for block in page.blocks:
            if isinstance(block, Picture) and format != 'html':  # html has it inline
                folder = os.path.dirname(path)
                picture = f'{folder}/{block.file}' if folder else block.file
                files[picture] = marked_text(picture, block.svg, 'xml')
    return files


def write_files(files: dict[str, str], folder: str, *, force: bool = False
                ) -> tuple[list[str], list[Diagnostic]]:
    """Write ``files`` (from :func:`render_files`) under ``folder``: the paths written (a
    file that already holds its text is left alone), and a diagnostic per file not written."""
    written: list[str] = []
    problems: list[Diagnostic] = []
    for name, text in files.items():
        path = os.path.join(folder, *name.split('/'))
        try:
            if write_marked(path, text, force=force, style=None, make_parents=True, within=folder):
                written.append(path)
        except WriteError as exc:
            problems.append(exc.diagnostic)
    return written, problems
