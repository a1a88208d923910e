"""What a registration records besides the definition: plugin class and node name."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl.packaging import nodl_data_files
from nodl.registry.node_info import find_plugin, format_node_info, parse_node_info, plugin_key, read_node_info

PREFIX = [str(Path(__file__).parent / 'fixtures' / 'analysis' / 'prefix')]
SENSORS = Path(__file__).parent / 'fixtures' / 'analysis' / 'prefix' / 'share' / 'sensors'


def test_read_back_from_the_index() -> None:
    assert read_node_info('sensors', 'lidar_node', PREFIX).node_name == 'lidar'
    assert read_node_info('sensors', 'imu_filter', PREFIX).node_name is None
    found = find_plugin('sensors', 'sensors::CameraDriver', PREFIX)
    assert found is not None and found.key == 'camera_driver'
    assert find_plugin('sensors', 'sensors::Other', PREFIX) is None


@pytest.mark.parametrize(('plugin', 'key'), [
    ('rover_sensors::CameraDriver', 'camera_driver'), ('a::b::HTTPServer', 'http_server'),
    ('Lidar2D', 'lidar2_d'), ('talker', 'talker')])
def test_plugin_key_is_the_class_name_in_snake_case(plugin: str, key: str) -> None:
    assert plugin_key(plugin) == key


def test_format_and_parse_round_trip_and_refuse_bad_values() -> None:
    text = format_node_info('pkg::Class', 'node')
    assert parse_node_info('p', 'k', text + 'future=1\n') == ('p', 'k', 'pkg::Class', 'node')
    with pytest.raises(ValueError):
        format_node_info('pkg:Class')
    with pytest.raises(ValueError):
        format_node_info(None, 'bad-name')


def test_the_setup_py_helper_records_them(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(SENSORS)
    entries = dict(nodl_data_files('sensors', nodes={'camera_driver': 'nodl/camera.nodl.yaml'},
                                   validate=False, staging_dir=str(tmp_path),
                                   plugins={'camera_driver': 'sensors::CameraDriver'},
                                   node_names={'camera_driver': 'camera'}))
    markers = entries['share/ament_index/resource_index/nodl_node_info']
    assert Path(markers[0]).name == 'sensors__camera_driver'
    assert parse_node_info('sensors', 'camera_driver', Path(markers[0]).read_text()) == \
        ('sensors', 'camera_driver', 'sensors::CameraDriver', 'camera')
    with pytest.raises(SystemExit, match="names 'other', which is not in nodes"):
        nodl_data_files('sensors', nodes={'camera_driver': 'nodl/camera.nodl.yaml'},
                        validate=False, staging_dir=str(tmp_path), node_names={'other': 'x'})
