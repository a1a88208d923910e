"""The `nodl_conformance` fixture (pytest11 entry point) and assert_conforms, on a real node.

The inner test files run in-process with pytester against a node this module
starts (and always stops); the fixture reaches them only through the
installed entry point, as it reaches a package's own tests.
"""

from __future__ import annotations

import copy
from collections.abc import Iterator
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

import pytest

# Imported before pytester runs anything in-process: its module snapshot then keeps them
# (re-importing rclpy's extension modules after they were dropped would break).
import rclpy  # noqa: F401
import rclpy.action  # noqa: F401
import rclpy.executors  # noqa: F401
from rcl_interfaces.srv import DescribeParameters  # noqa: F401

from conftest import FIXTURES, NodeProcess
from nodl import dump_nodl, load_nodl
from nodl.live.check import CheckResult
from nodl.testing import NodeDrift, assert_conforms

pytest_plugins = ['pytester']

DEFINITION = FIXTURES / 'live' / 'full_node.nodl.yaml'
#: Inner runs: no cache, and not hypothesis's plugin (it imports hypothesis anew each run, ~3 s).
INNER = ('-p', 'no:cacheprovider', '-p', 'no:hypothesispytest')


@pytest.fixture(scope='module')
def full() -> Iterator[NodeProcess]:
    node = NodeProcess('full_node.py', 'full', '/plug')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def drifting(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """full_node's definition with another type for one subscription."""
    definition: dict[str, Any] = copy.deepcopy(load_nodl(DEFINITION).to_dict())
    stop = next(e for e in definition['main']['subscriptions'] if e['name'] == '/emergency_stop')
    stop['type'] = 'std_msgs/msg/String'
    path = tmp_path_factory.mktemp('plugin') / 'drifting.nodl.yaml'
    path.write_text(dump_nodl(definition, 'yaml'), encoding='utf-8')
    return path


def test_plugin_is_registered_as_a_pytest11_entry_point() -> None:
    plugins = {e.name: e.value for e in entry_points(group='pytest11')}
    assert plugins.get('nodl') == 'nodl.testing.pytest_plugin'


def test_fixture_passes_for_a_conforming_node(pytester: pytest.Pytester, full: NodeProcess) -> None:
    pytester.makepyfile(test_inner=f'''
        from nodl.live.check import CheckResult


        def test_node_conforms(nodl_conformance):
            result = nodl_conformance({full.fqn!r}, {str(DEFINITION)!r}, timeout=15)
            assert isinstance(result, CheckResult)
            assert result.conforms
    ''')
    result = pytester.runpytest(*INNER)
    result.assert_outcomes(passed=1)


def test_fixture_fails_with_node_drift(pytester: pytest.Pytester, full: NodeProcess,
                                       drifting: Path) -> None:
    pytester.makepyfile(test_inner=f'''
        def test_node_conforms(nodl_conformance):
            nodl_conformance({full.fqn!r}, {str(drifting)!r}, timeout=15)
    ''')
    result = pytester.runpytest(*INNER)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines([
        '*NodeDrift*',
        "*/plug/full: error: type: subscription '/emergency_stop': declared type "
        'std_msgs/msg/String, observed std_msgs/msg/Bool (declared in main)*',
        '*/plug/full drifts from *drifting.nodl.yaml: 1 difference*',
    ])


def test_fixture_comes_from_the_entry_point(pytester: pytest.Pytester) -> None:
    """With the `nodl` plugin disabled, the fixture does not exist."""
    pytester.makepyfile(test_inner='''
        def test_uses_it(nodl_conformance):
            pass
    ''')
    result = pytester.runpytest(*INNER, '-p', 'no:nodl')
    result.assert_outcomes(errors=1)
    result.stdout.fnmatch_lines(["*fixture 'nodl_conformance' not found*"])


def test_assert_conforms_directly(full: NodeProcess, drifting: Path) -> None:
    result = assert_conforms(full.fqn, DEFINITION, timeout=15)
    assert isinstance(result, CheckResult) and result.conforms

    with pytest.raises(NodeDrift) as caught:
        assert_conforms(full.fqn, drifting, timeout=15)
    assert isinstance(caught.value, AssertionError)
    message = str(caught.value)
    assert "error: type: subscription '/emergency_stop'" in message
    assert message.rstrip().splitlines()[-1].startswith('/plug/full drifts from ')
    assert 'unverifiable' in message.splitlines()[-1]
    # the differences as coded diagnostics, placed in the definition, for a test's own use
    drift = caught.value.result
    assert drift is not None and caught.value.diagnostics == drift.differences
    (wrong,) = [d for d in caught.value.diagnostics if d.code == 'NODL403']
    assert (wrong.file, wrong.line > 0) == (str(drifting), True)


def test_assert_conforms_accepts_remaps(full: NodeProcess, tmp_path: Path) -> None:
    """The node subscribes to `commands`; a definition declaring `cmd_in` matches it when the
    check is told the node was started with `cmd_in:=commands`."""
    definition: dict[str, Any] = copy.deepcopy(load_nodl(DEFINITION).to_dict())
    commands = next(e for e in definition['main']['subscriptions'] if e['name'] == 'commands')
    commands['name'] = 'cmd_in'
    path = tmp_path / 'renamed.nodl.yaml'
    path.write_text(dump_nodl(definition, 'yaml'), encoding='utf-8')
    result = assert_conforms(full.fqn, path, timeout=15, remaps=['cmd_in:=commands'])
    assert result.remaps == {'/plug/cmd_in': '/plug/commands'}


def test_assert_conforms_applies_codes_and_the_configuration(full: NodeProcess, drifting: Path,
                                                             tmp_path: Path) -> None:
    """As `nodl check` does: --ignore/--error as arguments, nodl.toml found upward."""
    result = assert_conforms(full.fqn, drifting, timeout=15, ignore=['NODL403'])
    assert [d.kind for d in result.ignored] == ['type']
    with pytest.raises(ValueError, match="unknown code 'NODL4O3'"):
        assert_conforms(full.fqn, drifting, timeout=15, ignore=['NODL4O3'])

    folder = tmp_path / 'configured'
    folder.mkdir()
    copy_ = folder / 'drifting.nodl.yaml'
    copy_.write_text(drifting.read_text(encoding='utf-8'), encoding='utf-8')
    (folder / 'nodl.toml').write_text('ignore = ["NODL403"]\n', encoding='utf-8')
    assert assert_conforms(full.fqn, copy_, timeout=15).conforms
    with pytest.raises(NodeDrift):
        assert_conforms(full.fqn, copy_, timeout=15, use_config=False)
    with pytest.raises(NodeDrift, match=r'error: type: .*\[NODL403\]'):
        assert_conforms(full.fqn, copy_, timeout=15, error=['NODL403'])  # the argument wins
