"""The ament resource index reader (nodl.ament_index)."""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl import ament_index

FIRST = str(FIXTURES / 'index' / 'first')
SECOND = str(FIXTURES / 'index' / 'second')
BOTH = [FIRST, SECOND]
INDEX = os.path.join('share', 'ament_index', 'resource_index')


def test_prefix_paths_splits_in_order_without_duplicates_or_empty_parts() -> None:
    value = os.pathsep.join(['/b', '', '/a', '/b', '/c', ''])
    assert ament_index.prefix_paths({'AMENT_PREFIX_PATH': value}) == ['/b', '/a', '/c']
    assert ament_index.prefix_paths({}) == []
    assert ament_index.prefix_paths({'AMENT_PREFIX_PATH': ''}) == []


def test_prefix_paths_reads_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', os.pathsep.join(BOTH))
    assert ament_index.prefix_paths() == BOTH
    monkeypatch.delenv('AMENT_PREFIX_PATH')
    assert ament_index.prefix_paths() == []


def test_resource_file() -> None:
    assert ament_index.resource_file('/opt/ros', 'nodl_nodes', 'p__e') == os.path.join(
        '/opt/ros', INDEX, 'nodl_nodes', 'p__e')


def test_get_resource_reads_content_prefix_and_path() -> None:
    resource = ament_index.get_resource('nodl_interfaces', 'alpha__chatter', BOTH)
    assert resource == ament_index.Resource('nodl/chatter.nodl.yaml\n', FIRST,
                                      os.path.join(FIRST, INDEX, 'nodl_interfaces',
                                                   'alpha__chatter'))


def test_get_resource_first_prefix_wins() -> None:
    assert ament_index.get_resource('nodl_nodes', 'alpha__talker', BOTH).prefix == FIRST
    assert ament_index.get_resource('nodl_nodes', 'alpha__talker', [SECOND, FIRST]).prefix == SECOND
    # only in the second
    assert ament_index.get_resource('nodl_nodes', 'alpha__listener', BOTH).prefix == SECOND


def test_get_resource_missing_is_none() -> None:
    assert ament_index.get_resource('nodl_nodes', 'alpha__nope', BOTH) is None
    assert ament_index.get_resource('no_such_type', 'alpha', BOTH) is None
    assert ament_index.get_resource('packages', 'alpha', []) is None


