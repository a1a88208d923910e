"""The naming module against real rclpy nodes: the table in tests/fixtures/naming/.

Every case creates a real node with the same arguments (one context per case,
all in this process) and compares what rcl resolves with what
:mod:`nodl.naming` computes, name for name, topic and service.
"""

from __future__ import annotations

from functools import partial
from pathlib import Path
from typing import Any

import pytest
import yaml

from nodl.naming import InvalidNameError, InvalidRemapRuleError, node_fqn, parse_remap_rules, resolve_name

TABLE = yaml.safe_load((Path(__file__).parent / 'fixtures' / 'naming' / 'rclpy_cases.yaml')
                       .read_text(encoding='utf-8'))
CASES: list[dict[str, Any]] = TABLE['cases']
INVALID_RULES: list[str] = TABLE['invalid_rules']

#: Nodes rcl refuses to create: node_fqn must refuse them too.
INVALID_NODES = [
    ('1drv', '/ns', []),
    ('d-rv', '/ns', []),
    ('', '/ns', []),
    ('drv', '/ns/', []),
    ('drv', '/a//b', []),
    ('drv', '/1a', []),
    ('drv', '/ns', ['__ns:=/a/']),
]


def _argv(args: list[str]) -> list[str]:
    if '--ros-args' in args:
        return list(args)
    return ['--ros-args', *[part for rule in args for part in ('-r', rule)]]


def _outcome(call: Any) -> str:
    try:
        return call()
    except Exception as exc:  # what rcl rejects; the tests only need to know that it did
        return f'ERROR: {exc}'


def _with_node(node_name: str, namespace: str, argv: list[str], use: Any) -> Any:
    import rclpy
    from rclpy.node import Node

    context = rclpy.Context()
    rclpy.init(context=context, args=[])
    try:
        node = Node(node_name, namespace=namespace, cli_args=argv, context=context,
                    start_parameter_services=False, enable_rosout=False)
        try:
            return use(node)
        finally:
            node.destroy_node()
    finally:
        rclpy.shutdown(context=context)


@pytest.fixture(scope='module')
def by_rclpy() -> dict[str, dict[str, Any]]:
    """What real rclpy nodes say for every case of the table (computed once)."""
    out: dict[str, dict[str, Any]] = {}
    for case in CASES:
        def ask(node: Any, case: dict[str, Any] = case) -> dict[str, Any]:
            names = {}
            for name in case['names']:
                names[name] = (_outcome(partial(node.resolve_topic_name, name)),
                               _outcome(partial(node.resolve_service_name, name)))
            return {'fqn': node.get_fully_qualified_name(), 'names': names}
        out[case['id']] = _with_node(case['node'], case['namespace'], _argv(case['args']), ask)
    return out


def _ours(name: str, case: dict[str, Any], service: bool) -> str:
    try:
        return resolve_name(name, case['node'], case['namespace'], _argv(case['args']),
                            service=service)
    except InvalidNameError as exc:
        return f'ERROR: {exc}'


_NAME_CASES = [pytest.param(case, name, id=f"{case['id']}:{name or 'EMPTY'}")
               for case in CASES for name in case['names']]


def test_the_table_is_large_enough() -> None:
    assert len(_NAME_CASES) >= 60
    assert len({case['id'] for case in CASES}) == len(CASES)


@pytest.mark.parametrize('case', [pytest.param(c, id=c['id']) for c in CASES])
def test_node_fqn_agrees_with_rclpy(case: dict[str, Any], by_rclpy: dict[str, Any]) -> None:
    assert node_fqn(case['node'], case['namespace'], _argv(case['args'])) == \
        by_rclpy[case['id']]['fqn']
    # the list form and the command-line form mean the same
    if '--ros-args' not in case['args']:
        assert node_fqn(case['node'], case['namespace'], case['args']) == \
            by_rclpy[case['id']]['fqn']


