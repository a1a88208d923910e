"""nodl.studio.layout: the positions' side file next to the launch file."""

from __future__ import annotations

from pathlib import Path

from nodl.studio.layout import layout_file, read_layout, write_layout


def test_positions_are_written_and_read_back(tmp_path: Path) -> None:
    launch = str(tmp_path / 'rover.launch.xml')
    path = write_layout(launch, {'/rover/lidar': {'x': 10.04, 'y': -3}, '/a': {'x': 0, 'y': 1}})
    assert path == layout_file(launch) == launch + '.studio.json'
    assert Path(path).read_text() == ('{\n "version": 1,\n "positions": {\n  "/a": {\n   "x": 0.0,\n'
                                      '   "y": 1.0\n  },\n  "/rover/lidar": {\n   "x": 10.0,\n'
                                      '   "y": -3.0\n  }\n }\n}\n')
    assert read_layout(launch) == {'/a': {'x': 0.0, 'y': 1.0}, '/rover/lidar': {'x': 10.0, 'y': -3.0}}


def test_a_missing_or_broken_side_file_is_an_empty_layout(tmp_path: Path) -> None:
    launch = str(tmp_path / 'rover.launch.xml')
    assert read_layout(launch) == {}
    Path(layout_file(launch)).write_text('{not json')
    assert read_layout(launch) == {}
    Path(layout_file(launch)).write_text('{"positions": {"/a": {"x": true, "y": 1}, "/b": [1, 2],'
                                         ' "/c": {"x": 1, "y": 2}}}')
    assert read_layout(launch) == {'/c': {'x': 1.0, 'y': 2.0}}


def test_a_link_at_the_side_file_is_replaced_not_followed(tmp_path: Path) -> None:
    target = tmp_path / 'elsewhere.json'
    target.write_text('keep')
    launch = str(tmp_path / 'rover.launch.xml')
    Path(layout_file(launch)).symlink_to(target)
    write_layout(launch, {'/a': {'x': 1, 'y': 2}})
    assert target.read_text() == 'keep'
    assert not Path(layout_file(launch)).is_symlink()
