"""nodl doc's targets: a file, PACKAGE, PACKAGE/EXECUTABLE, a definitions folder, a launch file."""

from __future__ import annotations

import sys

from conftest import FIXTURES, REPO
from nodl.doc.blocks import Contents, Link, Table
from nodl.doc.collect import Displayer, collect
from nodl.targets.resolve import gather_definitions

DOC = FIXTURES / 'doc'
PREFIXES = [sys.prefix]


def _defs():  # type: ignore[no-untyped-def]
    return gather_definitions([str(DOC / 'defs')], use_config=False)


def test_a_definitions_folder_gives_package_and_node_pages_and_an_index() -> None:
    docs = collect([str(DOC / 'defs')], root=str(REPO), prefixes=PREFIXES)
    assert sorted(docs.pages) == ['doc_pkg/index', 'doc_pkg/listener', 'doc_pkg/talker', 'index']
    package = docs.pages['doc_pkg/index']
    links = [c[0] for row in next(b for b in package.blocks if isinstance(b, Table)).rows for c in row[:1]]
    assert links == [Link('listener', 'node-doc-pkg-listener', 'doc_pkg/listener'),
                     Link('talker', 'node-doc-pkg-talker', 'doc_pkg/talker')]
    contents = next(b for b in docs.pages['index'].blocks if isinstance(b, Contents))
    assert 'doc_pkg/talker' in contents.pages


def test_package_and_package_executable_targets_with_definitions_folders() -> None:
    docs = collect(['doc_pkg/talker'], root=str(REPO), prefixes=PREFIXES, definitions=_defs())
    assert sorted(docs.pages) == ['doc_pkg/talker', 'index'] and not docs.failed
    docs = collect(['doc_pkg'], root=str(REPO), prefixes=PREFIXES, definitions=_defs())
    assert 'doc_pkg/index' in docs.pages and 'doc_pkg/listener' in docs.pages


def test_targets_that_cannot_be_documented_are_errors_not_exceptions() -> None:
    docs = collect(['no/such/file.nodl.yaml', 'no_such_package', 'doc_pkg/nothing'],
                   root=str(REPO), prefixes=PREFIXES, definitions=_defs())
    assert docs.failed and docs.pages == {}
    codes = [d.code for d in docs.diagnostics]
    assert codes.count('NODL273') == 2 and len(codes) == 3


def test_paths_are_shown_relative_to_the_root_or_the_prefix() -> None:
    display = Displayer('/work/x', ['/opt/ros'])
    assert display('/work/x/a/b.yaml') == 'a/b.yaml'
    assert display('/opt/ros/share/p/n.yaml') == 'share/p/n.yaml'
    assert display('/elsewhere/n.yaml') == '/elsewhere/n.yaml'
    # a workspace's install inside the folder the pages are built from: still the prefix's
    # path, so that the pages are the same built from the workspace or from the package
    inside = Displayer('/ws', ['/ws/install/pkg'])
    assert inside('/ws/install/pkg/share/pkg/nodl/n.nodl.yaml') == 'share/pkg/nodl/n.nodl.yaml'
    assert inside('/ws/src/pkg/nodl/n.nodl.yaml') == 'src/pkg/nodl/n.nodl.yaml'


def test_a_launch_file_gives_the_system_page_and_its_node_pages() -> None:
    docs = collect([str(DOC / 'system.launch.xml')], root=str(REPO), prefixes=PREFIXES,
                   definitions=_defs())
    assert sorted(docs.pages) == ['doc_pkg/listener', 'doc_pkg/talker', 'index', 'systems/system']
    assert len(docs.pictures()) == 1
