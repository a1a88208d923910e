"""The system graph: DOT escaping, the SVG layout, and a self-contained HTML page."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

from nodl_schema.analysis import analyse_launch
from nodl_schema.analysis.graph import render_graph
from nodl_schema.analysis.graph.dot import dot_string
from nodl_schema.analysis.graph.html import json_for_script
from nodl_schema.analysis.graph.model import build_graph

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]


def _analysis():  # type: ignore[no-untyped-def]
    return analyse_launch(FIXTURES / 'launch' / 'checks.launch.xml', prefixes=PREFIX)


def test_dot_strings_are_escaped() -> None:
    assert dot_string('a"b\\c\nd') == '"a\\"b\\\\c\\nd"'


def test_script_json_cannot_close_the_script() -> None:
    text = json_for_script({'m': '</script><!-- & \u2028'})
    assert '</' not in text and '<!--' not in text and json.loads(text) == {'m': '</script><!-- & \u2028'}


def test_the_graph_leaves_the_client_library_out_and_marks_findings() -> None:
    graph = build_graph(_analysis())
    names = {v.name for v in graph.vertices.values()}
    assert '/rosout' not in names and '/planner/get_parameters' not in names
    assert {'/scan', '/get_map', '/dock', '/planner', '/ghost'} <= names
    scan = next(v for v in graph.vertices.values() if v.name == '/scan')
    assert scan.kind == 'topic' and scan.worst == 'error'   # qos-incompatible
    ghost = next(v for v in graph.vertices.values() if v.name == '/ghost')
    assert not ghost.defined
    assert any(e.findings for e in graph.edges)


def test_svg_is_laid_out() -> None:
    svg = render_graph(_analysis(), 'svg')
    assert '<svg' in svg and 'class="node"' in svg and '/planner' in svg


def test_html_page_is_self_contained_and_complete(tmp_path: Path) -> None:
    analysis = _analysis()
    page = render_graph(analysis, 'html')
    # no fetches: no src=/href= to anything, no URLs but the SVG namespaces
    urls = set(re.findall(r'https?://[^\s"\'<>)]+', page))
    assert urls <= {'http://www.w3.org/2000/svg', 'http://www.w3.org/1999/xlink'}, urls
    assert not re.search(r'\b(src|href)\s*=', page.replace('xlink:href', ''))
    data = json.loads(re.search(r'<script type="application/json" id="nodl-data">(.*?)</script>',
                                page, re.S).group(1))
    assert {v['name'] for v in data['vertices'].values() if v['kind'] == 'node'} == \
        {n.fqn for n in analysis.nodes}
    for vid in data['vertices']:
        assert f'id="{vid}"' in page   # every vertex is clickable in the SVG
    script = re.findall(r'<script>(.*?)</script>', page, re.S)[0]
    node = shutil.which('node') or shutil.which('nodejs')
    if node is not None:
        js = tmp_path / 'page.js'
        js.write_text(script)
        assert subprocess.run([node, '--check', str(js)], timeout=60).returncode == 0
    # balanced braces and parentheses at least (no JavaScript engine needed)
    stripped = re.sub(r"'(?:\\.|[^'\\])*'|/(?:\\.|[^/\\\n])+/[gimsuy]*", '', script)
    assert stripped.count('{') == stripped.count('}') and stripped.count('(') == stripped.count(')')


def test_a_wide_graph_scrolls_instead_of_shrinking_its_labels() -> None:
    """Looked at in headless Chromium: an LR layout of a real system is several times wider
    than the panel; scaled to fit, its labels were unreadable dots. The page keeps at least 60%
    of the natural size (the panel scrolls) and wraps long locations in the findings."""
    page = render_graph(_analysis(), 'html')
    svg = re.search(r'<svg[^>]*>', page).group(0)
    natural = float(re.search(r'viewBox="[\d.]+ [\d.]+ ([\d.]+)', svg).group(1))
    least = float(re.search(r'min-width:([\d.]+)pt', svg).group(1))
    assert abs(least - 0.6 * natural) <= 1 and ' width=' not in svg
    assert 'min-height:100%' not in page and 'overflow-wrap:anywhere' in page


def test_labels_and_page_text_show_control_and_bidi_characters() -> None:
    from nodl_schema.analysis.graph.html import _h

    assert dot_string('a\u202eb\x1b"c\nd') == '"a\\\\u202eb\\\\x1b\\"c\\nd"'
    assert _h('<a\u2066>') == '&lt;a\\u2066&gt;'
    assert json.loads(json_for_script({'name\u202e': ['\x1b']})) == {'name\\u202e': ['\\x1b']}
