"""Where things are written in a Python launch file (nodl.launch.python_places)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from nodl.launch.model import SourceLocation
from nodl.launch.python_places import frame_location, keyword_places


def test_keyword_places_point_at_each_item_of_a_literal_list(tmp_path: Path) -> None:
    launch = tmp_path / 'x.launch.py'
    launch.write_text("Node(package='p',\n     remappings=[('a', 'b'),\n                 ('c', 'd')],\n"
                      "     parameters=params)\n")
    call = SourceLocation(str(launch), 1, 1)
    places = keyword_places(call, 'remappings')
    assert isinstance(places, list)
    assert [(p.line, p.column) for p in places] == [(2, 18), (3, 18)]
    whole = keyword_places(call, 'parameters')
    assert isinstance(whole, SourceLocation) and (whole.line, whole.column) == (4, 17)
    assert keyword_places(call, 'arguments') is None
    assert keyword_places(SourceLocation(str(launch), 9, 1), 'remappings') is None


def test_frame_location_finds_the_innermost_frame_of_the_file(tmp_path: Path) -> None:
    launch = tmp_path / 'y.launch.py'
    launch.write_text('import sys\n\ndef where():\n    return sys._getframe()\n\nframe = where()\n')
    namespace: dict[str, object] = {}
    exec(compile(launch.read_text(), str(launch), 'exec'), namespace)
    found = frame_location(str(launch), namespace['frame'])
    assert (found.file, found.line) == (str(launch), 4)
    assert found.column >= 1
    assert frame_location('/no/such/file.py', sys._getframe()).line == 0


def test_a_list_given_through_a_variable_is_placed_where_it_is_written(tmp_path: Path) -> None:
    """remappings=common (common = [...] assigned once in the function, or in the module),
    [*common, ...] and common + [...]: each item at the place it is written, so one rule
    given to many nodes is at one place; a parameter of the function or a name assigned
    twice is not plain to see (the argument's place)."""
    launch = tmp_path / 'v.launch.py'
    launch.write_text(
        "SHARED = [('x', 'y')]\n"                                   # 1
        "def generate_launch_description():\n"                       # 2
        "    common = [('a', 'b'),\n"                                # 3
        "              ('c', 'd')]\n"                                # 4
        "    Node(remappings=common)\n"                              # 5
        "    Node(remappings=[*common, ('e', 'f')])\n"               # 6
        "    Node(remappings=common + SHARED)\n"                     # 7
        "    twice = []\n"                                           # 8
        "    twice = [('g', 'h')]\n"                                 # 9
        "    Node(remappings=twice)\n"                               # 10
        "def make(rules):\n"                                         # 11
        "    return Node(remappings=rules)\n")                       # 12
    def at(line: int, column: int) -> list[tuple[int, int]] | tuple[int, int]:
        found = keyword_places(SourceLocation(str(launch), line, column), 'remappings')
        if isinstance(found, list):
            return [(p.line, p.column) for p in found]
        assert found is not None
        return (found.line, found.column)
    assert at(5, 5) == [(3, 15), (4, 15)]
    assert at(6, 5) == [(3, 15), (4, 15), (6, 31)]
    assert at(7, 5) == [(3, 15), (4, 15), (1, 11)]
    assert at(10, 5) == (10, 21)
    assert at(12, 12) == (12, 28)


def test_a_function_s_assignments_are_read_once_for_all_its_calls(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Twenty nodes of one function given remappings=common: the function's assignments (and
    the module's) are read once, not once per node, and every node's rules are placed at the
    one place they are written; a name assigned twice is still not plain to see (the
    argument's own place)."""
    from nodl.launch import python_places

    launch = tmp_path / 'many.launch.py'
    nodes = ''.join(f"        Node(name='n{i}', remappings=common),\n" for i in range(20))
    launch.write_text("def generate_launch_description():\n"
                      "    common = [('/tf', 'tf'), ('/tf_static', 'tf_static')]\n"
                      "    twice = []\n    twice = [('a', 'b')]\n"
                      f"    return [\n{nodes}        Node(name='x', remappings=twice),\n    ]\n")
    reads: list[object] = []
    real = python_places._assignments

    def counted(where: object) -> dict[str, list[object]]:
        reads.append(where)
        return real(where)  # type: ignore[arg-type]

    monkeypatch.setattr(python_places, '_assignments', counted)
    for line in range(6, 26):
        places = keyword_places(SourceLocation(str(launch), line, 9), 'remappings')
        assert isinstance(places, list)
        assert [(p.line, p.column) for p in places] == [(2, 15), (2, 30)]
    assert len(reads) == 1
    whole = keyword_places(SourceLocation(str(launch), 26, 9), 'remappings')
    assert isinstance(whole, SourceLocation) and (whole.line, whole.column) == (26, 35)
    assert len(reads) == 1