def test_get_resource_uses_the_environment_by_default(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', SECOND)
    assert ament_index.get_resource('nodl_nodes', 'alpha__talker').prefix == SECOND
    monkeypatch.setenv('AMENT_PREFIX_PATH', '')
    assert ament_index.get_resource('nodl_nodes', 'alpha__talker') is None


def test_get_resources_lists_names_with_their_first_prefix() -> None:
    nodes = ament_index.get_resources('nodl_nodes', BOTH)
    assert nodes == {
        'alpha__inline': FIRST, 'alpha__talker': FIRST, 'delta__dangling': FIRST,
        'noseparator': FIRST, 'alpha__listener': SECOND, 'beta__node': SECOND,
    }
    assert '.alpha__hidden' not in nodes  # hidden files are not resources
    assert ament_index.get_resources('packages', BOTH) == {
        'alpha': FIRST, 'delta': FIRST, 'gamma': FIRST, 'beta': SECOND}
    assert ament_index.get_resources('no_such_type', BOTH) == {}


def test_get_resources_skips_folders_and_missing_prefixes(tmp_path: Path) -> None:
    folder = tmp_path / INDEX / 'nodl_nodes'
    (folder / 'p__a_folder').mkdir(parents=True)
    (folder / 'p__file').write_text('x')
    assert ament_index.get_resources('nodl_nodes', [str(tmp_path / 'missing'), str(tmp_path)]) == {
        'p__file': str(tmp_path)}
    assert ament_index.get_resource('nodl_nodes', 'p__a_folder', [str(tmp_path)]) is None


def test_package_share_directory() -> None:
    assert ament_index.package_share_directory('alpha', BOTH) == os.path.join(FIRST, 'share', 'alpha')
    assert ament_index.package_share_directory('beta', BOTH) == os.path.join(SECOND, 'share', 'beta')
    assert ament_index.package_share_directory('zeta', BOTH) is None


def test_reading_needs_no_ros(tmp_path: Path) -> None:
    import subprocess
    import sys

    # Importing the index reader must not import ament_index_python or rclpy.
    code = ('import sys, nodl.registry.registrations; '
            "print(sorted(m for m in sys.modules if m.startswith(('rclpy', 'ament_index'))))")
    result = subprocess.run([sys.executable, '-c', code], cwd=FIXTURES.parent.parent, text=True,
                            capture_output=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == '[]'


def test_a_snapshot_answers_as_the_index_does() -> None:
    outside = ([ament_index.get_resource('nodl_interfaces', n, BOTH) for n in
                ('alpha__chatter', 'zeta__x', '')], ament_index.get_resources('packages', BOTH),
               ament_index.package_share_directory('beta', BOTH), ament_index.package_share_directory('zeta', BOTH))
    with ament_index.snapshot():
        for _ in range(2):  # listed, then remembered
            inside = ([ament_index.get_resource('nodl_interfaces', n, BOTH) for n in
                       ('alpha__chatter', 'zeta__x', '')], ament_index.get_resources('packages', BOTH),
                      ament_index.package_share_directory('beta', BOTH),
                      ament_index.package_share_directory('zeta', BOTH))
            assert inside == outside


def test_a_snapshot_lists_each_folder_once_and_ends_with_its_block(tmp_path: Path) -> None:
    folder = tmp_path / INDEX / 'nodl_nodes'
    (folder / 'p__a_folder').mkdir(parents=True)
    (folder / 'p__one').write_text('1')
    prefixes = [str(tmp_path)]
    with ament_index.snapshot():
        assert ament_index.get_resource('nodl_nodes', 'p__one', prefixes).content == '1'  # type: ignore[union-attr]
        (folder / 'p__two').write_text('2')  # after the listing: not seen in this run
        (folder / 'p__one').write_text('changed')  # already read: the run keeps what it read
        with ament_index.snapshot():  # a nested block shares the outer snapshot
            assert ament_index.get_resource('nodl_nodes', 'p__two', prefixes) is None
            assert ament_index.get_resources('nodl_nodes', prefixes) == {'p__one': str(tmp_path)}
        assert ament_index.get_resource('nodl_nodes', 'p__one', prefixes).content == '1'  # type: ignore[union-attr]
        assert ament_index.get_resource('nodl_nodes', 'p__a_folder', prefixes) is None
    assert ament_index.get_resource('nodl_nodes', 'p__two', prefixes).content == '2'  # type: ignore[union-attr]
    assert ament_index.get_resource('nodl_nodes', 'p__one', prefixes).content == 'changed'  # type: ignore[union-attr]


def test_a_snapshot_looks_a_name_with_a_separator_up_as_a_path(tmp_path: Path) -> None:
    (tmp_path / INDEX / 'nodl_nodes' / 'sub').mkdir(parents=True)
    (tmp_path / INDEX / 'nodl_nodes' / 'sub' / 'x').write_text('deep')
    outside = ament_index.get_resource('nodl_nodes', os.path.join('sub', 'x'), [str(tmp_path)])
    with ament_index.snapshot():
        assert ament_index.get_resource('nodl_nodes', os.path.join('sub', 'x'), [str(tmp_path)]) == outside


def test_remembered_computes_once_per_key_inside_a_snapshot_only() -> None:
    calls: list[str] = []

    def compute() -> int:
        calls.append('x')
        return len(calls)

    assert [ament_index.remembered('k', compute) for _ in range(2)] == [1, 2]
    with ament_index.snapshot():
        assert [ament_index.remembered('k', compute) for _ in range(3)] == [3, 3, 3]
        assert ament_index.remembered('other', compute) == 4
    assert ament_index.remembered('k', compute) == 5


def test_an_entry_reads_as_a_text_file_does(tmp_path: Path) -> None:
    # Entries are read through the file descriptor; the text is what open() in text mode gives.
    folder = tmp_path / INDEX / 'nodl_nodes'
    folder.mkdir(parents=True)
    raw = '\ufeffline one\r\nline two\rline three\n\u00e9'.encode('utf-8') + b'x' * 70000
    (folder / 'p__mixed').write_bytes(raw)
    with open(folder / 'p__mixed', encoding='utf-8') as f:
        expected = f.read()
    prefixes = [str(tmp_path)]
    assert ament_index.get_resource('nodl_nodes', 'p__mixed', prefixes).content == expected  # type: ignore[union-attr]
    with ament_index.snapshot():
        assert ament_index.get_resource('nodl_nodes', 'p__mixed', prefixes).content == expected  # type: ignore[union-attr]
    (folder / 'p__bad').write_bytes(b'ok\xff')
    with pytest.raises(UnicodeDecodeError):
        ament_index.get_resource('nodl_nodes', 'p__bad', prefixes)


def test_package_prefix_is_where_the_share_directory_is() -> None:
    for inside in (False, True):
        with ament_index.snapshot() if inside else contextlib.nullcontext():
            assert ament_index.package_prefix('alpha', BOTH) == FIRST
            assert ament_index.package_prefix('beta', BOTH) == SECOND
            assert ament_index.package_prefix('beta', [SECOND, FIRST]) == SECOND
            assert ament_index.package_prefix('zeta', BOTH) is None
            assert ament_index.package_prefix('', BOTH) is None


#: The modules that may read the ament index directly, and why: the registry (NoDL's
#: registrations) and the consumers of resources that are not NoDL's.
READERS = {
    'nodl/registry/registrations.py': "NoDL's registrations",
    'nodl/registry/node_info.py': "NoDL's node info entries",
    'nodl/registry/legacy.py': 'legacy nodl_desc markers and package manifests',
    'nodl/composition/client_library.py': "a package's build type (its package.xml)",
    'nodl/composition/bases.py': "the run's snapshot keeps one base layer per run",
    'nodl/interface_types/resolve.py': 'ROS interface types (rosidl_interfaces)',
    'nodl/launch/context.py': 'launch substitutions (find-pkg-prefix, find-pkg-share)',
}


def test_only_the_registry_and_non_nodl_consumers_read_the_index() -> None:
    import ast

    root = FIXTURES.parent.parent
    readers = set()
    for package in ('nodl', 'nodl_schema'):
        for path in sorted((root / package).rglob('*.py')):
            name = path.relative_to(root).as_posix()
            for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
                if isinstance(node, ast.ImportFrom) and node.module is not None:
                    modules = [f'{node.module}.{a.name}' for a in node.names] + [node.module]
                elif isinstance(node, ast.Import):
                    modules = [a.name for a in node.names]
                else:
                    continue
                if 'nodl.ament_index' in modules and name != 'nodl/ament_index.py':
                    readers.add(name)
    assert readers == set(READERS)
