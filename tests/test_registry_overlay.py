"""Definitions folders (nodl.registry.overlay): layout, checks, precedence, look-ups."""

from __future__ import annotations

from conftest import FIXTURES
from nodl.registry import node_info, registrations
from nodl.registry.overlay import Definitions, active, read_folder, read_folders, using

OVERLAYS = FIXTURES / 'overlays'
DEFS = str(OVERLAYS / 'defs')
SECOND = str(OVERLAYS / 'second')
BAD = str(OVERLAYS / 'bad')


def test_a_folder_is_read_by_package() -> None:
    folder = read_folder(DEFS)
    assert folder.diagnostics == []
    assert sorted(folder.nodes) == [('nav', 'controller'), ('upstream_drv', 'driver'),
                                    ('upstream_drv', 'fusion')]
    assert folder.interfaces == {('upstream_drv', 'status'):
                                 f'{DEFS}/upstream_drv/interfaces/status.nodl.yaml'}
    assert folder.info[('upstream_drv', 'fusion')] == ('upstream_drv::Fusion', 'fusion')
    assert folder.label == f'overlay {DEFS}'


def test_every_layout_error_is_one_located_diagnostic() -> None:
    found = {(d.file.removeprefix(BAD + '/'), d.line, d.column, d.code, d.severity.value)
             for d in read_folder(BAD).diagnostics}
    assert found == {
        ('stray.nodl.yaml', 0, 0, 'NODL240', 'error'),          # outside any package folder
        ('Not-A-Package', 0, 0, 'NODL243', 'error'),            # not a package name
        ('my_pkg/extra', 0, 0, 'NODL240', 'error'),             # a folder but interfaces/
        ('my_pkg/notes.txt', 0, 0, 'NODL240', 'error'),         # not a definition
        ('my_pkg/interfaces/todo.txt', 0, 0, 'NODL240', 'error'),
        ('my_pkg/nodes.yaml', 2, 11, 'NODL242', 'error'),       # a plugin of another package
    }
    # README.md is left alone; the well-placed definition still serves
    assert read_folder(BAD).nodes == {('my_pkg', 'node'): f'{BAD}/my_pkg/node.nodl.yaml'}


def test_nodes_file_and_duplicates(tmp_path) -> None:  # type: ignore[no-untyped-def]
    package = tmp_path / 'pkg'
    package.mkdir()
    (package / 'a.nodl.yaml').write_text('nodl_version: 2\n')
    (package / 'a.nodl.json').write_text('{}\n')
    (package / 'nodes.yaml').write_text('a: {plugin: pkg::A, colour: red}\nb: {node_name: 1x}\n'
                                        'c: [1]\n')
    codes = sorted((d.code, d.line, d.column) for d in read_folder(str(tmp_path)).diagnostics)
    assert codes == [('NODL244', 1, 21), ('NODL244', 2, 16), ('NODL244', 3, 4),
                     ('NODL245', 2, 1), ('NODL247', 0, 0)]
    (package / 'nodes.yaml').write_text('a: [unclosed\n')
    assert sorted(d.code for d in read_folder(str(tmp_path)).diagnostics) == ['NODL244', 'NODL247']


def test_a_missing_folder_is_a_diagnostic_not_an_exception(tmp_path) -> None:  # type: ignore[no-untyped-def]
    folder = read_folder(str(tmp_path / 'nowhere'), 'NODL_PATH')
    assert [(d.code, 'NODL_PATH' in d.message) for d in folder.diagnostics] == [('NODL246', True)]


def test_first_folder_wins_and_a_folder_given_twice_is_read_once() -> None:
    both = read_folders([(DEFS, '--definitions'), (SECOND, '--definitions'), (DEFS, 'NODL_PATH')])
    assert [f.root for f in both.folders] == [DEFS, SECOND]
    assert both.find_node('upstream_drv', 'driver') == (f'{DEFS}/upstream_drv/driver.nodl.yaml',
                                                        both.folders[0])
    swapped = read_folders([(SECOND, '--definitions'), (DEFS, '--definitions')])
    assert swapped.find_node('upstream_drv', 'driver')[0].startswith(SECOND)  # type: ignore[index]
    names = [(e.package, e.name, f.root) for e, f in swapped.entries('upstream_drv')]
    assert names == [('upstream_drv', 'driver', SECOND), ('upstream_drv', 'fusion', DEFS),
                     ('upstream_drv', 'status', DEFS)]


def test_the_index_lookups_consult_the_folders_in_force(tmp_path) -> None:  # type: ignore[no-untyped-def]
    prefixes = [str(FIXTURES / 'analysis' / 'prefix')]
    definitions = Definitions([read_folder(DEFS)])
    assert registrations.find_node('upstream_drv', 'driver', prefixes) is None
    assert registrations.find_node('nav', 'controller', prefixes).origin == 'index'  # type: ignore[union-attr]
    with using(definitions):
        assert active() is definitions
        found = registrations.find_node('nav', 'controller', prefixes)
        assert found is not None and found.origin == f'overlay {DEFS}'
        assert found.file == f'{DEFS}/nav/controller.nodl.yaml'
        assert registrations.find_node('nav', 'planner', prefixes).origin == 'index'  # type: ignore[union-attr]
        assert node_info.find_plugin('upstream_drv', 'upstream_drv::Fusion', prefixes) == \
            node_info.NodeInfo('upstream_drv', 'fusion', 'upstream_drv::Fusion', 'fusion')
        assert node_info.read_node_info('upstream_drv', 'driver', prefixes).node_name == 'drv'
        listed = {(r.package, r.name, r.kind, r.origin.split()[0])
                  for r in registrations.list_registrations('nav', prefixes)}
        assert listed == {('nav', 'controller', 'node', 'overlay'), ('nav', 'planner', 'node', 'index')}
    assert active() is None


def test_nodes_file_keys_sorted_after_it_name_definitions(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # 'talker' sorts after 'nodes.yaml': the keys are checked once every definition is read
    package = tmp_path / 'pkg'
    package.mkdir()
    (package / 'talker.nodl.yaml').write_text('nodl_version: 2\n')
    (package / 'nodes.yaml').write_text('talker: {plugin: pkg::Talker, node_name: talker}\n')
    folder = read_folder(str(tmp_path))
    assert folder.diagnostics == []
    assert folder.info[('pkg', 'talker')] == ('pkg::Talker', 'talker')
