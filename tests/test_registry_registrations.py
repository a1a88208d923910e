"""Registered NoDL definitions (nodl.registry.registrations)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import nodl
from conftest import FIXTURES
from nodl.composition import ResolutionError
from nodl.registry.registrations import Registration, describe_missing, find_node, list_registrations, read_registration

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


# -- what the reference implementation's current ament_nodl_register installs ---------------
# tests/fixtures/index/reference is such an install: nodl/<package>__<name> entries holding
# the (local:// -> nodl:// rewritten) documents, copies under share/<package>/nodl/, and a
# PACKAGE override (custom_pkg) that is no installed package.

REFERENCE = str(FIXTURES / 'index' / 'reference')


def reference_entry(name: str) -> str:
    return entry(REFERENCE, 'nodl', name)


def test_the_reference_registrations_are_listed_as_nodes() -> None:
    assert list_registrations(prefixes=[REFERENCE]) == [
        Registration('custom_pkg', 'custom_exe', 'node', reference_entry('custom_pkg__custom_exe')),
        Registration('ref_robot', 'lidar', 'node', reference_entry('ref_robot__lidar')),
        Registration('ref_robot', 'listener', 'node', reference_entry('ref_robot__listener')),
        Registration('ref_robot', 'sensor_common', 'node', reference_entry('ref_robot__sensor_common')),
        Registration('ref_robot', 'talker', 'node', reference_entry('ref_robot__talker')),
    ]
    assert list_registrations('ref_robot', [REFERENCE], kind='interface') == []
    assert [r.name for r in list_registrations('custom_pkg', [REFERENCE], kind='node')] == ['custom_exe']


def test_a_reference_registration_is_found_and_read_as_a_node() -> None:
    found = find_node('ref_robot', 'talker', [REFERENCE])
    assert found == Registration('ref_robot', 'talker', 'node', reference_entry('ref_robot__talker'))
    assert 'Publishes greetings' in read_registration(found, [REFERENCE]).text
    assert find_node('ref_robot', 'nothing', [REFERENCE]) is None
    assert describe_missing('ref_robot', 'nothing', [REFERENCE]) == (
        "package 'ref_robot' registers no node definition for 'nothing' (it has: lidar, listener, "
        'sensor_common, talker)')


def test_a_node_of_our_own_registration_wins_over_the_references(tmp_path: Path) -> None:
    own = tmp_path / 'share' / 'ament_index' / 'resource_index' / 'nodl_nodes'
    own.mkdir(parents=True)
    (own / 'ref_robot__talker').write_text('nodl_version: 2\nmain:\n  nodl_version: 2\n')
    prefixes = [REFERENCE, str(tmp_path)]
    talker = [r for r in list_registrations('ref_robot', prefixes) if r.name == 'talker']
    assert talker == [Registration('ref_robot', 'talker', 'node', str(own / 'ref_robot__talker'))]
    assert find_node('ref_robot', 'talker', prefixes) == talker[0]


def test_a_flat_reference_document_composes_as_a_node_of_its_interface() -> None:
    from nodl.registry.registrations import compose_registered

    composed, diagnostics, source = compose_registered('ref_robot', 'talker', [REFERENCE])
    assert composed is not None, diagnostics
    assert source == reference_entry('ref_robot__talker')
    # No dialect warning for an installed document: its user cannot convert it.
    assert [d.code for d in diagnostics] == []
    assert [layer.label for layer in composed.layers] == ['main']
    assert set(composed.interface.parameters) == {'greeting'}
    assert composed.node.codegen == composed.interface.codegen == {
        'cpp': {'role': 'base_class', 'header': 'ref_robot/talker_base.hpp'}}


def test_rewritten_includes_resolve_through_the_reference_registrations() -> None:
    from nodl.registry.registrations import compose_registered

    composed, diagnostics, _ = compose_registered('ref_robot', 'lidar', [REFERENCE], 'rclcpp')
    assert composed is not None, diagnostics
    assert [layer.label for layer in composed.layers] == [
        'base:node', 'nodl://ref_robot/sensor_common', 'main']
    assert {'frame_id', 'use_sim_time'} <= set(composed.interface.parameters)
    assert '/clock' in {s.name for s in composed.interface.subscriptions}
    assert composed.interface.codegen == {'cpp': {'role': 'base_class'}}


def test_a_missing_nodl_reference_names_both_resource_types(tmp_path: Path) -> None:
    from nodl import compose

    text = 'nodl_version: 2\ninclude:\n  - ref: nodl://ref_robot/no_such\n'
    with pytest.raises(nodl.ValidationError) as caught:
        compose(text, prefixes=[REFERENCE])
    [error] = caught.value.errors
    assert ("package 'ref_robot' registers no interface definition 'no_such' (it registers: lidar, "
            'listener, sensor_common, talker)') in error.message
    assert reference_entry('ref_robot__no_such') in error.message


def test_a_package_installed_by_a_re_creation_of_the_references_macro(tmp_path: Path) -> None:
    # Configure and install a real CMake package with tests/fixtures/reference_ament_nodl's
    # re-creation of the reference's ament_nodl_register, then read the install.
    import shutil
    import subprocess
    import sys

    here = FIXTURES / 'reference_ament_nodl'
    cmake = shutil.which('cmake')
    assert cmake is not None, 'cmake is needed (it is installed with the ROS build tools)'
    build, install = tmp_path / 'build', tmp_path / 'install'
    for step in ([cmake, '-S', str(here / 'ref_pkg'), '-B', str(build),
                  f'-DNODL_TEST_MACRO={here / "ament_nodl_register.cmake"}'],
                 [cmake, '--install', str(build), '--prefix', str(install)]):
        done = subprocess.run(step, capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, done.stdout + done.stderr
    prefixes = [str(install)]
    assert [(r.package, r.name, r.kind) for r in list_registrations(prefixes=prefixes)] == [
        ('other_pkg', 'reset_node', 'node'), ('ref_pkg', 'camera', 'node'),
        ('ref_pkg', 'sensor_common', 'node')]
    # The local:// include was rewritten on install; it resolves through the index.
    entry_text = (install / 'share' / 'ament_index' / 'resource_index' / 'nodl' / 'ref_pkg__camera')
    assert '- ref: nodl://ref_pkg/sensor_common' in entry_text.read_text()
    from nodl.registry.registrations import compose_registered

    composed, diagnostics, _ = compose_registered('ref_pkg', 'camera', prefixes)
    assert composed is not None, diagnostics
    assert [layer.label for layer in composed.layers] == ['base:node', 'nodl://ref_pkg/sensor_common', 'main']
    assert composed.interface.parameters['frame_id'].default_value == 'camera_link'
    assert composed.node.codegen == {'cpp': {'role': 'base_class'}}
    shown = subprocess.run([sys.executable, '-m', 'nodl', 'show', 'other_pkg', 'reset_node'],
                           cwd=FIXTURES.parent.parent, env=dict(os.environ, AMENT_PREFIX_PATH=str(install)),
                           text=True,
                           capture_output=True, timeout=60)
    assert shown.returncode == 0, shown.stderr
    assert '~/reset' in shown.stdout


def test_find_interface_reads_the_first_registration_and_its_entry() -> None:
    from nodl.registry.registrations import find_interface, interface_entry

    found = interface_entry('alpha', 'chatter', prefixes=BOTH)
    assert found is not None and found.path == entry(FIRST, 'nodl_interfaces', 'alpha__chatter')
    assert interface_entry('alpha', 'chatter', 'nodl', BOTH) is None
    assert find_interface('alpha', 'chatter', BOTH).file == share(FIRST, 'alpha', 'chatter.nodl.yaml')


def test_find_interface_says_what_the_package_registers() -> None:
    from nodl.registry.registrations import find_interface

    with pytest.raises(ResolutionError, match=r"registers no interface definition 'nope' "
                                              r'\(it registers: chatter\)') as caught:
        find_interface('alpha', 'nope', BOTH)
    assert caught.value.searched == [entry(p, t, 'alpha__nope') for t in ('nodl_interfaces', 'nodl')
                                     for p in BOTH]
    with pytest.raises(ResolutionError, match="package 'zeta' is not in the ament index "
                                              r'\(prefixes searched: '):
        find_interface('zeta', 'x', BOTH)
    with pytest.raises(ResolutionError, match='no ament prefix was given'):
        find_interface('alpha', 'chatter', [])


def test_search_path_is_the_given_prefixes_else_ament_prefix_path(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from nodl.registry.registrations import search_path

    monkeypatch.setenv('AMENT_PREFIX_PATH', os.pathsep.join([SECOND, FIRST, SECOND]))
    assert search_path() == [SECOND, FIRST]
    assert search_path(BOTH) == BOTH
    assert search_path([]) == []


def test_one_run_reads_each_registered_document_once() -> None:
    from nodl import ament_index
    from nodl.registry.registrations import one_run, read_registered

    resource = ament_index.get_resource('nodl_nodes', 'alpha__talker', BOTH)
    assert resource is not None
    assert read_registered(resource, 'alpha') is not read_registered(resource, 'alpha')
    with one_run():
        assert ament_index.in_snapshot()
        assert read_registered(resource, 'alpha') is read_registered(resource, 'alpha')
    assert not ament_index.in_snapshot()


def test_checked_registration_is_read_once_within_a_run_and_composed_from() -> None:
    from unittest import mock

    from nodl import loading
    from nodl.registry import registrations
    from nodl.registry.registrations import checked_registration, compose_registered, one_run

    talker = find_node('alpha', 'talker', BOTH)
    assert talker is not None
    report = checked_registration(talker, BOTH)
    assert report.file == talker.file and not report.has_errors()
    assert report.data == loading.check_source(Path(talker.file), kind='node', file=talker.file).data
    assert checked_registration(talker, BOTH) is not report  # outside a run: read each time
    with one_run():
        first = checked_registration(talker, BOTH)
        assert checked_registration(talker, BOTH) is first
        with mock.patch.object(registrations.loading, 'check_source',
                               side_effect=AssertionError('read again')):
            composed, diagnostics, source = compose_registered('alpha', 'talker', BOTH)
    assert composed is not None and source == talker.file
    dangling = find_node('delta', 'dangling', BOTH)
    assert dangling is not None
    with pytest.raises(ResolutionError):
        checked_registration(dangling, BOTH)
