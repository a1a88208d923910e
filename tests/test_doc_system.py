"""nodl doc's system page: final names, connections, parameters and where they come from, findings."""

from __future__ import annotations

import sys

from conftest import FIXTURES, REPO
from nodl.doc.blocks import Heading, Picture, Table, text_of
from nodl.doc.collect import collect
from nodl.targets.resolve import gather_definitions

DOC = FIXTURES / 'doc'


def _page():  # type: ignore[no-untyped-def]
    docs = collect([str(DOC / 'system.launch.xml')], root=str(REPO), prefixes=[sys.prefix],
                   definitions=gather_definitions([str(DOC / 'defs')], use_config=False))
    return docs.pages['systems/system']


def _table(page, title: str) -> list[list[str]]:  # type: ignore[no-untyped-def]
    at = next(i for i, b in enumerate(page.blocks) if isinstance(b, Heading) and b.text == title)
    table = next(b for b in page.blocks[at:] if isinstance(b, Table))
    return [[text_of(cell) for cell in row] for row in table.rows]


def test_nodes_topics_services_parameters_findings_and_graph() -> None:
    page = _page()
    assert _table(page, 'Nodes') == [
        ['/demo/talker', 'doc_pkg', 'talker', f'doc_pkg/talker (overlay {DOC / "defs"})'],
        ['/demo/listener', 'doc_pkg', 'listener', f'doc_pkg/listener (overlay {DOC / "defs"})']]
    assert _table(page, 'Topics') == [['/demo/chatter', 'std_msgs/msg/String', '/demo/talker',
                                       '/demo/listener']]
    assert ['/talker/reset', 'std_srvs/srv/Trigger', 'none', '/demo/listener'] in _table(page, 'Services')
    assert _table(page, '/demo/talker') == [
        ['rate', '5.0', 'inline', 'tests/fixtures/doc/system.launch.xml:5'],
        ['targets', '[world]', 'inline', 'tests/fixtures/doc/system.launch.xml:6']]
    assert 'NODL556' in [row[1] for row in _table(page, 'Findings')]
    [picture] = [b for b in page.blocks if isinstance(b, Picture)]
    assert '<svg' in picture.svg and '/demo/chatter' in picture.svg
