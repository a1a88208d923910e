"""nodl doc's files: marked (reStructuredText too), rewritten only when changed, never over the user's."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl.doc.collect import collect
from nodl.doc.writer import mark_rst, render_files, write_files
from nodl.writing import marker_state

DOC = FIXTURES / 'doc'


def test_a_rst_marker_sits_in_a_comment_and_reads_as_valid() -> None:
    marked = mark_rst('Title\n=====\n')
    assert marked.startswith('..\n   # nodl: generated; sha256=')
    assert marker_state(marked) == 'valid'
    assert marker_state(marked.replace('Title', 'Other')) == 'edited'
    assert mark_rst(marked) == marked


@pytest.mark.parametrize('format', ['md', 'html', 'rst'])
def test_written_once_then_left_alone_and_a_users_file_is_refused(tmp_path: Path, format: str) -> None:
    docs = collect([str(DOC / 'talker.nodl.yaml')], root=str(REPO), prefixes=[sys.prefix])
    files = render_files(docs, format)
    assert sorted(files) == [f'index.{format}', f'talker.{format}']
    written, problems = write_files(files, str(tmp_path))
    assert len(written) == 2 and problems == []
    assert all(marker_state((tmp_path / name).read_text()) == 'valid' for name in files)
    assert write_files(files, str(tmp_path)) == ([], [])
    (tmp_path / f'talker.{format}').write_text('my own notes\n')
    written, problems = write_files(files, str(tmp_path))
    assert written == [] and [p.code for p in problems] == ['NODL031']
    assert (tmp_path / f'talker.{format}').read_text() == 'my own notes\n'
    written, problems = write_files(files, str(tmp_path), force=True)
    assert problems == [] and written == [str(tmp_path / f'talker.{format}')]
