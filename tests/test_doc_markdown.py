"""nodl doc's MyST Markdown: golden pages, a real sphinx-build -W, hostile descriptions."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

from conftest import FIXTURES, REPO, Golden
from nodl.doc.collect import collect
from nodl.doc.markdown import escape, render_markdown
from nodl.doc.writer import render_files, write_files

DOC = FIXTURES / 'doc'
PREFIXES = [sys.prefix]
CONF = "extensions = ['myst_parser']\nsource_suffix = {'.md': 'markdown'}\nmaster_doc = 'index'\n"


def sphinx(source: Path, out: Path) -> subprocess.CompletedProcess[str]:
    """A real sphinx-build, warnings as errors."""
    return subprocess.run([sys.executable, '-m', 'sphinx', '-W', '-q', '-b', 'html', str(source),
                           str(out)], text=True, capture_output=True, timeout=120)


def test_the_golden_page(golden: Golden) -> None:
    docs = collect([str(DOC / 'talker.nodl.yaml')], root=str(REPO), prefixes=PREFIXES)
    golden.check(render_markdown(docs.pages['talker']), DOC / 'expected' / 'talker.md')


def test_escaping_leaves_no_markup() -> None:
    assert escape('a|b *c* `d` {r}`x` <s> $m$') == (
        'a\\|b \\*c\\* \\`d\\` \\{r\\}\\`x\\` \\<s\\> \\$m\\$')
    assert escape('line\nbreak\x1b[31m') == 'line break\\\\x1b\\[31m'


def test_pages_build_with_sphinx_warnings_as_errors_and_hostile_text_stays_text(tmp_path: Path) -> None:
    docs = collect([str(DOC / 'hostile.nodl.yaml'), str(DOC / 'system.launch.xml')],
                   root=str(REPO), prefixes=PREFIXES, definitions=_defs())
    written, problems = write_files(render_files(docs, 'md'), str(tmp_path / 'src'))
    assert problems == [] and written
    (tmp_path / 'src' / 'conf.py').write_text(CONF)
    result = sphinx(tmp_path / 'src', tmp_path / 'html')
    assert result.returncode == 0, result.stderr
    html = (tmp_path / 'html' / 'hostile.html').read_text()
    assert '<script>alert' not in html and '&lt;script&gt;alert(1)&lt;/script&gt;' in html
    assert '<b>not bold</b>' not in html and '{{ braces }}' in html
    # the pipe in a description did not split its row: every row of the parameters table has 9 cells
    table = html[html.index('id="node-hostile-parameters"'):]
    table = table[:table.index('</table>')]
    rows = re.findall(r'<tr[^>]*>(.*?)</tr>', table, re.S)
    assert rows and all(len(re.findall(r'<t[dh][ >]', r)) == 9 for r in rows)
    # the field table of the uninstalled type is marked unavailable, saying what to install
    assert 'missing_msgs is not installed' in html
    # the system page links the node pages and embeds the graph
    system = (tmp_path / 'html' / 'systems' / 'system.html').read_text()
    assert 'href="../doc_pkg/talker.html#node-doc-pkg-talker"' in system
    assert (tmp_path / 'html' / '_images' / 'system.graph.svg').is_file()


def _defs():  # type: ignore[no-untyped-def]
    from nodl.targets.resolve import gather_definitions

    return gather_definitions([str(DOC / 'defs')], use_config=False)
