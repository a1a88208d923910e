"""The include dialect against a REAL rclpy node: `nodl check`, `show` and `describe` agree.

The definition is the node's own description, split the way the reference implementation's
users write it: a flat interface that includes the base description, a local file that
itself includes another one (nested), and the rest.
"""

from __future__ import annotations

import copy
import json
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from conftest import REPO, NodeProcess
from nodl.live.describe import describe_node


def nodl(*args: str) -> subprocess.CompletedProcess[str]:
    result = subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO, text=True,
                            capture_output=True, timeout=90)
    assert 'Traceback' not in result.stdout + result.stderr, result.stderr
    return result


@pytest.fixture(scope='module')
def full() -> Iterator[NodeProcess]:
    node = NodeProcess('full_node.py', 'full', '/include_live')
    try:
        yield node
    finally:
        node.stop()


def _write(path: Path, data: dict[str, Any]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(yaml.safe_dump(data, sort_keys=False), encoding='utf-8')


def _split(main: dict[str, Any], folder: Path) -> Path:
    """Write ``main`` as an include-dialect node: services two includes deep, subscriptions one."""
    (folder / 'package.xml').write_text('<package format="3"><name>full_pkg</name></package>')
    _write(folder / 'nodl' / 'parts' / 'services.nodl.yaml', {
        'nodl_version': 2, 'description': 'What the node serves and calls.',
        'service_servers': main.pop('service_servers'), 'service_clients': main.pop('service_clients')})
    _write(folder / 'nodl' / 'parts' / 'inputs.nodl.yaml', {
        'nodl_version': 2, 'include': [{'ref': 'local://services.nodl.yaml'}],
        'subscriptions': main.pop('subscriptions')})
    node = folder / 'nodl' / 'full.nodl.yaml'
    _write(node, {'nodl_version': 2,
                  'include': [{'ref': 'nodl://rclcpp/node'}, {'ref': 'local://parts/inputs.nodl.yaml'}],
                  'codegen': {'cpp': {'class': 'FullBase'}}, **main})
    return node


@pytest.fixture(scope='module')
def description(full: NodeProcess) -> dict[str, Any]:
    described = describe_node(full.fqn, timeout=15)
    assert described.definition['base'] == 'node'
    return described.definition


def test_check_accepts_a_conforming_include_dialect_definition(full: NodeProcess, description: dict[str, Any],
                                                               tmp_path: Path) -> None:
    main = copy.deepcopy(description['main'])
    main.pop('nodl_version', None)
    node = _split(main, tmp_path)
    result = nodl('check', full.fqn, str(node), '--timeout', '15')
    assert result.returncode == 0, result.stdout + result.stderr
    assert f'{full.fqn} conforms to {node}' in result.stdout
    assert "'include' dialect" in result.stderr + result.stdout  # the one dialect warning
    shown = nodl('show', '--layers', str(node))
    assert shown.returncode == 0, shown.stderr
    assert '# layer: parts/inputs.nodl.yaml > services.nodl.yaml\n  - name: ~/reset' in shown.stdout


def test_check_names_the_nested_layer_of_a_drifting_entity(full: NodeProcess, description: dict[str, Any],
                                                          tmp_path: Path) -> None:
    main = copy.deepcopy(description['main'])
    main.pop('nodl_version', None)
    next(s for s in main['service_servers'] if s['name'] == '~/reset')['type'] = 'std_srvs/srv/SetBool'
    node = _split(main, tmp_path)
    result = nodl('check', full.fqn, str(node), '--timeout', '15', '--format', 'json')
    assert result.returncode == 1, result.stdout + result.stderr
    data = json.loads(result.stdout)
    [drift] = [d for d in data['differences'] if d['severity'] == 'error']
    assert (drift['kind'], drift['name']) == ('type', f'{full.fqn}/reset')
    assert drift['layer'] == 'parts/inputs.nodl.yaml > services.nodl.yaml'
    assert drift['file'].endswith('services.nodl.yaml')  # where to fix it
