"""The example system (examples/system): built with a real colcon build, then analysed.

One colcon build (module scope) of its four packages: two ament_cmake packages
registering with ``ament_nodl_register_node(... PLUGIN ... NODE_NAME ...)`` and two
ament_python packages registering with ``nodl_data_files(..., node_names=)``.  The
tests read the registrations back from the ament index, analyse the launch files
(XML including YAML and Python) with the installed definitions as a user does
(``nodl analyse``), and find every planted problem exactly where it is planted and
nothing else; the system's SROS 2 policy is a golden file.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import REPO
from nodl.analysis import KINDS, analyse_launch
from nodl.registry.node_info import find_plugin, read_node_info

VENV = Path(sys.prefix)
SYSTEM = REPO / 'examples' / 'system'
LAUNCH = SYSTEM / 'launch' / 'rover.launch.xml'
PACKAGES = ('rover_base', 'rover_sensors', 'rover_navigation', 'rover_tools')
GOLDEN = REPO / 'tests' / 'fixtures' / 'policy' / 'expected' / 'example_system.policy.xml'
#: The launch argument that leaves the planted duplicate node out (for the policy).
WITHOUT_DUPLICATE = {'with_aggregator': 'false'}

# Every planted problem: kind, file (under examples/system), line, what that line holds
# (so that an edit that moves it fails here with a clear message), and the endpoint or
# parameter the finding is about (None: the node itself) and the nodes it names.
PLANTED = [
    ('unknown-parameter', 'config/sensors.yaml', 5, 'frame: base_laser', 'frame', ['/rover/lidar']),
    ('parameter-type', 'config/sensors.yaml', 7, 'scan_rate: 10', 'scan_rate', ['/rover/lidar']),
    ('type-mismatch', 'launch/navigation.launch.py', 22, "executable='localizer'",
     '/rover/wheel_odom', ['/rover/motor_controller', '/rover/localizer']),
    ('qos-warning', 'launch/navigation.launch.py', 22, "executable='localizer'",
     '/rover/imu/data', ['/rover/imu_filter', '/rover/localizer']),
    ('orphan-subscription', 'launch/navigation.launch.py', 22, "executable='localizer'",
     '/rover/gps/fix', ['/rover/localizer']),
    ('orphan-service-client', 'launch/navigation.launch.py', 25, "executable='planner'",
     '/rover/clear_costmap', ['/rover/planner']),
    ('unused-remap', 'launch/rover.launch.xml', 20, '<remap from="odom" to="wheel_odom"/>', '/rover/odom',
     ['/rover/motor_controller']),
    ('qos-incompatible', 'launch/rover.launch.xml', 25, 'exec="safety_controller"', '/rover/scan',
     ['/rover/lidar', '/rover/safety_controller']),
    ('duplicate-node', 'launch/rover.launch.xml', 29, 'exec="diagnostic_aggregator"', None,
     ['/rover/diagnostic_aggregator']),
    ('multiple-publishers', 'launch/rover.launch.xml', 34, 'exec="teleop"', '/rover/cmd_vel',
     ['/rover/safety_controller', '/rover/teleop']),
    ('orphan-action-client', 'launch/rover.launch.xml', 36, 'exec="mission_executive"',
     '/rover/dock', ['/rover/mission']),
    ('no-definition', 'launch/rover.launch.xml', 39, 'exec="web_bridge"', None, ['/rover/web_bridge']),
    ('missing-parameter', 'launch/sensors.launch.yaml', 11, '- node:', 'port', ['/rover/imu']),
    ('parameter-invalid', 'launch/sensors.launch.yaml', 30, '- {name: fps, value: 90.0}',
     'fps', ['/rover/camera']),
    ('orphan-publisher', 'launch/sensors.launch.yaml', 32, 'plugin: rover_sensors::ImageRectifier',
     '/rover/image_rect', ['/rover/rectifier']),
]


class Build:
    def __init__(self, root: Path, result: subprocess.CompletedProcess[str]) -> None:
        self.root = root
        self.result = result
        self.install = root / 'install'   # --merge-install: one prefix

    @property
    def prefixes(self) -> list[str]:
        return [str(self.install), str(VENV)]

    def env(self) -> dict[str, str]:
        return dict(os.environ, AMENT_PREFIX_PATH=os.pathsep.join(self.prefixes),
                    ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')


@pytest.fixture(scope='module')
def build(tmp_path_factory: pytest.TempPathFactory) -> Build:
    root = tmp_path_factory.mktemp('system_ws')
    for package in PACKAGES:   # a copy: setup.py stages index markers next to itself
        shutil.copytree(SYSTEM / package, root / 'src' / package)
    env = dict(os.environ)
    env.pop('MAKEFLAGS', None)
    env.update(AMENT_PREFIX_PATH=str(VENV), CMAKE_PREFIX_PATH=str(VENV),
               PATH=os.pathsep.join([str(VENV / 'bin'), env.get('PATH', '')]))
    result = subprocess.run([str(VENV / 'bin' / 'colcon'), 'build', '--merge-install',
                             '--event-handlers', 'console_cohesion-'],
                            cwd=root, env=env, text=True, capture_output=True, timeout=600)
    assert result.returncode == 0, result.stdout + result.stderr
    return Build(root, result)


@pytest.fixture(scope='module')
def report(build: Build) -> dict:  # type: ignore[type-arg]
    # the command a user runs (the configuration examples/system/nodl.toml applies)
    result = subprocess.run([sys.executable, '-m', 'nodl', 'analyse', str(LAUNCH),
                             '--format', 'json'], cwd=REPO, env=build.env(), text=True,
                            capture_output=True, timeout=120)
    assert result.returncode == 1, result.stdout + result.stderr   # errors are planted
    data: dict = json.loads(result.stdout)  # type: ignore[type-arg]
    return data


@pytest.fixture(scope='module')
def workspace(build: Build):  # type: ignore[no-untyped-def]
    """The built workspace, NOT sourced: AMENT_PREFIX_PATH holds the virtual environment only,
    so what the analyses below find of the workspace (the launch files' find-pkg-share, the
    definitions and their nodl:// mixins) comes from the prefixes= they are given."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv('AMENT_PREFIX_PATH', str(VENV))
        yield build


@pytest.fixture(scope='module')
def analysis(workspace: Build):  # type: ignore[no-untyped-def]
    return analyse_launch(LAUNCH, prefixes=workspace.prefixes)


def test_the_four_packages_build_with_colcon(build: Build) -> None:
    for package in PACKAGES:
        assert f'Finished <<< {package}' in build.result.stdout, build.result.stdout
    index = build.install / 'share' / 'ament_index' / 'resource_index'
    assert len(list((index / 'nodl_nodes').iterdir())) == 15
    assert [p.name for p in (index / 'nodl_interfaces').iterdir()] == ['rover_base__diagnostics']


def test_registrations_read_back_from_the_index(build: Build) -> None:
    prefixes = [str(build.install)]
    # ament_cmake: ament_nodl_register_node(... PLUGIN ...) and (... NODE_NAME ...)
    camera = read_node_info('rover_sensors', 'camera_driver', prefixes)
    assert (camera.plugin, camera.node_name) == ('rover_sensors::CameraDriver', None)
    lidar = read_node_info('rover_sensors', 'lidar_driver', prefixes)
    assert (lidar.plugin, lidar.node_name) == (None, 'lidar')
    found = find_plugin('rover_sensors', 'rover_sensors::CameraDriver', prefixes)
    assert found is not None and found.key == 'camera_driver'
    # registered without either: nothing recorded
    assert read_node_info('rover_sensors', 'image_rectifier', prefixes) == (
        'rover_sensors', 'image_rectifier', None, None)
    assert find_plugin('rover_sensors', 'rover_sensors::ImageRectifier', prefixes) is None
    # ament_python: nodl_data_files(..., node_names=)
    assert read_node_info('rover_tools', 'mission_executive', prefixes).node_name == 'mission'
    assert read_node_info('rover_navigation', 'localizer', prefixes).node_name == 'localizer'


def test_the_table_covers_every_check_kind() -> None:
    kinds = [row[0] for row in PLANTED]
    assert len(kinds) == len(set(kinds))
    # (assumed-duplicate-node is planted in tests/fixtures/analysis/launch/assumed_names.launch.xml;
    # type-definition-mismatch needs two installed definitions of one type, which
    # tests/test_system_checks_types.py plants in an overlay; draft-gaps needs an extracted
    # draft, which tests/test_cli_analyse.py plants from tests/fixtures/overlays/gaps)
    assert set(kinds) == set(KINDS) - {'unnamed-node', 'not-analysable', 'broken-check',
                                       'assumed-duplicate-node', 'type-definition-mismatch',
                                       'draft-gaps'}


@pytest.mark.parametrize(('kind', 'file', 'line', 'text', 'about', 'nodes'), PLANTED,
                         ids=[row[0] for row in PLANTED])
def test_each_planted_problem_is_found_where_it_is_planted(report, kind, file, line, text,  # type: ignore[no-untyped-def]
                                                           about, nodes) -> None:
    path = SYSTEM / file
    assert text in path.read_text(encoding='utf-8').splitlines()[line - 1], (
        f'{file}:{line} no longer holds {text!r}: update the table')
    found = [f for f in report['findings'] if f['kind'] == kind]
    assert len(found) == 1, found
    finding = found[0]
    assert (Path(os.path.normpath(finding['file'])), finding['line']) == (path, line)
    assert finding['code'] == KINDS[kind]
    assert finding.get('endpoint', finding.get('parameter')) == about
    assert finding['nodes'] == nodes


def test_there_is_nothing_else(report) -> None:  # type: ignore[no-untyped-def]
    assert len(report['findings']) == len(PLANTED), [f['message'] for f in report['findings']]
    assert len(report['nodes']) == 18   # 17 nodes and the component container


def test_unnamed_nodes_take_the_recorded_name(analysis) -> None:  # type: ignore[no-untyped-def]
    lidar = next(n for n in analysis.nodes if n.entry.executable == 'lidar_driver')
    assert lidar.entry.name is None and lidar.fqn == '/rover/lidar'   # NODE_NAME lidar (CMake)
    mission = next(n for n in analysis.nodes if n.entry.executable == 'mission_executive')
    assert mission.entry.name is None and mission.fqn == '/rover/mission'   # node_names (setup.py)
    assert not [f for f in analysis.findings if f.kind == 'unnamed-node']


def test_composable_nodes_are_matched_by_plugin(analysis) -> None:  # type: ignore[no-untyped-def]
    by_plugin = {n.entry.plugin: n for n in analysis.nodes if n.entry.plugin}
    camera = by_plugin['rover_sensors::CameraDriver']
    assert camera.match.how == 'plugin' and camera.match.file.endswith('camera_driver.nodl.yaml')
    assert camera.fqn == '/rover/camera' and camera.entry.container == '/rover/camera_container'
    rectifier = by_plugin['rover_sensors::ImageRectifier']   # no PLUGIN: the class name in snake case
    assert rectifier.match.how == 'class name'
    assert rectifier.match.file.endswith('image_rectifier.nodl.yaml')


def test_the_policy_of_the_example_system(workspace: Build, golden, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    from nodl.policy.launched import launch_policy
    from nodl.policy.writer import write_policy
    from test_policy_generate import round_trip

    monkeypatch.chdir(REPO)   # the comments name launch files relative to the working directory
    result = launch_policy(LAUNCH, WITHOUT_DUPLICATE, allow_missing=True, prefixes=workspace.prefixes)
    assert result.ok, result.diagnostics
    # the two nodes without definition are warned about, and their gaps marked
    assert sorted(d.code for d in result.diagnostics) == ['NODL601', 'NODL601']
    text = write_policy(result.policy)
    golden.check(text.replace(str(workspace.install), '$INSTALL'), GOLDEN)
    instances = [n.instance for n in analyse_launch(LAUNCH, WITHOUT_DUPLICATE,
                                                    prefixes=workspace.prefixes, checks={}).nodes
                 if n.instance is not None]
    assert len(instances) == 15
    round_trip(instances, text)


def test_a_widened_copy_of_the_policy_is_over_privileged(workspace: Build, tmp_path: Path) -> None:
    from nodl.policy.check import check_policy_file
    from nodl.policy.launched import launch_policy
    from nodl.policy.writer import write_policy

    sys.path.insert(0, str(REPO / 'examples'))
    try:
        from demo import widen_policy  # what make demo does
    finally:
        sys.path.remove(str(REPO / 'examples'))
    result = launch_policy(LAUNCH, WITHOUT_DUPLICATE, allow_missing=True, prefixes=workspace.prefixes)
    widened = tmp_path / 'widened.policy.xml'
    widened.write_text(widen_policy(write_policy(result.policy)), encoding='utf-8')
    found = check_policy_file(widened, result.policy)
    assert [(d.code, d.message) for d in found] == [
        ('NODL605', 'extra: /rover/teleop is granted topic publish on /rover/cmd_vel_nav, '
                    'which it does not need (over-privilege)')]


def test_the_library_finds_what_the_command_reports(analysis, report) -> None:  # type: ignore[no-untyped-def]
    # the command also applies examples/system/nodl.toml (the /diagnostics allow list)
    kinds = sorted(f.kind for f in analysis.findings if f.kind != 'multiple-publishers')
    assert kinds == sorted(f['kind'] for f in report['findings'] if f['kind'] != 'multiple-publishers')
    assert {f.endpoint for f in analysis.findings if f.kind == 'multiple-publishers'} == {
        '/rover/cmd_vel', '/diagnostics'}


from browser import assert_fits, browser, open_page  # noqa: E402,F401  (browser: a fixture)


def test_the_graph_page_of_the_example_system_fits_1280x800(analysis, browser, tmp_path) -> None:  # type: ignore[no-untyped-def]  # noqa: F811
    """The page `nodl analyse --graph rover.html` writes, in headless Chromium at 1280x800: the
    18 nodes fit the window on load (no scrolling), the /rover namespace folds to one box,
    and the screenshot a person looks at is kept in tmp_path (fleet of 100 nodes:
    tests/test_graph.py)."""
    from selenium.webdriver.common.by import By

    from nodl.graph import render_graph

    page = tmp_path / 'rover.html'
    page.write_text(render_graph(analysis, 'html'), encoding='utf-8')
    open_page(browser, page)
    assert_fits(browser)
    shot = tmp_path / 'rover-1280x800.png'
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 10_000
    browser.find_element(By.CSS_SELECTOR, 'button[data-do="fold-all"]').click()
    box = browser.find_element(By.CSS_SELECTOR, 'g.fold')
    assert box.is_displayed() and box.text.startswith('\u25b8 /rover (')
    lidar = browser.execute_script(
        "var d = JSON.parse(document.getElementById('nodl-data').textContent);"
        "return Object.keys(d.vertices).filter(k => d.vertices[k].name === '/rover/lidar')[0];")
    assert browser.find_element(By.ID, lidar).is_displayed() is False


def test_the_docs_of_the_example_system_build_with_sphinx_and_pass_check(build: Build, tmp_path: Path) -> None:
    """nodl doc of the example system's launch file (its packages installed): the MyST pages
    build with a real sphinx-build -W (the node launched twice is two parameter sections,
    not one duplicate target), every launched node with a definition links its page, and
    nodl doc --check passes on what was written."""
    site = tmp_path / 'site'

    def doc(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([sys.executable, '-m', 'nodl', 'doc', str(LAUNCH), '-o',
                               str(site), *args], cwd=REPO, env=build.env(), text=True,
                              capture_output=True, timeout=120)

    written = doc()
    assert written.returncode == 0, written.stderr
    system = (site / 'systems' / 'rover.md').read_text(encoding='utf-8')
    assert system.count('(../rover_base/diagnostic_aggregator.md#') == 2
    assert 'launched again\\, at examples\\/system\\/launch\\/rover\\.launch\\.xml\\:29' in system
    assert (site / 'rover_sensors' / 'lidar_driver.md').is_file()
    (site / 'conf.py').write_text("extensions = ['myst_parser']\nsource_suffix = {'.md': 'markdown'}\n"
                                  "master_doc = 'index'\n", encoding='utf-8')
    sphinx = subprocess.run([sys.executable, '-m', 'sphinx', '-W', '-q', '-b', 'html', str(site),
                             str(tmp_path / 'html')], text=True, capture_output=True, timeout=120)
    assert sphinx.returncode == 0, sphinx.stderr
    assert 'rover_base/motor_controller.html' in (tmp_path / 'html' / 'systems' / 'rover.html').read_text(
        encoding='utf-8')
    checked = doc('--check')
    assert checked.returncode == 0, checked.stderr
