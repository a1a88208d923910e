"""nodl doc --check: stale, missing and left-over pages are found; nothing is written."""

from __future__ import annotations

import sys
from pathlib import Path

from conftest import FIXTURES, REPO
from nodl.doc.check import check_files
from nodl.doc.collect import collect
from nodl.doc.writer import render_files, write_files

DOC = FIXTURES / 'doc'


def test_fresh_pages_pass_and_each_kind_of_staleness_is_found(tmp_path: Path) -> None:
    docs = collect([str(DOC / 'talker.nodl.yaml'), str(DOC / 'hostile.nodl.yaml')], root=str(REPO),
                   prefixes=[sys.prefix])
    files = render_files(docs, 'md')
    write_files(files, str(tmp_path))
    assert check_files(files, str(tmp_path), 'md') == []
    page = tmp_path / 'talker.md'
    page.write_text(page.read_text().replace('Greetings per second', 'Greetings per minute'))
    (tmp_path / 'hostile.md').unlink()
    fewer = {k: v for k, v in files.items() if k != 'hostile.md'}
    problems = check_files(files, str(tmp_path), 'md')
    assert sorted(p.code for p in problems) == ['NODL275', 'NODL276']
    stale = next(p for p in problems if p.code == 'NODL275')
    assert stale.file == str(page) and 'from line' in stale.message
    write_files(files, str(tmp_path), force=True)
    assert [p.code for p in check_files(fewer, str(tmp_path), 'md')] == ['NODL277']
    (tmp_path / 'notes.md').write_text('the user\'s own page\n')  # not nodl's: not left over
    assert [p.code for p in check_files(fewer, str(tmp_path), 'md')] == ['NODL277']
