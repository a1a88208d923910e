"""The one target resolution (nodl.targets.resolve): precedence, provenance, coverage."""

from __future__ import annotations

import os

import pytest

from conftest import FIXTURES
from nodl.config import ConfigError
from nodl.launch.model import LaunchedNode
from nodl.location import Location
from nodl.registry.registrations import one_run
from nodl.system.matching import DefinitionMatcher
from nodl.targets.resolve import (
    Provenance,
    coverage_line,
    gather_definitions,
    made_by,
    no_header,
    resolve_reference,
    resolve_target,
    target_name,
)

OVERLAYS = FIXTURES / 'overlays'
DEFS = str(OVERLAYS / 'defs')
SECOND = str(OVERLAYS / 'second')
PREFIXES = [str(FIXTURES / 'analysis' / 'prefix')]


def test_precedence_definitions_then_nodl_path_then_config(tmp_path) -> None:  # type: ignore[no-untyped-def]
    (tmp_path / 'nodl.toml').write_text('definitions = ["defs"]\n')
    (tmp_path / 'defs').mkdir()
    found = gather_definitions([SECOND], environ={'NODL_PATH': os.pathsep.join([DEFS, ''])},
                               start=str(tmp_path))
    assert [(f.root, f.given_by) for f in found.folders] == [
        (SECOND, '--definitions'), (DEFS, 'NODL_PATH'),
        (str(tmp_path / 'defs'), str(tmp_path / 'nodl.toml'))]
    (tmp_path / 'nodl.toml').write_text('definitions = "defs"\n')
    with pytest.raises(ConfigError, match="'definitions' must be a list"):
        gather_definitions([], environ={}, start=str(tmp_path))


def test_pyproject_table_is_read_relative_to_its_file(tmp_path) -> None:  # type: ignore[no-untyped-def]
    (tmp_path / 'pyproject.toml').write_text('[tool.nodl]\ndefinitions = ["../x"]\n')
    (tmp_path / 'sub').mkdir()
    found = gather_definitions([], environ={}, start=str(tmp_path / 'sub'))
    assert [f.root for f in found.folders] == [os.path.normpath(str(tmp_path / '..' / 'x'))]


def test_resolution_says_where_each_definition_came_from() -> None:
    definitions = gather_definitions([DEFS, SECOND], environ={}, use_config=False)
    driver = resolve_target(['upstream_drv', 'driver'], prefixes=PREFIXES, definitions=definitions)
    assert driver.node is not None and driver.provenance == Provenance('overlay', DEFS, None)
    # its nodl:// mixin came from the folder's interfaces/
    assert {e.name for e in driver.node.endpoints} >= {'status', 'scan'}
    controller = resolve_target(['nav', 'controller'], prefixes=PREFIXES, definitions=definitions)
    assert str(controller.provenance) == f'overlay {DEFS}, extracted'
    planner = resolve_target(['nav', 'planner'], prefixes=PREFIXES, definitions=definitions)
    assert planner.provenance == Provenance('index') and planner.node is not None
    file = resolve_target(f'{DEFS}/upstream_drv/fusion.nodl.yaml', prefixes=PREFIXES)
    assert file.provenance == Provenance('file', None, 'described')
    missing = resolve_target(['upstream_drv', 'nope'], prefixes=PREFIXES, definitions=definitions)
    assert missing.node is None and missing.provenance.source == 'none'
    assert [d.code for d in missing.diagnostics] == ['NODL306']
    assert DEFS in missing.diagnostics[0].message
    # without the folders the index alone answers
    assert resolve_target(['nav', 'controller'], prefixes=PREFIXES).provenance == Provenance('index')
    with pytest.raises(OSError, match='no such file'):
        resolve_target('no/such.nodl.yaml')


def test_references_resolve_from_the_folders_first() -> None:
    definitions = gather_definitions([DEFS], environ={}, use_config=False)
    text, file, problems = resolve_reference('nodl://upstream_drv/status', prefixes=PREFIXES,
                                             definitions=definitions)
    assert problems == [] and file.endswith('interfaces/status.nodl.yaml') and text
    text, _, problems = resolve_reference('nodl://upstream_drv/status', prefixes=PREFIXES)
    assert text is None and [d.code for d in problems] == ['NODL306']


