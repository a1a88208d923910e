"""nodl doc's HTML: golden page, self-contained, hostile descriptions escaped."""

from __future__ import annotations

import sys
from html.parser import HTMLParser

from conftest import FIXTURES, REPO, Golden
from nodl.doc.collect import collect
from nodl.doc.html import render_html
from nodl.targets.resolve import gather_definitions

DOC = FIXTURES / 'doc'
PREFIXES = [sys.prefix]


class _Shape(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.tags: list[str] = []
        self.rows: list[int] = []
        self.sources: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append(tag)
        if tag == 'tr':
            self.rows.append(0)
        elif tag in ('td', 'th'):
            self.rows[-1] += 1
        self.sources += [v or '' for k, v in attrs if k in ('src', 'href') and tag in ('script', 'link', 'img')]


def test_the_golden_page(golden: Golden) -> None:
    docs = collect([str(DOC / 'talker.nodl.yaml')], root=str(REPO), prefixes=PREFIXES)
    golden.check(render_html(docs.pages['talker']), DOC / 'expected' / 'talker.html')


def test_hostile_text_never_becomes_markup_and_tables_keep_their_shape() -> None:
    docs = collect([str(DOC / 'hostile.nodl.yaml')], root=str(REPO), prefixes=PREFIXES)
    shape = _Shape()
    shape.feed(render_html(docs.pages['hostile']))
    assert 'script' not in shape.tags and 'b' not in shape.tags
    assert shape.rows.count(9) >= 2 and set(shape.rows) <= {2, 3, 4, 5, 6, 9}


def test_the_system_page_is_self_contained_with_the_graph_inline() -> None:
    docs = collect([str(DOC / 'system.launch.xml')], root=str(REPO), prefixes=PREFIXES,
                   definitions=gather_definitions([str(DOC / 'defs')], use_config=False))
    text = render_html(docs.pages['systems/system'])
    shape = _Shape()
    shape.feed(text)
    assert shape.sources == []  # nothing fetched: no script, style sheet or image file
    assert 'svg' in shape.tags and '<style>' in text
