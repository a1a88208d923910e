"""PyYAML as a launch's Python code gets it (nodl.launch.shared_yaml): the same work done once,
the same results; and nav2's bringup with its real RewrittenYaml read exactly as before."""

from __future__ import annotations

import io
import json
import shutil
import sys
import tempfile
from pathlib import Path

import pytest
import yaml

from nodl.launch.shared_yaml import SharedYaml

NAV2 = Path(__file__).parent / 'fixtures' / 'launch' / 'nav2_bringup'


@pytest.fixture
def calls(monkeypatch: pytest.MonkeyPatch) -> dict[str, int]:
    """How often PyYAML's own safe_load and dump are called."""
    counted = {'safe_load': 0, 'dump': 0}
    for name in counted:
        real = getattr(yaml, name)

        def counting(*args: object, _real: object = real, _name: str = name, **kwargs: object) -> object:
            counted[_name] += 1
            return _real(*args, **kwargs)  # type: ignore[operator]
        monkeypatch.setattr(yaml, name, counting)
    return counted


def test_a_text_read_again_is_parsed_once_and_each_reader_gets_its_own_copy(
        tmp_path: Path, calls: dict[str, int]) -> None:
    shared = SharedYaml()
    file = tmp_path / 'params.yaml'
    file.write_text('node:\n  ros__parameters:\n    a: &x [1, 2.0, yes]\n    b: *x\n    when: 2001-12-14\n',
                    encoding='utf-8')
    with file.open(encoding='utf-8') as stream:
        first = shared.safe_load(stream)
    with file.open(encoding='utf-8') as stream:
        second = shared.safe_load(stream)
    third = shared.safe_load(file.read_text(encoding='utf-8'))
    assert calls['safe_load'] == 1 and shared.reused[0] == 2
    assert first == second == third == yaml.safe_load(file.read_text(encoding='utf-8'))
    params = second['node']['ros__parameters']
    assert params['a'] is params['b']  # (an alias stays one object, as PyYAML makes it)
    assert [type(v) for v in params['a']] == [int, float, bool]
    params['a'].append('changed')  # a reader changes its copy (RewrittenYaml does)...
    assert shared.safe_load(file.read_text(encoding='utf-8')) == first  # ...and no one else sees it
    assert first['node']['ros__parameters']['a'] == [1, 2.0, True]


def test_an_error_is_the_one_pyyaml_raises_for_that_stream(tmp_path: Path) -> None:
    file = tmp_path / 'broken.yaml'
    file.write_text('a: [1, 2\n', encoding='utf-8')
    with file.open(encoding='utf-8') as stream, pytest.raises(yaml.YAMLError) as own:
        yaml.safe_load(stream)
    with file.open(encoding='utf-8') as stream, pytest.raises(yaml.YAMLError) as shared:
        SharedYaml().safe_load(stream)
    assert str(shared.value) == str(own.value) and str(file) in str(shared.value)


def test_equal_data_is_dumped_once_but_only_when_it_is_equal_type_for_type(calls: dict[str, int]) -> None:
    shared = SharedYaml()
    out = io.StringIO()
    assert shared.dump({'a': [1, 'x']}, out) is None
    assert shared.dump({'a': [1, 'x']}) == out.getvalue()
    assert calls['dump'] == 1 and shared.reused[1] == 1
    assert out.getvalue() == yaml.dump({'a': [1, 'x']})
    # 1, True and 1.0 are equal in Python, not in YAML: each is dumped as itself
    assert [shared.dump({'a': v}) for v in (1, True, 1.0)] == ['a: 1\n', 'a: true\n', 'a: 1.0\n']
    assert shared.dump({'b': 1, 'a': 2}, sort_keys=False) == 'b: 1\na: 2\n'  # the options count
    assert shared.dump({'b': 1, 'a': 2}) == 'a: 2\nb: 1\n'


def test_what_the_memo_cannot_tell_apart_is_pyyaml_own_call(calls: dict[str, int]) -> None:
    shared = SharedYaml()
    for data in ((1, 2), {'a': (1, 2)}, {'s': {1, 2}}):  # not plain: always PyYAML's own dump
        assert shared.dump(data) == shared.dump(data) == yaml.dump(data)
    assert shared.dump({'a': 1}, encoding='utf-8') == b'a: 1\n'
    assert shared.dump({'a': 1}, Dumper=yaml.SafeDumper) == 'a: 1\n'
    assert shared.reused == [0, 0]


def test_the_module_is_pyyaml_with_the_walks_safe_load_and_dump() -> None:
    shared = SharedYaml()
    module = shared.module()
    assert module is shared.module()
    assert module.safe_load == shared.safe_load and module.dump == shared.dump
    for name in ('load', 'SafeLoader', 'YAMLError', 'safe_dump', 'CSafeLoader', 'constructor'):
        assert getattr(module, name) is getattr(yaml, name)


def test_nav2_bringup_with_its_rewritten_yaml_reads_as_before(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """nodl analyse of nav2's bringup_launch.py with nav2_common installed (its RewrittenYaml
    performed: five files, one per including launch file): every node's name, remaps, parameters
    (with where each is written) are those found before PyYAML's work was shared
    (expected_nodes_nav2_common.json was written by the toolkit before that change)."""
    from nodl.cli.main import main

    prefix = tmp_path / 'prefix'
    shutil.copytree(NAV2 / 'prefix', prefix)
    site = prefix / 'lib' / f'python{sys.version_info[0]}.{sys.version_info[1]}' / 'site-packages'
    shutil.copytree(NAV2 / 'nav2_common', site / 'nav2_common')
    for package in ('nav2_bt_navigator', 'nav2_route'):  # (its parameters find their share folders)
        (prefix / 'share' / 'ament_index' / 'resource_index' / 'packages' / package).touch()
        (prefix / 'share' / package).mkdir(parents=True)
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    monkeypatch.setattr(tempfile, 'tempdir', str(tmp_path))  # (where RewrittenYaml leaves its files)
    launch = prefix / 'share' / 'nav2_bringup' / 'launch'
    assert main(['analyse', str(launch / 'bringup_launch.py'), '--format', 'json']) == 0
    nodes = json.loads(capsys.readouterr().out)['nodes']
    found = [{'name': n['name'], 'source': [n['source']['file'].replace(f'{launch}/', ''), n['source']['line']],
              'remaps': n['remaps'], 'parameters': n['parameters'], 'parameters_complete': n['parameters_complete'],
              'run_time': n['run_time']} for n in nodes]
    found = json.loads(json.dumps(found).replace(str(prefix), '<prefix>'))
    expected = json.loads((NAV2 / 'expected_nodes_nav2_common.json').read_text(encoding='utf-8'))
    assert found == expected
    assert len(found) == 21 and not any(n['run_time'] for n in found)  # (RewrittenYaml was performed)
    # the value rewrites of each file (KEEPOUT_ZONE_ENABLED, SPEED_ZONE_ENABLED) reached its nodes
    by_name = {n['name']: n['parameters'] for n in found}
    assert by_name['/controller_server']['use_sim_time'] is False
