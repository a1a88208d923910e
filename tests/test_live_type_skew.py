"""Version skew (nodl_schema.live.type_skew): a real node built against one definition of
std_msgs/msg/String, checked while the index reads another (a modified copy installed in a
private prefix in front of the environment's)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path
from typing import Iterator

import pytest

from conftest import NodeProcess
from nodl_schema.live.check import check_node
from nodl_schema.live.describe import describe_node, render_description

VENV = Path(sys.prefix)
INDEX = Path('share') / 'ament_index' / 'resource_index' / 'rosidl_interfaces'


@pytest.fixture(scope='module')
def typed() -> Iterator[NodeProcess]:
    node = NodeProcess('typed_node.py', 'typed', '/skew')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def definition(typed: NodeProcess, tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp('skew') / 'typed.nodl.yaml'
    path.write_text(render_description(describe_node(typed.fqn, timeout=15)), encoding='utf-8')
    return path


def _modified_std_msgs(root: Path) -> Path:
    """A prefix whose std_msgs has a String with one more field (its .msg only: no .idl)."""
    prefix = root / 'prefix'
    (prefix / INDEX).mkdir(parents=True)
    shutil.copytree(VENV / 'share' / 'std_msgs' / 'msg', prefix / 'share' / 'std_msgs' / 'msg')
    (prefix / 'share' / 'std_msgs' / 'msg' / 'String.idl').unlink()
    (prefix / 'share' / 'std_msgs' / 'msg' / 'String.msg').write_text(
        'string data\nint32 revision\n', encoding='utf-8')
    listing = (VENV / INDEX / 'std_msgs').read_text(encoding='utf-8').splitlines()
    (prefix / INDEX / 'std_msgs').write_text(
        '\n'.join(line for line in listing if line != 'msg/String.idl') + '\n', encoding='utf-8')
    return prefix


def test_the_same_definition_installed_is_no_skew(typed: NodeProcess, definition: Path,
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(VENV))
    result = check_node(typed.fqn, definition, timeout=15)
    assert not [d for d in result.differences if d.code in ('NODL420', 'NODL421')]
    assert result.conforms


def test_a_modified_installed_message_is_a_skew_naming_the_field(
        typed: NodeProcess, definition: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = _modified_std_msgs(tmp_path)
    monkeypatch.setenv('AMENT_PREFIX_PATH', f'{prefix}:{VENV}')
    result = check_node(typed.fqn, definition, timeout=15)
    skew = [d for d in result.differences if d.kind == 'version_skew']
    assert [d.name for d in skew] == ['/skew/chatter']
    assert not result.conforms
    message = skew[0].message
    assert "field 'revision' (int32) is in the installed definition, not in the running node's" in message
    diagnostic = result.diagnostic(skew[0])
    assert diagnostic.code == 'NODL420' and diagnostic.file == str(definition) and diagnostic.line > 1
    # the check can be told not to compare hashes
    assert not [d for d in check_node(typed.fqn, definition, timeout=15, types=False).differences
                if d.kind == 'version_skew']
