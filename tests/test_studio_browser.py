"""nodl studio in a real browser (headless Chromium driven by Selenium, tests/browser.py): the
example system opened (drawn in time), a node added from the palette, two ports joined by dragging one onto
the other (incompatible ports shown as such during the drag), a parameter set to a value
that breaks its validator (the error shown), the launch file saved; and the screenshots of
the example system and of a 100-node system at 1280x800, compared with golden pictures with
a tolerance (``pytest --update-golden`` rewrites them; Chromium decodes both pictures).

One browser for the module; each test its own server (in a thread of the test process) on a
copy of the example system (tests/fixtures/studio/example_definitions: no build).
"""

from __future__ import annotations

import shutil
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from browser import HEIGHT, browser  # noqa: F401  (browser: a fixture)
from conftest import FIXTURES, REPO
from nodl.studio.app import create_app
from nodl.studio.guard import new_token
from nodl.studio.server import StudioServer, bind
from nodl.studio.session import Session
from nodl.system.run import analyse_launch
from nodl.targets.resolve import gather_definitions

DEFINITIONS = FIXTURES / 'studio' / 'example_definitions'
EXPECTED = FIXTURES / 'studio' / 'expected'
#: The findings bar (the bottom 120 pixels) holds the temporary folder's path: not compared.
COMPARED_HEIGHT = HEIGHT - 120


class Studio:
    """A studio server on a launch file, in a thread."""

    def __init__(self, launch: Path) -> None:
        definitions = gather_definitions([str(DEFINITIONS)], use_config=False)
        self.session = Session(str(launch), definitions=definitions, roots=[str(DEFINITIONS)])
        self.token = new_token()
        sock = bind(0)
        self.server = StudioServer(create_app(self.session, self.token, sock.getsockname()[1]),
                                   sock)
        self.started = time.monotonic()
        self.server.start()
        self.url = f'http://127.0.0.1:{self.server.port}/?token={self.token}'


@pytest.fixture
def example(tmp_path: Path) -> Iterator[Studio]:
    """A studio on a copy of the example system (each test its own: under xdist the tests of
    this module may run in different workers)."""
    root = tmp_path / 'system'
    shutil.copytree(REPO / 'examples' / 'system', root)
    studio = Studio(root / 'launch' / 'rover.launch.xml')
    try:
        yield studio
    finally:
        studio.server.stop()


def wait(driver: Any, condition: Callable[[], Any], what: str, timeout: float = 10.0) -> Any:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.05)
    logs = driver.get_log('browser')
    raise AssertionError(f'timed out waiting for {what}; browser log: {logs}')


def js(driver: Any, script: str, *args: Any) -> Any:
    return driver.execute_script(script, *args)


def open_studio(driver: Any, studio: Studio) -> float:
    """Load the page; the seconds until it drew the system (from the server's start)."""
    driver.get(studio.url)
    wait(driver, lambda: js(driver, 'return document.body.dataset.ready'), 'the first drawing')
    shown = time.monotonic() - studio.started
    wait(driver, lambda: js(driver, 'return document.body.dataset.palette'), 'the palette')
    return shown


def node_id(driver: Any, fqn: str) -> str | None:
    return js(driver, 'var want = arguments[0];'
                      'var n = studio.state.nodes.filter(function (n) { return n.fqn === want; })[0];'
                      'return n ? n.id : null;', fqn)


def page_point(driver: Any, element: str) -> tuple[int, int]:
    """Where ``element`` (a Cytoscape id) is drawn, in the page's coordinates."""
    x, y = js(driver, "var r = document.getElementById('canvas').getBoundingClientRect();"
                      'var p = studio.cy.getElementById(arguments[0]).renderedPosition();'
                      'return [r.left + p.x, r.top + p.y];', element)
    return int(x), int(y)


def pointer(driver: Any, steps: Callable[[Any], Any]) -> None:
    """Run mouse ``steps`` (on a pointer input, page coordinates)."""
    from selenium.webdriver.common.actions.action_builder import ActionBuilder

    actions = ActionBuilder(driver)
    steps(actions.pointer_action)
    actions.perform()


