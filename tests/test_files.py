"""Finding NoDL files (nodl_schema.files)."""

from __future__ import annotations

import os

from conftest import FIXTURES
from nodl_schema.files import STDIN, Target, find_nodl_files

TREE = FIXTURES / 'tree'


def test_directories_are_searched_recursively_for_the_three_suffixes() -> None:
    targets = find_nodl_files([str(TREE)])
    assert [os.path.relpath(t.path, TREE) for t in targets if t.problem is None] == [
        'a.nodl.yaml', os.path.join('sub', 'b.nodl.json'), os.path.join('sub', 'c.nodl.yml')]


def test_explicit_files_are_taken_whatever_their_extension() -> None:
    path = str(TREE / 'sub' / 'ignored.yaml')
    assert find_nodl_files([path]) == [Target(path)]


def test_stdin_and_problems_keep_their_order() -> None:
    empty = str(TREE / 'empty_dir')
    targets = find_nodl_files(['-', 'missing.yaml', empty])
    assert targets[0] == Target(STDIN)
    assert targets[1] == Target('missing.yaml', 'no such file or directory')
    assert targets[2].path == empty and 'no NoDL files' in (targets[2].problem or '')
