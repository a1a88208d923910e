"""Where things are written in a Python launch file (nodl_schema.launch.python_places)."""

from __future__ import annotations

import sys
from pathlib import Path

from nodl_schema.launch.model import SourceLocation
from nodl_schema.launch.python_places import frame_location, keyword_places


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
