"""nodl analyse, type-definition-mismatch (nodl.system.checks.types): a topic's endpoints share a
type name, but the overlay its publisher is installed in has another std_msgs/msg/String."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

from nodl.analysis import analyse_launch
from nodl.system.checks.types import TypeDefinitionCheck

VENV = Path(sys.prefix)
INDEX = Path('share') / 'ament_index' / 'resource_index'
QOS = '{history: KEEP_LAST, depth: 10, reliability: RELIABLE}'


def _package(prefix: Path, package: str, executable: str, section: str) -> None:
    (prefix / INDEX / 'packages').mkdir(parents=True, exist_ok=True)
    (prefix / INDEX / 'packages' / package).write_text('', encoding='utf-8')
    (prefix / INDEX / 'nodl_nodes').mkdir(parents=True, exist_ok=True)
    (prefix / INDEX / 'nodl_nodes' / f'{package}__{executable}').write_text(
        f'nodl/{executable}.nodl.yaml', encoding='utf-8')
    (prefix / 'share' / package / 'nodl').mkdir(parents=True)
    (prefix / 'share' / package / 'nodl' / f'{executable}.nodl.yaml').write_text(
        'nodl_version: 2\nbase: node\nmain:\n  nodl_version: 2\n'
        f'  {section}:\n    - {{name: /chatter, type: std_msgs/msg/String, description: Text., '
        f'qos: {QOS}}}\n', encoding='utf-8')


def _system(tmp_path: Path, modified: bool) -> list:  # type: ignore[type-arg]
    overlay, underlay = tmp_path / 'overlay', tmp_path / 'underlay'
    _package(overlay, 'talker_pkg', 'talker', 'publishers')
    _package(underlay, 'listener_pkg', 'listener', 'subscriptions')
    if modified:  # the overlay builds its own std_msgs, whose String has one more field
        shutil.copytree(VENV / 'share' / 'std_msgs' / 'msg', overlay / 'share' / 'std_msgs' / 'msg')
        (overlay / 'share' / 'std_msgs' / 'msg' / 'String.idl').unlink()
        (overlay / 'share' / 'std_msgs' / 'msg' / 'String.msg').write_text(
            'string data\nint32 revision\n', encoding='utf-8')
        (overlay / INDEX / 'rosidl_interfaces').mkdir(parents=True)
        listing = (VENV / INDEX / 'rosidl_interfaces' / 'std_msgs').read_text(encoding='utf-8')
        (overlay / INDEX / 'rosidl_interfaces' / 'std_msgs').write_text(
            listing.replace('msg/String.idl\n', ''), encoding='utf-8')
    launch = tmp_path / 'system.launch.xml'
    launch.write_text('<launch>\n  <node pkg="talker_pkg" exec="talker" name="talker"/>\n'
                      '  <node pkg="listener_pkg" exec="listener" name="listener"/>\n</launch>\n',
                      encoding='utf-8')
    # the check alone (as registered in pyproject's nodl.checks entry points)
    analysis = analyse_launch(launch, prefixes=[str(overlay), str(underlay), str(VENV)],
                              checks={'type-definition-mismatch': TypeDefinitionCheck()})
    return [f for f in analysis.findings if f.kind == 'type-definition-mismatch']


def test_different_definitions_of_one_type_name_are_found(tmp_path: Path) -> None:
    found = _system(tmp_path, modified=True)
    assert len(found) == 1
    finding = found[0]
    assert finding.code == 'NODL570'
    assert finding.to_dict().get('endpoint') == '/chatter'
    assert 'std_msgs/msg/String but 2 different definitions' in finding.diagnostic.message
    assert str(tmp_path / 'overlay') in finding.diagnostic.message
    assert finding.diagnostic.file.endswith('system.launch.xml') and finding.diagnostic.line == 2


def test_one_definition_is_quiet(tmp_path: Path) -> None:
    assert _system(tmp_path, modified=False) == []