@pytest.mark.parametrize('case, name', _NAME_CASES)
def test_resolve_name_agrees_with_rclpy(case: dict[str, Any], name: str,
                                        by_rclpy: dict[str, Any]) -> None:
    topic, service = by_rclpy[case['id']]['names'][name]
    for expected, ours in ((topic, _ours(name, case, False)), (service, _ours(name, case, True))):
        if expected.startswith('ERROR'):
            assert ours.startswith('ERROR'), f'rclpy rejects {name!r} ({expected}), we gave {ours}'
            assert ' is invalid: ' in ours  # says which name and why
        else:
            assert ours == expected


@pytest.mark.parametrize('rule', INVALID_RULES)
def test_rules_rclpy_refuses_are_refused(rule: str) -> None:
    from rclpy._rclpy_pybind11 import RCLInvalidROSArgsError

    with pytest.raises(RCLInvalidROSArgsError):
        _with_node('drv', '/ns', ['--ros-args', '-r', rule], lambda node: None)
    with pytest.raises(InvalidRemapRuleError, match='invalid remapping '):
        parse_remap_rules([rule])
    with pytest.raises(InvalidRemapRuleError):
        parse_remap_rules(['--ros-args', '-r', rule])


@pytest.mark.parametrize('node_name, namespace, args', INVALID_NODES)
def test_nodes_rclpy_refuses_are_refused(node_name: str, namespace: str, args: list[str]) -> None:
    from rclpy._rclpy_pybind11 import RCLError  # a namespace remapped to an invalid one
    from rclpy.exceptions import NameValidationException

    with pytest.raises((NameValidationException, RCLError)):
        _with_node(node_name, namespace, _argv(args), lambda node: None)
    with pytest.raises(InvalidNameError, match=' is invalid: '):
        node_fqn(node_name, namespace, args)


@pytest.mark.parametrize('rules, expected', [
    (['plan:=moved'], '/ns/moved'),
    (['rostopic://plan:=t'], '/ns/t'),
    (['rosservice://plan:=s'], '/ns/plan'),
    (['rosservice://plan:=s', 'rostopic://plan:=t'], '/ns/t'),
    (['__node:=renamed', '~/plan:=x'], '/ns/plan'),
])
def test_an_action_name_resolves_as_a_topic_name(rules: list[str], expected: str) -> None:
    """rcl_action resolves the action's name as a topic; NodeNames.resolve does the same."""
    import os
    import time

    from rclpy.action import ActionServer
    from test_msgs.action import Fibonacci

    node_name = f'act_{os.getpid()}_{abs(hash(tuple(rules))) % 10**6}'

    def served(node: Any) -> list[str]:
        ActionServer(node, Fibonacci, 'plan', lambda goal: None)
        final = node.get_name()
        deadline = time.monotonic() + 10.0
        while time.monotonic() < deadline:
            names = [n for n, _ in node.get_service_names_and_types_by_node(final, '/ns')
                     if '/_action/' in n]
            if len(names) == 3:
                return names
            time.sleep(0.02)
        raise AssertionError('the action server did not appear in the graph within 10 s')

    names = _with_node(node_name, '/ns', _argv(rules), served)
    assert {n.partition('/_action/')[0] for n in names} == {expected}
    assert resolve_name('plan', node_name, '/ns', rules) == expected


#: Names a definition may write, where the two former rule sets disagreed ('~x', 'a//b',
#: '{foo}') and around them: declared_name_error must refuse exactly what rclpy refuses.
DECLARED_NAMES = ['~x', '~', '~/x', '~xy', 'a//b', '//a', '{foo}', '{foo}/x', '{}', '{1a}',
                  '{node}', '{ns}/x', '/{ns}/x', 'a/{namespace}', '{node}/{ns}', 'x/', '1a',
                  'a/1b', 'a b', 'a}{b', '{node', '{{node}}', '/', '', 'scan', '/scan']


def test_declared_name_error_refuses_what_rclpy_refuses() -> None:
    from nodl.naming import declared_name_error

    def ask(node: Any) -> dict[str, bool]:
        return {name: _outcome(partial(node.resolve_topic_name, name)).startswith('ERROR')
                for name in DECLARED_NAMES}

    refused = _with_node('n', '/ns', [], ask)
    assert {name: declared_name_error(name) is not None for name in DECLARED_NAMES} == refused
    assert refused['a//b'] and refused['{foo}'] and not refused['~x']
