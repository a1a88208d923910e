"""The system graph: DOT escaping, the SVG layout, and a self-contained HTML page."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest

from nodl.analysis import analyse_launch
from nodl.graph import render_graph
from nodl.graph.dot import dot_string, format_dot, grid_edges
from nodl.graph.html import json_for_script
from nodl.graph.layout import fit_scale, layout_graph, layout_svg
from nodl.graph.model import build_graph
from nodl.system.run import analyse_definitions
from nodl.targets.placement import Definition

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]
#: The definitions of the generated fleet (a system of any size, namespaced per robot).
FLEET = Path(__file__).parent / 'fixtures' / 'graph'


def _analysis():  # type: ignore[no-untyped-def]
    return analyse_launch(FIXTURES / 'launch' / 'checks.launch.xml', prefixes=PREFIX)


def _fleet(robots: int = 10, workers: int = 7, stages: int = 1, prefix: str = '/fleet'):  # type: ignore[no-untyped-def]
    """``robots`` robots, each in its namespace: a pipeline driver -> raw -> filter (``stages``
    filters in a row) -> fusion, which publishes the fleet's /fleet/state and serves a reset,
    and ``workers`` nodes without an edge. With stages=0, no pipeline at all."""
    targets: list[Definition] = []
    names: list[str] = []

    def add(kind: str, name: str) -> None:
        targets.append(Definition(file=str(FLEET / f'{kind}.nodl.yaml')))
        names.append(name)

    for r in range(robots):
        robot = f'{prefix}/robot{r}'
        if stages:
            add('driver', f'{robot}/driver')
            for stage in range(stages):
                add('filter', f'{robot}/filter' + (f'{stage}' if stages > 1 else ''))
            add('fusion', f'{robot}/fusion')
        for w in range(workers):
            add('worker', f'{robot}/worker{w}')
    remaps = []
    if stages > 1:   # filter<i> reads what filter<i-1> writes
        for _r in range(robots):
            for stage in range(stages):
                source = 'raw' if stage == 0 else f'stage{stage - 1}'
                target = 'filtered' if stage == stages - 1 else f'stage{stage}'
                remaps += [f'filter{stage}:raw:={source}', f'filter{stage}:filtered:={target}']
    analysis = analyse_definitions(targets, names, remaps=remaps)
    assert not [f for f in analysis.findings if f.diagnostic.severity.value == 'error'], \
        [f.diagnostic.message for f in analysis.findings]
    return analysis


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
                                page, re.DOTALL).group(1))
    assert {v['name'] for v in data['vertices'].values() if v['kind'] == 'node'} == \
        {n.fqn for n in analysis.nodes}
    for vid in data['vertices']:
        assert f'id="{vid}"' in page   # every vertex is clickable in the SVG
    script = re.findall(r'<script>(.*?)</script>', page, re.DOTALL)[0]
    node = shutil.which('node') or shutil.which('nodejs')
    if node is not None:
        js = tmp_path / 'page.js'
        js.write_text(script)
        assert subprocess.run([node, '--check', str(js)], timeout=60).returncode == 0
    # balanced braces and parentheses at least (no JavaScript engine needed)
    stripped = re.sub(r"'(?:\\.|[^'\\])*'|/(?:\\.|[^/\\\n])+/[gimsuy]*", '', script)
    assert stripped.count('{') == stripped.count('}') and stripped.count('(') == stripped.count(')')


def test_the_drawing_fills_the_canvas_and_a_long_pipeline_is_laid_out_downwards() -> None:
    """The page's script fits the drawing to the canvas (the SVG fills it; zoom and pan move
    the viewBox). Left to right, a long pipeline is many times wider than a window: fitted,
    its labels would be dots, so it is laid out top to bottom when that fits larger."""
    page = render_graph(_analysis(), 'html')
    svg = re.search(r'<svg[^>]*>', page).group(0)
    assert 'width="100%" height="100%"' in svg and 'viewBox=' in svg
    assert 'overflow-wrap:anywhere' in page
    graph = build_graph(_fleet(robots=1, workers=0, stages=12))
    across = layout_svg(format_dot(graph, 'LR'))
    chosen = layout_graph(graph)
    assert fit_scale(chosen) > 1.2 * fit_scale(across)
    assert chosen == layout_svg(format_dot(graph, 'TB'))
    small = build_graph(_fleet(robots=1, workers=3, stages=0))   # fits as it is
    assert layout_graph(small) == layout_svg(format_dot(small, 'LR'))   # rqt_graph's way


def test_namespaces_are_nested_clusters() -> None:
    graph = build_graph(_fleet(robots=3, workers=2))
    by_name = {c.name: c for c in graph.clusters.values()}
    assert set(by_name) == {'/fleet', '/fleet/robot0', '/fleet/robot1', '/fleet/robot2'}
    fleet = by_name['/fleet']
    assert fleet.parent is None and sorted(graph.clusters[c].name for c in fleet.children) == [
        '/fleet/robot0', '/fleet/robot1', '/fleet/robot2']
    names = {graph.vertices[v].name for v in fleet.vertices}
    assert names == {'/fleet/state'}   # the topic every robot publishes
    robot = by_name['/fleet/robot1']
    assert robot.parent == fleet.id
    assert {graph.vertices[v].name for v in robot.vertices} == {
        '/fleet/robot1/driver', '/fleet/robot1/filter', '/fleet/robot1/fusion',
        '/fleet/robot1/worker0', '/fleet/robot1/worker1', '/fleet/robot1/raw',
        '/fleet/robot1/filtered', '/fleet/robot1/fusion/reset'}   # a lone vertex: no box
    dot = format_dot(graph)
    assert dot.count('subgraph cluster_') == 4
    assert re.search(r'subgraph cluster_k\d+ \{\n\s+id="k\d+"; label="/fleet/robot1"', dot)
    # a namespace holding nothing but one namespace is not drawn; one vertex gets no box
    deep = build_graph(_fleet(robots=1, workers=2, prefix='/site/hall/fleet'))
    assert sorted(c.name for c in deep.clusters.values()) == ['/site/hall/fleet/robot0']
    alone = build_graph(_fleet(robots=1, workers=0, prefix='/x', stages=0))
    assert alone.clusters == {}


def _centres(svg: str) -> list[tuple[float, float]]:
    return [(float(x), float(y)) for x, y in
            re.findall(r'<ellipse [^>]*cx="([-\d.]+)" cy="([-\d.]+)"', svg)]


def test_nodes_without_edges_are_a_grid_not_a_column() -> None:
    """30 nodes nothing connects: left to right, dot puts them all in the first rank (one
    column 30 nodes tall); chained into rows they are a grid about as wide as a window."""
    graph = build_graph(_fleet(robots=1, workers=30, stages=0))
    assert all(not c.vertices or c.name == '/fleet/robot0' for c in graph.clusters.values())
    svg = layout_graph(graph)
    centres = _centres(svg)
    assert len(centres) == 30
    columns = {round(x) for x, _ in centres}
    rows = {round(y) for _, y in centres}
    assert len(columns) >= 3 and len(rows) >= 3, (columns, rows)   # not 1 x 30
    width = max(x for x, _ in centres) - min(x for x, _ in centres)
    height = max(y for _, y in centres) - min(y for _, y in centres)
    assert 0.8 <= width / height <= 3.5, (width, height)
    # the same with namespaces: each namespace's grid, and the namespaces in a grid too
    spread = build_graph(_fleet(robots=9, workers=4, stages=0))
    centres = _centres(layout_graph(spread))
    xs = sorted({round(x) for x, _ in centres})
    ys = sorted({round(y) for _, y in centres})
    assert len(xs) >= 4 and len(ys) >= 4
    assert 0.6 <= (xs[-1] - xs[0]) / (ys[-1] - ys[0]) <= 4
    lr = grid_edges(spread, 'LR')
    assert lr and all(a in spread.vertices and b in spread.vertices for a, b, _ in lr)


def test_a_node_s_own_interface_comes_before_its_client_library_s() -> None:
    graph = build_graph(_fleet(robots=1, workers=0))
    fusion = next(v for v in graph.vertices.values() if v.name == '/fleet/robot0/fusion')
    interface = fusion.details['interface']
    providers = [e['provider'] for e in interface]
    assert providers[0] == 'implementation' and 'client_library' in providers
    assert providers == sorted(providers, key=lambda p: p == 'client_library')
    assert [e['name'] for e in interface[:3]] == [
        '/fleet/state', '/fleet/robot0/filtered', '/fleet/robot0/fusion/reset']
    assert {'/rosout', '/parameter_events'} <= {e['name'] for e in interface[3:]}
    assert fusion.details['client_library'] == 'rclpy'   # no package: the default
    # the tooltip: the node's own endpoints listed, the client library's counted after them
    tooltip = re.search(r'id="' + fusion.id + r'", tooltip="([^"]*)"', format_dot(graph)).group(1)
    lines = tooltip.split('\\n')
    assert lines[0] == '/fleet/robot0/fusion'
    own = lines.index('publisher /fleet/state (std_msgs/msg/String)')   # after its findings
    assert lines[own:own + 3] == ['publisher /fleet/state (std_msgs/msg/String)',
                          'subscription /fleet/robot0/filtered (std_msgs/msg/String)',
                          'service server /fleet/robot0/fusion/reset (std_srvs/srv/Trigger)']
    assert lines[own + 3:] == [f'+ {len(interface) - 3} from rclpy (parameter services, '
                               '/parameter_events, /rosout, ...)']


def test_labels_and_page_text_show_control_and_bidi_characters() -> None:
    from nodl.graph.html import _h

    assert dot_string('a\u202eb\x1b"c\nd') == '"a\\\\u202eb\\\\x1b\\"c\\nd"'
    assert _h('<a\u2066>') == '&lt;a\\u2066&gt;'
    assert json.loads(json_for_script({'name\u202e': ['\x1b']})) == {'name\\u202e': ['\\x1b']}


# ---- the page in a real browser (headless Chromium at 1280x800: tests/browser.py) ----

from browser import assert_fits, browser, open_page  # noqa: E402,F401  (browser: a fixture)


def _view(driver) -> list[float]:  # type: ignore[no-untyped-def]
    return [float(n) for n in driver.execute_script(
        "return document.querySelector('#canvas svg').getAttribute('viewBox')").split()]


def _displayed(driver, vid: str) -> bool:  # type: ignore[no-untyped-def]
    return bool(driver.execute_script(
        'var g = document.getElementById(arguments[0]);'
        'return !!g && g.getBoundingClientRect().width > 0 && getComputedStyle(g).display != "none"'
        ' && !g.closest("[style*=\\"display: none\\"]");', vid))


@pytest.fixture(scope='module')
def fleet_page(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Any]:
    """The page of a 100-node system: 10 robots in their namespaces, 7 of each robot's 10
    nodes without an edge."""
    analysis = _fleet(robots=10, workers=7)
    assert len(analysis.nodes) == 100
    page = tmp_path_factory.mktemp('fleet') / 'fleet.html'
    page.write_text(render_graph(analysis, 'html'), encoding='utf-8')
    return page, build_graph(analysis)


def test_the_100_node_page_fits_the_window_on_load(browser, fleet_page, tmp_path) -> None:  # type: ignore[no-untyped-def]  # noqa: F811
    page, _ = fleet_page
    open_page(browser, page)
    box = assert_fits(browser)
    # fitted, not merely inside: the drawing spans the free height or width of the canvas
    assert (box['bottom'] - box['top']) > 0.8 * (box['cbottom'] - box['ctop'] - 74) or \
        (box['right'] - box['left']) > 0.8 * (box['cright'] - box['cleft'] - 20), box
    # what the issue asks to look at: kept as a file (pytest's tmp_path) for a person to see
    shot = tmp_path / 'fleet-1280x800.png'
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 10_000


def test_zoom_and_pan_move_the_view_box(browser, fleet_page) -> None:  # type: ignore[no-untyped-def]  # noqa: F811
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.actions.wheel_input import ScrollOrigin
    from selenium.webdriver.common.by import By

    page, _ = fleet_page
    open_page(browser, page)
    fitted = _view(browser)
    svg = browser.find_element(By.CSS_SELECTOR, '#canvas svg')
    ActionChains(browser).scroll_from_origin(ScrollOrigin.from_element(svg), 0, -300).perform()
    zoomed = _view(browser)
    assert zoomed[2] < fitted[2] * 0.9 and abs(zoomed[2] / zoomed[3] - fitted[2] / fitted[3]) < 0.01
    browser.find_element(By.CSS_SELECTOR, 'button[data-do="zoom-out"]').click()
    assert _view(browser)[2] > zoomed[2] * 1.2
    before = _view(browser)
    ActionChains(browser).move_to_element(svg).click_and_hold().move_by_offset(120, 80) \
        .release().perform()
    panned = _view(browser)
    assert panned[0] < before[0] and panned[1] < before[1] and panned[2:] == before[2:]
    browser.find_element(By.CSS_SELECTOR, 'button[data-do="fit"]').click()
    assert _view(browser) == fitted
    assert_fits(browser)


def test_search_highlights_and_centres_a_node(browser, fleet_page) -> None:  # type: ignore[no-untyped-def]  # noqa: F811
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    page, graph = fleet_page
    open_page(browser, page)
    target = next(v.id for v in graph.vertices.values() if v.name == '/fleet/robot7/filter')
    search = browser.find_element(By.ID, 'search')
    search.send_keys('robot7/filter')
    matched = browser.execute_script(
        "return Array.from(document.querySelectorAll('#canvas g.match')).map(g => g.id)")
    assert set(matched) == {target, next(v.id for v in graph.vertices.values()
                                         if v.name == '/fleet/robot7/filtered')}
    assert browser.find_element(By.ID, 'found').text == '2 found'
    search.send_keys(Keys.ENTER)
    centre = browser.execute_script(
        'var g = document.getElementById(arguments[0]).getBoundingClientRect();'
        "var c = document.getElementById('canvas').getBoundingClientRect();"
        'return [g.left + g.width / 2 - c.left, g.top + g.height / 2 - c.top, c.width, c.height,'
        ' g.height];', target)
    x, y, width, height, node_height = centre
    assert abs(x - width / 2) < 0.1 * width and abs(y - (48 + (height - 74) / 2)) < 0.1 * height
    assert node_height >= 30   # readable: at least its natural size (36 pt = 48 px)
    assert browser.find_element(By.CSS_SELECTOR, '#panel h2').text == '/fleet/robot7/filter'
    search.send_keys('zzz')
    assert browser.find_element(By.ID, 'found').text == 'nothing found'


def test_a_folded_namespace_hides_its_members(browser, fleet_page) -> None:  # type: ignore[no-untyped-def]  # noqa: F811
    from selenium.webdriver.common.by import By

    page, graph = fleet_page
    open_page(browser, page)
    robot = next(c for c in graph.clusters.values() if c.name == '/fleet/robot3')
    members = robot.vertices
    other = next(v.id for v in graph.vertices.values() if v.name == '/fleet/robot4/driver')
    assert all(_displayed(browser, v) for v in members)
    label = browser.find_element(By.CSS_SELECTOR, f'g#{robot.id} > text')
    assert label.text.endswith('/fleet/robot3')
    browser.execute_script('arguments[0].dispatchEvent(new MouseEvent("click", {bubbles: true}))',
                           label)
    assert not any(_displayed(browser, v) for v in members)
    assert _displayed(browser, other)
    box = browser.find_element(By.CSS_SELECTOR, f'g.fold[data-cluster="{robot.id}"]')
    assert box.is_displayed() and box.text == '\u25b8 /fleet/robot3 (10 nodes, 2 topics, 1 service)'
    # an edge from inside to the rest (fusion -> /fleet/state) stays, ending at the box
    fusion = next(v.id for v in graph.vertices.values() if v.name == '/fleet/robot3/fusion')
    state = next(v.id for v in graph.vertices.values() if v.name == '/fleet/state')
    assert _displayed(browser, f'{fusion}-{state}')
    # the search finds what a folded namespace holds: the box is marked
    browser.find_element(By.ID, 'search').send_keys('robot3/worker5')
    assert 'match' in box.get_attribute('class')
    browser.execute_script('arguments[0].dispatchEvent(new MouseEvent("click", {bubbles: true}))',
                           box)
    assert all(_displayed(browser, v) for v in members)
    browser.find_element(By.CSS_SELECTOR, 'button[data-do="fold-all"]').click()
    assert not _displayed(browser, other) and not _displayed(browser, members[0])


def test_the_panel_lists_the_node_s_own_interface_first(browser, fleet_page) -> None:  # type: ignore[no-untyped-def]  # noqa: F811
    from selenium.webdriver.common.by import By

    page, graph = fleet_page
    open_page(browser, page)
    fusion = next(v.id for v in graph.vertices.values() if v.name == '/fleet/robot0/fusion')
    browser.execute_script('arguments[0].dispatchEvent(new MouseEvent("click", {bubbles: true}))',
                           browser.find_element(By.ID, fusion))
    headings = [h.text.lower() for h in browser.find_elements(By.CSS_SELECTOR, '#panel > h3')]
    assert headings[:3] == ['publishers', 'subscriptions', 'service servers'], headings
    base = browser.find_element(By.CSS_SELECTOR, '#panel details.base')
    assert 'given by the client library (rclpy)' in base.text
    panel = browser.find_element(By.ID, 'panel').get_attribute('innerHTML')
    assert panel.index('/fleet/state') < panel.index('details') < panel.index('/rosout')
