"""ROS 2 names (topics, services, actions) and parameter names: nodl.validation.names."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nodl.diagnostics import Severity
from nodl.validation import Kind, validate_data
from nodl.validation.names import (
    SUBSTITUTIONS,
    check_parameter_name,
    check_ros_name,
    parameter_name_problem,
    ros_name_problem,
)

# -- topic / service / action names ------------------------------------------

VALID_NAMES = [
    'scan',                      # relative
    'robot/scan',                # relative, several tokens
    '/scan',                     # absolute
    '/robot/front/scan',         # absolute, several tokens
    '_private_looking',          # underscore first
    '/_a/_1',                    # a token may start with '_' and contain digits
    'scan2d',                    # digits after the first character
    'CamelCase/Topic',           # uppercase is allowed
    '~',                         # the node's private namespace itself
    '~/scan',                    # private
    '~/a/b/c',                   # private, several tokens
    '{node}',                    # substitutions
    '{ns}/scan',
    '{namespace}/scan',
    '~/{node}_status',
    'a_{node}_b',
    '{ns}/{node}/x',
    '~x',                        # rcl accepts it (and expands it to '/ns/nx' for n in /ns)
    '{node}1',                   # a digit after a substitution is not a token start
]


@pytest.mark.parametrize('name', VALID_NAMES)
def test_valid_ros_names(name: str) -> None:
    assert ros_name_problem(name) is None
    out: list = []
    check_ros_name(name, ('publishers', 0, 'name'), out)
    assert out == []


# (name, a fragment of the rule that the message must name)
INVALID_NAMES = [
    ('', 'must not be empty'),
    ('//scan', "repeated '/'"),
    ('a//b', "repeated '/'"),
    ('/a/b//', "must not end with '/'"),  # rcl's first rule broken
    ('scan/', "must not end with '/'"),
    ('/robot/', "must not end with '/'"),
    ('~/', "must not end with '/'"),
    ('/', "'/' alone"),
    ('2d_scan', "token '2d_scan' starts with a digit"),
    ('/robot/3d', "token '3d' starts with a digit"),
    ('a/1b/c', "token '1b' starts with a digit"),
    ('~/1b', "token '1b' starts with a digit"),
    ('/{node}/9', "token '9' starts with a digit"),
    ('~foo', "'~' may only start a name, followed by '/'"),
    ('~~', "'~' may only start a name"),
    ('a/~/b', "'~' may only start a name"),
    ('scan~', "'~' may only start a name"),
    ('/~/x', "'~' may only start a name"),
    ('laser scan', "contains ' '"),
    ('laser-scan', "contains '-'"),
    ('laser.scan', "contains '.'"),
    ('scan\n', "contains '\\n'"),
    ('sc\u00e4n', "contains '\u00e4'"),
    ('a:b', "contains ':'"),
    ('{node', "'{' without a matching '}'"),
    ('/a/{ns', "'{' without a matching '}'"),
    ('node}', "'}' without a matching '{'"),
    ('a}{b', "'}' without a matching '{'"),
    ('{{node}}', 'cannot be nested'),
    ('{a{node}}', 'cannot be nested'),
    ('{foo}', "unknown substitution '{foo}'"),
    # rcl expands '{ns}' to an absolute namespace: '/ns//ns/x' for every node
    ('/{namespace}/scan', "gives a repeated '/' once expanded"),
    ('{node}/{ns}/x', "gives a repeated '/' once expanded"),
    ('/{robot}/scan', "unknown substitution '{robot}'"),
    ('{}', "substitution '{}' must hold a name"),
    ('{1a}', "substitution '{1a}' must hold a name"),
]


@pytest.mark.parametrize(('name', 'rule'), INVALID_NAMES)
def test_invalid_ros_names_name_the_rule(name: str, rule: str) -> None:
    problem = ros_name_problem(name)
    assert problem is not None, f'{name!r} was accepted'
    assert rule in problem


@pytest.mark.parametrize(('name', 'rule'), INVALID_NAMES)
def test_check_ros_name_reports_one_error_at_the_value(name: str, rule: str) -> None:
    out: list = []
    path = ('main', 'publishers', 3, 'name')
    check_ros_name(name, path, out)
    assert len(out) == 1
    diagnostic = out[0]
    assert diagnostic.severity is Severity.ERROR
    assert diagnostic.path == path
    assert diagnostic.anchor == 'value'
    assert diagnostic.message.startswith('invalid ROS name ')
    assert rule in diagnostic.message
    assert '\n' not in diagnostic.message


def test_bad_character_message_says_what_is_allowed() -> None:
    problem = ros_name_problem('a-b')
    assert problem is not None
    assert "letters, digits, '_' and '/'" in problem
    assert "'~/' prefix" in problem


def test_unknown_substitution_lists_the_known_ones() -> None:
    problem = ros_name_problem('{foo}')
    assert problem is not None
    for substitution in ('{node}', '{ns}', '{namespace}'):
        assert substitution in problem


def test_substitutions_are_those_rcl_expands() -> None:
    assert SUBSTITUTIONS == ('node', 'ns', 'namespace')
    for substitution in SUBSTITUTIONS:
        assert ros_name_problem('{' + substitution + '}/x') is None


@pytest.mark.parametrize('value', [42, 1.5, None, True, ['scan'], {'a': 1}])
def test_non_string_ros_name(value: object) -> None:
    out: list = []
    check_ros_name(value, ('publishers', 0, 'name'), out)
    assert len(out) == 1
    assert out[0].severity is Severity.ERROR
    assert out[0].message.startswith("'name' must be a string, not ")


def test_non_string_ros_name_shows_the_value() -> None:
    out: list = []
    check_ros_name(42, ('publishers', 0, 'name'), out)
    assert out[0].message == "'name' must be a string, not an integer (42)"


def test_every_endpoint_section_checks_names() -> None:
    sections = {
        'publishers': {'type': 'std_msgs/msg/String', 'qos': {'history': 'KEEP_ALL',
                                                              'reliability': 'RELIABLE'}},
        'subscriptions': {'type': 'std_msgs/msg/String', 'qos': {'history': 'KEEP_ALL',
                                                                 'reliability': 'RELIABLE'}},
        'service_servers': {'type': 'std_srvs/srv/Trigger'},
        'service_clients': {'type': 'std_srvs/srv/Trigger'},
        'action_servers': {'type': 'test_msgs/action/Fibonacci'},
        'action_clients': {'type': 'test_msgs/action/Fibonacci'},
    }
    doc = {'nodl_version': 2}
    for section, entry in sections.items():
        doc[section] = [dict(entry, name='bad name', description='x')]
    errors = [d for d in validate_data(doc, Kind.INTERFACE) if d.severity is Severity.ERROR]
    assert sorted(d.path for d in errors) == sorted((s, 0, 'name') for s in sections)
    assert all("contains ' '" in d.message for d in errors)


# Property: names built by the rules are accepted; breaking one rule is caught.

_token = st.from_regex(r'[A-Za-z_][A-Za-z0-9_]{0,8}', fullmatch=True)
_tokens = st.lists(_token, min_size=1, max_size=4)
_prefix = st.sampled_from(['', '/', '~/'])


@settings(max_examples=200, deadline=None, derandomize=True)
@given(_prefix, _tokens)
def test_property_well_formed_names_are_valid(prefix: str, tokens: list[str]) -> None:
    assert ros_name_problem(prefix + '/'.join(tokens)) is None


@settings(max_examples=200, deadline=None, derandomize=True)
@given(_prefix, _tokens, st.data())
def test_property_a_token_starting_with_a_digit_is_invalid(
        prefix: str, tokens: list[str], data: st.DataObject) -> None:
    index = data.draw(st.integers(0, len(tokens) - 1))
    digit = data.draw(st.sampled_from('0123456789'))
    tokens = list(tokens)
    tokens[index] = digit + tokens[index]
    problem = ros_name_problem(prefix + '/'.join(tokens))
    assert problem is not None and 'starts with a digit' in problem


@settings(max_examples=200, deadline=None, derandomize=True)
@given(_prefix, _tokens, st.sampled_from(' -.:@#$%*+!?,;"\'\\'), st.data())
def test_property_a_forbidden_character_is_invalid(
        prefix: str, tokens: list[str], char: str, data: st.DataObject) -> None:
    name = prefix + '/'.join(tokens)
    where = data.draw(st.integers(len(prefix), len(name)))
    bad = name[:where] + char + name[where:]
    problem = ros_name_problem(bad)
    assert problem is not None and f'contains {char!r}' in problem


# -- parameter names ---------------------------------------------------------

VALID_PARAMETER_NAMES = ['gain', 'use_sim_time', '_hidden', 'pid.kp', 'a1.b2.c3',
                         'Camera.FPS', 'controller._internal.x']


@pytest.mark.parametrize('name', VALID_PARAMETER_NAMES)
def test_valid_parameter_names(name: str) -> None:
    assert parameter_name_problem(name) is None
    out: list = []
    check_parameter_name(name, ('parameters', name), out)
    assert out == []


INVALID_PARAMETER_NAMES = ['1gain', 'pid..kp', '.kp', 'kp.', 'max-speed', 'max speed',
                           'pid.1kp', 'a:b', 'gain!']


@pytest.mark.parametrize('name', INVALID_PARAMETER_NAMES)
def test_invalid_parameter_names(name: str) -> None:
    problem = parameter_name_problem(name)
    assert problem is not None
    assert "separated by '.'" in problem
    assert "starting with a letter or '_'" in problem
    out: list = []
    check_parameter_name(name, ('parameters', name), out)
    assert len(out) == 1
    assert out[0].severity is Severity.ERROR
    assert out[0].anchor == 'key'
    assert out[0].path == ('parameters', name)
    assert out[0].message.startswith(f"invalid parameter name '{name}': ")


def test_empty_parameter_name() -> None:
    assert parameter_name_problem('') == 'a parameter name must not be empty'


def test_parameter_name_check_ignores_non_strings() -> None:
    # A non-string key is reported by the structural check of the mapping.
    out: list = []
    check_parameter_name(5, ('parameters', 5), out)
    assert out == []


def test_parameter_names_are_checked_in_interfaces() -> None:
    doc = {'nodl_version': 2, 'parameters': {
        '1gain': {'type': 'int', 'description': 'x'},
        'ok.name': {'type': 'int', 'description': 'x'},
    }}
    errors = [d for d in validate_data(doc, Kind.INTERFACE) if d.severity is Severity.ERROR]
    assert [(d.path, d.anchor) for d in errors] == [(('parameters', '1gain'), 'key')]


# -- the definition rules against rcl's (nodl.naming) ------------------------------------
# Two checks of one fact: what a definition may write is at least as strict as what rcl accepts.

_name_pieces = st.sampled_from(list('ab1_/~{}') + ['node', 'ns', 'namespace', 'x'])


def _rcl_refuses(name: str) -> str | None:
    from nodl.naming import InvalidNameError, resolve_name, topic_name_error

    problem = topic_name_error(name)
    if problem is None:
        try:
            resolve_name(name, 'n', '/ns')
        except InvalidNameError as exc:
            problem = str(exc)
    return problem


@settings(max_examples=3000, deadline=None, derandomize=True)
@given(st.lists(_name_pieces, max_size=8).map(''.join))
def test_property_definition_names_are_names_rcl_accepts(name: str) -> None:
    # one rule set: a definition may write exactly the names rcl accepts
    assert (ros_name_problem(name) is None) == (_rcl_refuses(name) is None), name


def test_substitutions_are_the_ones_the_naming_module_expands() -> None:
    from nodl.naming import expand_name
    from nodl.vocabulary import NAME_SUBSTITUTIONS

    assert SUBSTITUTIONS is NAME_SUBSTITUTIONS
    expanded = {word: expand_name('{' + word + '}/x', 'n', '/ns') for word in SUBSTITUTIONS}
    assert expanded == {'node': '/ns/n/x', 'ns': '/ns/x', 'namespace': '/ns/x'}
