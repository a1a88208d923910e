"""nodl.extract.diff: the source against a definition, each difference a coded diagnostic."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl.diagnostics import ValidationError
from nodl.extract.diff import diff_node
from nodl.extract.python import extract_source

SOURCE = '''import rclpy
from rclpy.node import Node
from std_msgs.msg import String, Bool


class Talker(Node):
    def __init__(self, topic):
        super().__init__('talker')
        self.declare_parameter('rate', 2.0)
        self.create_publisher(String, 'chatter', 5)
        self.create_publisher(String, 'extra', 10)
        self.create_subscription(Bool, 'stop', lambda m: None, 10)
        self.create_publisher(String, topic, 10)
'''

DEFINITION = '''nodl_version: 2
base: lifecycle_node
main:
  nodl_version: 2
  parameters:
    rate: {type: double, default_value: 1.0}
  publishers:
    - {name: chatter, type: std_msgs/msg/String, qos: {history: KEEP_LAST, depth: 10, reliability: RELIABLE}}
    - {name: gone, type: std_msgs/msg/String, qos: {history: KEEP_LAST, depth: 10, reliability: RELIABLE}}
  subscriptions:
    - {name: stop, type: std_msgs/msg/String, qos: {history: KEEP_LAST, depth: 10, reliability: RELIABLE}}
    - {name: old, type: std_msgs/msg/Bool, qos: {history: KEEP_LAST, depth: 10, reliability: RELIABLE}}
'''


def test_every_difference_is_coded_and_located(tmp_path: Path) -> None:
    definition = tmp_path / 'talker.nodl.yaml'
    definition.write_text(DEFINITION, encoding='utf-8')
    node = extract_source(SOURCE, 'talker.py').nodes[0]
    found = {(d.code, d.file if d.file != str(definition) else 'def', d.line) for d in diff_node(node, str(definition))}
    assert found == {
        ('NODL925', 'def', 0),                 # base: node in the source
        ('NODL924', 'talker.py', 9),           # default 2.0 against 1.0
        ('NODL923', 'talker.py', 10),          # depth 5 against 10
        ('NODL920', 'talker.py', 11),          # extra: not declared
        ('NODL922', 'talker.py', 12),          # stop: Bool against String
        ('NODL926', 'def', 9),                 # gone: the source computes a publisher's name
        ('NODL921', 'def', 12),                # old: declared, not created
    }


def test_an_invalid_definition_is_refused(tmp_path: Path) -> None:
    definition = tmp_path / 'bad.nodl.yaml'
    definition.write_text('nodl_version: 2\nmain: 3\n', encoding='utf-8')
    with pytest.raises(ValidationError):
        diff_node(extract_source(SOURCE, 'talker.py').nodes[0], str(definition))
