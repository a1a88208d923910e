"""nodl doc's reStructuredText: golden page, a real sphinx-build -W, hostile descriptions."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from conftest import FIXTURES, REPO, Golden
from nodl.doc.collect import collect
from nodl.doc.rst import escape, render_rst
from nodl.doc.writer import render_files, write_files

DOC = FIXTURES / 'doc'
PREFIXES = [sys.prefix]


def test_the_golden_page(golden: Golden) -> None:
    docs = collect([str(DOC / 'talker.nodl.yaml')], root=str(REPO), prefixes=PREFIXES)
    golden.check(render_rst(docs.pages['talker']), DOC / 'expected' / 'talker.rst')


def test_escaping_leaves_no_markup() -> None:
    assert escape('.. note:: |x| *y* _z_') == '\\.\\. note\\:\\: \\|x\\| \\*y\\* \\_z\\_'


def test_hostile_pages_build_with_sphinx_warnings_as_errors(tmp_path: Path) -> None:
    docs = collect([str(DOC / 'hostile.nodl.yaml')], root=str(REPO), prefixes=PREFIXES)
    _, problems = write_files(render_files(docs, 'rst'), str(tmp_path / 'src'))
    assert problems == []
    (tmp_path / 'src' / 'conf.py').write_text("master_doc = 'index'\n")
    result = subprocess.run([sys.executable, '-m', 'sphinx', '-W', '-q', '-b', 'html',
                             str(tmp_path / 'src'), str(tmp_path / 'html')],
                            text=True, capture_output=True, timeout=120)
    assert result.returncode == 0, result.stderr
    html = (tmp_path / 'html' / 'hostile.html').read_text()
    assert '<script>alert' not in html and 'not a directive' in html
    assert 'nodl: generated' not in html  # the marker is in a comment