def test_the_example_system_is_shown(browser: Any, example: Studio,  # noqa: F811
                                     pytestconfig: pytest.Config) -> None:
    shown = open_studio(browser, example)
    # the target is 2 s (bench/bench_studio.py measures it); a loaded test machine is slower
    assert shown < 5.0, f'the example system took {shown:.2f} s to show'
    drawn = js(browser, "return studio.cy.nodes('.instance').length")
    assert drawn == len(example.session.snapshot()['nodes']) == 14
    # every node inside the canvas, the page not scrolled
    inside = js(browser, "var e = studio.cy.elements().renderedBoundingBox();"
                         "var c = document.getElementById('canvas').getBoundingClientRect();"
                         'return e.x1 >= 0 && e.y1 >= 0 && e.x2 <= c.width && e.y2 <= c.height'
                         ' && document.documentElement.scrollHeight <= window.innerHeight;')
    assert inside
    counts = browser.find_element('id', 'counts').text
    assert counts.startswith('5 errors · 7 warnings')
    assert 'NODL553' in browser.find_element('id', 'findings').text
    compare_screenshot(browser, EXPECTED / 'example.png', pytestconfig.getoption('--update-golden'))


def in_view(driver: Any, element: str | None) -> bool:
    """Whether the Cytoscape element ``element`` is drawn wholly inside the canvas."""
    return bool(js(driver, "var b = studio.cy.getElementById(arguments[0]).renderedBoundingBox();"
                           "var c = document.getElementById('canvas').getBoundingClientRect();"
                           'return b.x1 >= 0 && b.y1 >= 0 && b.x2 <= c.width && b.y2 <= c.height;',
                   element))


def boxes_meet(driver: Any, one: str, other: str) -> bool:
    return bool(js(driver, 'var a = studio.cy.getElementById(arguments[0]).boundingBox();'
                           'var b = studio.cy.getElementById(arguments[1]).boundingBox();'
                           'return a.x1 < b.x2 && b.x1 < a.x2 && a.y1 < b.y2 && b.y1 < a.y2;',
                   one, other))


def add_from_the_palette(driver: Any) -> None:
    search = driver.find_element('id', 'search')
    search.send_keys('dashboard')
    entries = driver.find_elements('css selector', '#definitions li')
    assert [e.get_attribute('data-executable') for e in entries] == ['dashboard']
    namespace = driver.find_element('id', 'add-namespace')
    namespace.clear()
    namespace.send_keys('/ops')
    entries[0].find_element('css selector', 'button.add').click()
    wait(driver, lambda: node_id(driver, '/ops/dashboard'), 'the added node')
    assert js(driver, "return studio.cy.getElementById('ns:/ops').length") == 1  # its group
    # shown where it was put (a new namespace's block, right of the others) without Fit
    assert in_view(driver, node_id(driver, '/ops/dashboard'))
    assert driver.find_element('id', 'panel-title').text == 'dashboard'


def join_by_dragging(driver: Any) -> None:
    js(driver, 'studio.cy.fit(undefined, 24)')
    source = f"{node_id(driver, '/rover/battery_monitor')}|publisher|battery"
    target = f"{node_id(driver, '/ops/dashboard')}|subscription|battery"
    scan = f"{node_id(driver, '/rover/safety_controller')}|subscription|scan"
    sx, sy = page_point(driver, source)
    tx, ty = page_point(driver, target)
    pointer(driver, lambda p: (p.move_to_location(sx, sy), p.click_and_hold(),
                                p.move_to_location(sx + 12, sy + 6)))
    wait(driver, lambda: js(driver, 'return studio.compatible !== null'), 'the verdicts')
    # while dragging: the compatible port is marked so, the others as incompatible
    assert js(driver, 'return studio.cy.getElementById(arguments[0]).hasClass("compatible")', target)
    assert js(driver, 'return studio.cy.getElementById(arguments[0]).hasClass("incompatible")', scan)
    pointer(driver, lambda p: (p.move_to_location(tx, ty), p.pause(0.3),
                                p.move_to_location(tx + 1, ty), p.pause(0.2), p.release()))
    edge = f'e:{source}>{target}'
    wait(driver, lambda: js(driver, 'return studio.cy.getElementById(arguments[0]).length', edge),
         'the new edge')
    assert 'battery:=/rover/battery' in driver.find_element('id', 'status').text
    assert not js(driver, "return studio.cy.nodes('.incompatible').length")


