"""Registered NoDL definitions (nodl_schema.index.registry)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from conftest import FIXTURES
from nodl_schema.composition import ResolutionError
from nodl_schema.index.registry import (
    Registration, describe_missing, find_node, list_registrations, read_registration)

FIRST = str(FIXTURES / 'index' / 'first')
SECOND = str(FIXTURES / 'index' / 'second')
BOTH = [FIRST, SECOND]
INDEX = os.path.join('share', 'ament_index', 'resource_index')


def share(prefix: str, package: str, name: str) -> str:
    return os.path.join(prefix, 'share', package, 'nodl', name)


def entry(prefix: str, resource_type: str, name: str) -> str:
    return os.path.join(prefix, INDEX, resource_type, name)


def test_list_registrations_of_every_package_sorted() -> None:
    assert list_registrations(prefixes=BOTH) == [
        Registration('alpha', 'chatter', 'interface', share(FIRST, 'alpha', 'chatter.nodl.yaml')),
        # a document held in the index entry is read from the entry
        Registration('alpha', 'inline', 'node', entry(FIRST, 'nodl_nodes', 'alpha__inline')),
        Registration('alpha', 'listener', 'node', share(SECOND, 'alpha', 'listener.nodl.yaml')),
        # in both prefixes: the first wins
        Registration('alpha', 'talker', 'node', share(FIRST, 'alpha', 'talker.nodl.yaml')),
        Registration('beta', 'node', 'node', share(SECOND, 'beta', 'node.nodl.yaml')),
        Registration('beta', 'status', 'interface', share(SECOND, 'beta', 'status.nodl.yaml')),
        # an entry pointing at a missing file is still listed (with the entry as its file)
        Registration('delta', 'dangling', 'node', entry(FIRST, 'nodl_nodes', 'delta__dangling')),
    ]


def test_list_registrations_of_one_package() -> None:
    assert [(r.name, r.kind) for r in list_registrations('beta', BOTH)] == [
        ('node', 'node'), ('status', 'interface')]
    assert list_registrations('gamma', BOTH) == []
    assert list_registrations('zeta', BOTH) == []


def test_the_prefix_order_decides_which_file_is_listed() -> None:
    talker = [r for r in list_registrations('alpha', [SECOND, FIRST]) if r.name == 'talker']
    assert talker == [Registration('alpha', 'talker', 'node',
                                   share(SECOND, 'alpha', 'talker.nodl.yaml'))]


def test_list_registrations_uses_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', SECOND)
    assert {(r.package, r.name) for r in list_registrations()} == {
        ('alpha', 'listener'), ('alpha', 'talker'), ('beta', 'node'), ('beta', 'status')}
    monkeypatch.setenv('AMENT_PREFIX_PATH', '')
    assert list_registrations() == []


def test_find_node_first_prefix_wins() -> None:
    found = find_node('alpha', 'talker', BOTH)
    assert found == Registration('alpha', 'talker', 'node', share(FIRST, 'alpha', 'talker.nodl.yaml'))
    assert 'FIRST prefix' in Path(found.file).read_text()
    found = find_node('alpha', 'talker', [SECOND, FIRST])
    assert 'SECOND prefix' in Path(found.file).read_text()


def test_find_node_finds_only_nodes() -> None:
    assert find_node('alpha', 'listener', BOTH).file == share(SECOND, 'alpha', 'listener.nodl.yaml')
    assert find_node('alpha', 'chatter', BOTH) is None  # an interface, not a node
    assert find_node('alpha', 'nope', BOTH) is None
    assert find_node('zeta', 'talker', BOTH) is None
    assert find_node('alpha', 'talker', []) is None


def test_find_node_of_a_dangling_entry_returns_the_entry() -> None:
    assert find_node('delta', 'dangling', BOTH) == Registration(
        'delta', 'dangling', 'node', entry(FIRST, 'nodl_nodes', 'delta__dangling'))


def test_find_node_uses_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', os.pathsep.join([SECOND, FIRST]))
    assert find_node('alpha', 'talker').file == share(SECOND, 'alpha', 'talker.nodl.yaml')


def test_read_registration() -> None:
    talker = find_node('alpha', 'talker', BOTH)
    resolved = read_registration(talker, BOTH)
    assert resolved.file == talker.file
    assert resolved.text == Path(talker.file).read_bytes()  # raw: the loader decodes it
    inline = find_node('alpha', 'inline', BOTH)
    resolved = read_registration(inline, BOTH)
    assert resolved.file == entry(FIRST, 'nodl_nodes', 'alpha__inline')
    assert 'A node definition held in the index entry itself.' in resolved.text
    chatter = next(r for r in list_registrations('alpha', BOTH) if r.name == 'chatter')
    assert read_registration(chatter, BOTH).text.startswith(b'nodl_version: 2\ndescription: Chatting.')


def test_read_registration_errors() -> None:
    with pytest.raises(ResolutionError) as exc:
        read_registration(find_node('delta', 'dangling', BOTH), BOTH)
    assert exc.value.message == (
        f"the index entry {entry(FIRST, 'nodl_nodes', 'delta__dangling')} points at "
        f"{share(FIRST, 'delta', 'gone.nodl.yaml')}, which does not exist (is the package fully "
        'installed?)')
    with pytest.raises(ResolutionError) as exc:
        read_registration(Registration('alpha', 'nope', 'node', 'x'), BOTH)
    assert exc.value.message == 'alpha/nope is not registered'


@pytest.mark.parametrize('package, executable, prefixes, message', [
    ('alpha', 'nope', BOTH,
     "package 'alpha' registers no node definition for 'nope' (it has: inline, listener, talker)"),
    ('beta', 'status', BOTH,  # an interface is not a node
     "package 'beta' registers no node definition for 'status' (it has: node)"),
    ('gamma', 'x', BOTH, "package 'gamma' registers no node definitions"),
    ('zeta', 'x', BOTH, "package 'zeta' is not in the ament index"),
    ('alpha', 'x', [], 'AMENT_PREFIX_PATH is empty; source the workspace (install/setup.bash) first'),
])
def test_describe_missing(package: str, executable: str, prefixes: list[str], message: str) -> None:
    assert find_node(package, executable, prefixes) is None
    assert describe_missing(package, executable, prefixes) == message


def test_describe_missing_uses_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv('AMENT_PREFIX_PATH', raising=False)
    assert describe_missing('alpha', 'x').startswith('AMENT_PREFIX_PATH is empty')
    monkeypatch.setenv('AMENT_PREFIX_PATH', FIRST)
    assert describe_missing('alpha', 'x') == (
        "package 'alpha' registers no node definition for 'x' (it has: inline, talker)")


def test_names_may_contain_double_underscores_after_the_package(tmp_path: Path) -> None:
    folder = tmp_path / INDEX / 'nodl_nodes'
    folder.mkdir(parents=True)
    (folder / 'pkg__my__exe').write_text('nodl_version: 2\nmain: {nodl_version: 2}\n')
    [registration] = list_registrations(prefixes=[str(tmp_path)])
    assert (registration.package, registration.name) == ('pkg', 'my__exe')
    assert find_node('pkg', 'my__exe', [str(tmp_path)]) is not None
