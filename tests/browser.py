"""A real browser for the tests of the graph page: headless Chromium driven by Selenium.

Nothing is installed here: the suite needs Debian's ``chromium`` and ``chromium-driver``
(the driver's path is given, so Selenium Manager never runs and nothing is downloaded).
Chromium is started with everything that would reach the network turned off; the pages
it opens are local files that fetch nothing.
"""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest

#: The window the page must fit (CSS pixels).
WIDTH, HEIGHT = 1280, 800
CHROMIUM_FLAGS = ('--headless=new', '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage',
                  '--disable-background-networking', '--disable-component-update',
                  '--disable-sync', '--no-first-run', '--disable-default-apps',
                  '--disable-extensions', '--mute-audio', f'--window-size={WIDTH},{HEIGHT}')


def _program(*names: str) -> str:
    for name in names:
        found = shutil.which(name)
        if found:
            return found
    raise AssertionError(f'{names[0]} is not installed: the graph page tests need Debian\'s '
                         "'chromium' and 'chromium-driver' packages (apt-get install chromium "
                         'chromium-driver)')


@pytest.fixture(scope='module')
def browser() -> Iterator[object]:
    """A headless Chromium whose viewport is exactly 1280x800; quit at the module's end."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = _program('chromium', 'chromium-browser')
    for flag in CHROMIUM_FLAGS:
        options.add_argument(flag)
    driver = webdriver.Chrome(options=options,
                              service=Service(_program('chromedriver')))
    try:
        driver.set_page_load_timeout(30)
        driver.set_script_timeout(10)
        driver.execute_cdp_cmd('Emulation.setDeviceMetricsOverride',
                               {'width': WIDTH, 'height': HEIGHT, 'deviceScaleFactor': 1,
                                'mobile': False})
        yield driver
    finally:
        driver.quit()


def open_page(driver: object, page: Path) -> None:
    """Load ``page`` (a file) and wait until its script has fitted the drawing."""
    from selenium.webdriver.support.ui import WebDriverWait

    driver.get(page.resolve().as_uri())  # type: ignore[attr-defined]
    WebDriverWait(driver, 10).until(  # type: ignore[arg-type]
        lambda d: d.execute_script('return document.readyState') == 'complete')


def fits(driver: object) -> dict[str, float]:
    """The drawing's box, the canvas's and the window's (client pixels), and whether the page
    scrolls, as the browser lays them out."""
    return driver.execute_script(  # type: ignore[attr-defined,no-any-return]
        "var g = document.querySelector('#canvas svg g.graph').getBoundingClientRect();"
        "var c = document.getElementById('canvas').getBoundingClientRect();"
        'return {left: g.left, top: g.top, right: g.right, bottom: g.bottom,'
        ' cleft: c.left, ctop: c.top, cright: c.right, cbottom: c.bottom,'
        ' width: window.innerWidth, height: window.innerHeight,'
        ' scroll_width: document.documentElement.scrollWidth,'
        ' scroll_height: document.documentElement.scrollHeight};')


def assert_fits(driver: object) -> dict[str, float]:
    """The whole drawing is inside the canvas, the canvas inside the 1280x800 window, and
    the page does not scroll."""
    box = fits(driver)
    assert (box['width'], box['height']) == (WIDTH, HEIGHT), box
    assert box['scroll_width'] <= WIDTH and box['scroll_height'] <= HEIGHT, box
    assert box['cleft'] - 0.5 <= box['left'] and box['right'] <= box['cright'] + 0.5, box
    assert box['ctop'] - 0.5 <= box['top'] and box['bottom'] <= box['cbottom'] + 0.5, box
    assert box['cright'] <= WIDTH and box['cbottom'] <= HEIGHT, box
    return box