def break_a_validator(driver: Any) -> None:
    battery = node_id(driver, '/rover/battery_monitor')
    x, y = page_point(driver, f'{battery}|spacer0')  # the node's box, left of its ports
    pointer(driver, lambda p: (p.move_to_location(x + 4, y - 2), p.click()))
    wait(driver, lambda: driver.find_element('id', 'panel-title').text == 'battery_monitor',
         'the panel of battery_monitor')
    editor = driver.find_element('css selector', '.param[data-name="capacity_ah"]')
    assert 'must be greater than 0.0' in editor.find_element('class name', 'constraints').text
    field = editor.find_element('css selector', 'input')
    field.clear()
    field.send_keys('-5.0')
    error = editor.find_element('class name', 'error-text')
    wait(driver, lambda: error.is_displayed() and 'greater than 0' in error.text,
         'the error under the editor')
    assert 'invalid' in editor.get_attribute('class')
    field.clear()
    field.send_keys('30.0')
    wait(driver, lambda: not error.is_displayed(), 'the error to go')


def save(driver: Any, example: Studio) -> None:
    driver.find_element('id', 'save').click()
    wait(driver, lambda: driver.find_element('id', 'status').text.startswith('saved '), 'saving')
    text = Path(example.session.launch_file).read_text(encoding='utf-8')
    assert '<param name="capacity_ah" value="30.0"/>' in text
    assert '<node pkg="rover_tools" exec="dashboard" name="dashboard">' in text
    assert '<remap from="battery" to="/rover/battery"/>' in text
    assert 'namespace="/ops"' in text or 'namespace="ops"' in text
    # the rest of the file is as it was: the includes and the planted problems
    original = (REPO / 'examples' / 'system' / 'launch' / 'rover.launch.xml').read_text()
    assert text.startswith(original.split('<node pkg="rover_base" exec="motor_controller">')[0])
    assert '<!-- PLANTED no-definition' in text
    side = Path(example.session.launch_file + '.studio.json')
    assert '"/ops/dashboard"' in side.read_text()


def test_a_system_is_composed_with_the_mouse(browser: Any, example: Studio) -> None:  # noqa: F811
    """From the example system: a node added from the palette, two ports joined by dragging,
    a value breaking a validator refused with its error, then saved."""
    open_studio(browser, example)
    add_from_the_palette(browser)
    join_by_dragging(browser)
    break_a_validator(browser)
    save(browser, example)


def test_a_system_is_built_from_an_empty_file(browser: Any, tmp_path: Path) -> None:  # noqa: F811
    """From no file: nodes added from the palette into two namespaces, each shown in its
    namespace's box (no box over another), joined by dragging, saved; nodl analyse of the file
    finds what the page showed."""
    launch = tmp_path / 'rover.launch.xml'
    studio = Studio(launch)
    try:
        open_studio(browser, studio)
        for executable, namespace in (('battery_monitor', '/rover'), ('dashboard', '/ops'),
                                      ('safety_controller', '/rover')):
            search = browser.find_element('id', 'search')
            search.clear()
            search.send_keys(executable)
            field = browser.find_element('id', 'add-namespace')
            field.clear()
            field.send_keys(namespace)
            count = len(studio.session.snapshot()['nodes'])
            browser.find_element('css selector', '#definitions li button.add').click()
            fqn = f'{namespace}/{executable}'
            wait(browser, lambda fqn=fqn: node_id(browser, fqn), fqn)
            assert len(studio.session.snapshot()['nodes']) == count + 1
            assert in_view(browser, node_id(browser, fqn)), f'{fqn} is not shown'
            assert js(browser, 'return studio.cy.zoom()') <= 1.0  # one node does not fill it
        assert not boxes_meet(browser, 'ns:/rover', 'ns:/ops')
        # the composer's own namespace groups are not listed as kept, read-only pieces
        assert browser.find_element('id', 'readonly-items').text == ''
        source = f"{node_id(browser, '/rover/battery_monitor')}|publisher|battery"
        target = f"{node_id(browser, '/ops/dashboard')}|subscription|battery"
        sx, sy = page_point(browser, source)
        tx, ty = page_point(browser, target)
        pointer(browser, lambda p: (p.move_to_location(sx, sy), p.click_and_hold(),
                                    p.move_to_location(sx + 12, sy + 6), p.pause(0.3),
                                    p.move_to_location(tx, ty), p.pause(0.3),
                                    p.move_to_location(tx + 1, ty), p.pause(0.2), p.release()))
        wait(browser, lambda: js(browser, 'return studio.cy.getElementById(arguments[0]).length',
                                 f'e:{source}>{target}'), 'the new edge')
        browser.find_element('id', 'save').click()
        wait(browser, lambda: browser.find_element('id', 'status').text.startswith('saved '),
             'saving')
        shown = sorted(js(browser, 'return studio.state.findings.map(function (f) {'
                                   ' return f.code + " " + f.message; })'))
        assert '<remap from="battery" to="/rover/battery"/>' in launch.read_text(encoding='utf-8')
        found = analyse_launch(str(launch), definitions=studio.session.definitions)
        assert sorted(f'{f.code} {f.message}' for f in found.findings) == shown
    finally:
        studio.server.stop()