def test_provenance_header(tmp_path) -> None:  # type: ignore[no-untyped-def]
    marked = tmp_path / 'a.nodl.yaml'
    marked.write_text('# nodl: generated; sha256=00\n# Extracted from talker.py by nodl extract\n')
    assert made_by(str(marked)) == 'extracted'
    marked.write_text('nodl_version: 2\n# Extracted from talker.py by nodl extract\n')
    assert made_by(str(marked)) is None  # a comment below the document is not its header
    assert made_by(str(tmp_path / 'missing')) is None
    # the headers nodl describe writes: one node, and a launched system (--all --launch)
    marked.write_text('# nodl: generated; sha256=00\n# Described from the running node /a by '
                      '`nodl describe`.\nnodl_version: 2\n')
    assert made_by(str(marked)) == 'described'
    marked.write_text('# nodl: generated; sha256=00\n# Described by `nodl describe --all --launch` '
                      'from the running system robot.launch.xml started.\n# Provenance: described; '
                      'a executable b, 1 instance:\nnodl_version: 2\n')
    assert made_by(str(marked)) == 'described'
    marked.write_text('# Described by hand, not by nodl describe\nnodl_version: 2\n')
    assert made_by(str(marked)) is None


def test_no_header_answers_without_reading_again_only_what_cannot_be_a_header() -> None:
    assert no_header('nodl_version: 2\n# Extracted from talker.py by nodl extract\n')
    assert no_header(b'\n \t{"nodl_version": 2}')
    # a comment, nothing, or a first character that is not ASCII: the file is read (made_by)
    assert not no_header('\n  # nodl: generated\n') and not no_header(b'#x')
    assert not no_header('') and not no_header(b' \n') and not no_header('\u3000# x')


def test_an_analysis_reads_a_registered_draft_header_from_the_file(tmp_path) -> None:  # type: ignore[no-untyped-def]
    index = tmp_path / 'share' / 'ament_index' / 'resource_index'
    for kind in ('packages', 'nodl_nodes'):
        (index / kind).mkdir(parents=True)
    definitions = {'drafted': '# nodl: generated; sha256=00\n# Extracted from a.py by nodl extract\n',
                   'plain': '', 'late': 'nodl_version: 2\n# Extracted from a.py by nodl extract\n'}
    for name, header in definitions.items():
        (index / 'packages' / name).write_text('')
        (index / 'nodl_nodes' / f'{name}__{name}').write_text(f'nodl/{name}.nodl.yaml')
        (tmp_path / 'share' / name / 'nodl').mkdir(parents=True)
        (tmp_path / 'share' / name / 'nodl' / f'{name}.nodl.yaml').write_text(
            header + ('' if header.startswith('nodl_version') else 'nodl_version: 2\n')
            + 'base: node\nmain: {nodl_version: 2}\n')
    matcher = DefinitionMatcher(prefixes=[str(tmp_path)])
    with one_run():
        made = {name: matcher.match(LaunchedNode('node', name, name, None, '/', Location('x', 1, 1)))
                for name in definitions}
    assert {name: m.provenance() for name, m in made.items()} == {
        'drafted': Provenance('index', None, 'extracted'), 'plain': Provenance('index'),
        'late': Provenance('index')}
    assert [m.problems for m in made.values() if m.resolved is None] == []


def test_coverage_line() -> None:
    sources = ['index'] * 9 + ['overlay'] * 6 + ['none']
    assert coverage_line(sources) == '16 nodes: 9 registered, 6 overlay, 1 without definition'
    assert coverage_line(['file', 'file']) == '2 nodes: 2 from files'
    assert coverage_line(['file', 'index']) == \
        '2 nodes: 1 registered, 0 overlay, 1 from files, 0 without definition'
    assert coverage_line([]) == '0 nodes'
    # drafts nodl extract or nodl describe wrote are counted within their source
    drafts = [Provenance('index'), Provenance('overlay', 'a', 'extracted'),
              Provenance('overlay', 'b', 'described'), Provenance('overlay', 'b', 'described'),
              Provenance('overlay', 'c'), Provenance('none')]
    assert coverage_line(drafts) == \
        '6 nodes: 1 registered, 4 overlay (1 extracted, 2 described), 1 without definition'
    assert coverage_line([Provenance('file', None, 'extracted')]) == '1 node: 1 from files (1 extracted)'


def test_an_invalid_file_resolves_to_its_diagnostics(tmp_path) -> None:  # type: ignore[no-untyped-def]
    bad = tmp_path / 'bad.nodl.yaml'
    bad.write_text('nodl_version: 2\nbase: nope\nmain: {nodl_version: 2}\n')
    found = resolve_target(str(bad))
    assert found.node is None and found.diagnostics and found.source == str(bad)
    assert found.provenance.source == 'file'


def test_target_name_is_the_executable_or_the_file() -> None:
    assert target_name(['pkg', 'exe']) == 'exe'
    assert target_name('dir/talker.nodl.yaml') == 'dir/talker.nodl.yaml'