def test_a_hundred_node_system_is_shown(browser: Any, tmp_path: Path,  # noqa: F811
                                       pytestconfig: pytest.Config) -> None:
    launch = tmp_path / 'hundred.launch.xml'
    shutil.copy(FIXTURES / 'studio' / 'hundred.launch.xml', launch)
    studio = Studio(launch)
    try:
        shown = open_studio(browser, studio)
        assert shown < 8.0  # (the benchmark measures it: bench/bench_studio.py)
        assert js(browser, "return studio.cy.nodes('.instance').length") == 100
        assert js(browser, "return studio.cy.nodes('.namespace').length") == 5
        compare_screenshot(browser, EXPECTED / 'hundred.png', pytestconfig.getoption('--update-golden'))
    finally:
        studio.server.stop()


# -- pictures ----------------------------------------------------------------------------------

#: Decodes two PNGs (data: URLs) in the page and counts the pixels above the findings bar
#: that differ clearly: a channel by more than 64 of 255 (anti-aliasing and font hinting
#: move less).  Chromium's own decoder: no imaging library is needed.
_COMPARE = """
var done = arguments[arguments.length - 1], rows = arguments[2];
function pixels(url) {
  return new Promise(function (resolve, reject) {
    var image = new Image();
    image.onload = function () {
      var canvas = document.createElement('canvas');
      canvas.width = image.width; canvas.height = image.height;
      var context = canvas.getContext('2d');
      context.drawImage(image, 0, 0);
      resolve({w: image.width, h: image.height,
               data: context.getImageData(0, 0, image.width, rows).data});
    };
    image.onerror = function () { reject('not a picture'); };
    image.src = url;
  });
}
Promise.all([pixels(arguments[0]), pixels(arguments[1])]).then(function (two) {
  var a = two[0], b = two[1];
  if (a.w !== b.w || a.h !== b.h) { done({size: [a.w, a.h, b.w, b.h]}); return; }
  var differ = 0;
  for (var i = 0; i < a.data.length; i += 4) {
    if (Math.abs(a.data[i] - b.data[i]) > 64 || Math.abs(a.data[i + 1] - b.data[i + 1]) > 64 ||
        Math.abs(a.data[i + 2] - b.data[i + 2]) > 64) { differ += 1; }
  }
  done({share: differ / (a.data.length / 4)});
}, function (why) { done({error: String(why)}); });
"""


def compare_screenshot(driver: Any, expected: Path, update: bool, tolerance: float = 0.02) -> None:
    """The page's screenshot against ``expected``: at most ``tolerance`` of its pixels (above
    the findings bar) may differ clearly (fonts, anti-aliasing); ``pytest --update-golden``
    rewrites it."""
    import base64

    js(driver, 'document.activeElement && document.activeElement.blur()')
    time.sleep(0.3)  # the last frame drawn
    actual = driver.get_screenshot_as_png()
    if update:
        expected.parent.mkdir(parents=True, exist_ok=True)
        expected.write_bytes(actual)
        return
    assert expected.exists(), f'{expected} is missing; run pytest --update-golden to make it'

    def url(data: bytes) -> str:
        return 'data:image/png;base64,' + base64.b64encode(data).decode('ascii')

    result = driver.execute_async_script(_COMPARE, url(actual), url(expected.read_bytes()),
                                         COMPARED_HEIGHT)
    assert 'share' in result and result.get('size') is None, result
    share = result['share']
    if share > tolerance:
        failed = expected.with_name(expected.stem + '.actual.png')
        failed.write_bytes(actual)
        raise AssertionError(f'{share:.1%} of the screenshot differs from {expected} (more than '
                             f'{tolerance:.0%}); the screenshot is {failed}; if the change is '
                             'intended, run pytest --update-golden and look at the pictures')
