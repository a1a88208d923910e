"""Interface type names (pkg/msg/Type, ...): nodl.validation.types."""

from __future__ import annotations

import pytest

from nodl.diagnostics import Severity
from nodl.validation import Kind, validate_data
from nodl.validation.types import (
    NAMESPACE_WORDS,
    check_action_type,
    check_msg_type,
    check_srv_type,
    split_type,
    type_problem,
)

CHECKS = {'msg': check_msg_type, 'srv': check_srv_type, 'action': check_action_type}
# Where each namespace belongs, and what a user calls that place.
USERS = {'msg': 'topics carry messages', 'srv': 'services need a service type',
         'action': 'actions need an action type'}


def run(namespace: str, value: object) -> list:
    out: list = []
    CHECKS[namespace](value, ('main', 'publishers', 0, 'type'), out)
    return out


def test_split_type() -> None:
    assert split_type('std_msgs/msg/String') == ('std_msgs', 'msg', 'String')
    assert split_type('std_msgs/String') == ('std_msgs', None, 'String')
    assert split_type('String') is None
    assert split_type('a/b/c/D') is None


@pytest.mark.parametrize(('namespace', 'name'), [
    ('msg', 'std_msgs/msg/String'),
    ('msg', 'sensor_msgs/msg/LaserScan'),
    ('msg', 'my_pkg2/msg/Type2'),
    ('msg', 'p/msg/A'),
    ('srv', 'std_srvs/srv/Trigger'),
    ('srv', 'rcl_interfaces/srv/SetParameters'),
    ('action', 'test_msgs/action/Fibonacci'),
    ('action', 'nav2_msgs/action/NavigateToPose'),
])
def test_valid_full_names(namespace: str, name: str) -> None:
    assert type_problem(name, namespace) is None
    assert run(namespace, name) == []


@pytest.mark.parametrize(('namespace', 'name', 'full'), [
    ('msg', 'std_msgs/String', 'std_msgs/msg/String'),
    ('srv', 'std_srvs/Trigger', 'std_srvs/srv/Trigger'),
    ('action', 'test_msgs/Fibonacci', 'test_msgs/action/Fibonacci'),
])
def test_short_form_is_a_warning_naming_the_full_form(namespace: str, name: str, full: str) -> None:
    out = run(namespace, name)
    assert len(out) == 1
    assert out[0].severity is Severity.WARNING
    assert out[0].message == f"'{name}' omits the interface namespace; write '{full}'"
    assert out[0].path == ('main', 'publishers', 0, 'type')


@pytest.mark.parametrize('expected', ['msg', 'srv', 'action'])
@pytest.mark.parametrize('given', ['msg', 'srv', 'action'])
def test_wrong_namespace_names_both(expected: str, given: str) -> None:
    if expected == given:
        assert run(expected, f'my_pkg/{given}/Thing') == []
        return
    out = run(expected, f'my_pkg/{given}/Thing')
    assert len(out) == 1
    assert out[0].severity is Severity.ERROR
    message = out[0].message
    # What was given ...
    assert f"'my_pkg/{given}/Thing' is {NAMESPACE_WORDS[given]}" in message
    # ... and what the section needs.
    assert USERS[expected] in message
    assert f'package/{expected}/Type' in message


@pytest.mark.parametrize(('namespace', 'middle'), [
    ('msg', 'msgs'), ('srv', 'service'), ('action', 'actions'), ('msg', 'Msg'),
])
def test_unknown_namespace(namespace: str, middle: str) -> None:
    out = run(namespace, f'pkg/{middle}/Thing')
    assert len(out) == 1 and out[0].severity is Severity.ERROR
    assert out[0].message == (f"unknown interface namespace '{middle}' in 'pkg/{middle}/Thing'; "
                              f"expected '{namespace}'")


@pytest.mark.parametrize('package', ['Std_msgs', '1pkg', '_pkg', 'std__msgs', 'std_msgs_',
                                     'std-msgs', 'STD', 'std.msgs'])
@pytest.mark.parametrize('namespace', ['msg', 'srv', 'action'])
def test_bad_package_names(package: str, namespace: str) -> None:
    name = f'{package}/{namespace}/Thing'
    out = run(namespace, name)
    assert len(out) == 1 and out[0].severity is Severity.ERROR
    assert out[0].message.startswith(f"package name '{package}' in '{name}' is invalid")
    assert 'lowercase letters, digits and single' in out[0].message


def test_bad_package_in_short_form_is_an_error_not_a_warning() -> None:
    out = run('msg', 'Std_msgs/String')
    assert [d.severity for d in out] == [Severity.ERROR]


@pytest.mark.parametrize('type_name', ['string', 'laserScan', '1String', 'Laser_Scan',
                                       'Laser-Scan', 'S\u00e9rie'])
def test_type_name_must_be_camel_case(type_name: str) -> None:
    name = f'std_msgs/msg/{type_name}'
    out = run('msg', name)
    assert len(out) == 1 and out[0].severity is Severity.ERROR
    assert out[0].message == (f"type name '{type_name}' in '{name}' must be CamelCase: an "
                              'uppercase letter followed by letters and digits')


def test_lowercase_type_name_in_short_form_is_an_error() -> None:
    out = run('srv', 'std_srvs/trigger')
    assert [d.severity for d in out] == [Severity.ERROR]
    assert 'must be CamelCase' in out[0].message


@pytest.mark.parametrize(('namespace', 'example'), [
    ('msg', 'std_msgs/msg/String'), ('srv', 'std_srvs/srv/Trigger'),
    ('action', 'test_msgs/action/Fibonacci')])
@pytest.mark.parametrize('name', ['String', '', 'a/b/c/D', 'std_msgs//String', 'std_msgs/msg/',
                                  '/msg/String', 'std_msgs/'])
def test_not_a_type_name(name: str, namespace: str, example: str) -> None:
    out = run(namespace, name)
    assert len(out) == 1 and out[0].severity is Severity.ERROR
    assert out[0].message == (f"'{name}' is not an interface type name; expected "
                              f'package/{namespace}/Type (for example {example})')


@pytest.mark.parametrize('value', [3, None, True, ['std_msgs/msg/String'], {'a': 1}])
def test_non_string_type(value: object) -> None:
    out = run('msg', value)
    assert len(out) == 1 and out[0].severity is Severity.ERROR
    assert out[0].message.startswith("'type' must be a string, not ")


def test_problems_are_reported_once_in_rule_order() -> None:
    # A package problem hides the others: one diagnostic per value.
    out = run('msg', 'Bad/srv/lower')
    assert len(out) == 1 and 'package name' in out[0].message
    # With a good package, the namespace is checked before the type name.
    out = run('msg', 'good/srv/lower')
    assert len(out) == 1 and 'is a service type' in out[0].message


def _interface(section: str, type_name: str) -> dict:
    entry = {'name': 'x', 'type': type_name, 'description': 'd'}
    if section in ('publishers', 'subscriptions'):
        entry['qos'] = {'history': 'KEEP_ALL', 'reliability': 'RELIABLE'}
    return {'nodl_version': 2, section: [entry]}


@pytest.mark.parametrize(('section', 'namespace'), [
    ('publishers', 'msg'), ('subscriptions', 'msg'), ('service_servers', 'srv'),
    ('service_clients', 'srv'), ('action_servers', 'action'), ('action_clients', 'action')])
def test_each_section_uses_its_namespace(section: str, namespace: str) -> None:
    assert validate_data(_interface(section, f'pkg/{namespace}/Thing'), Kind.INTERFACE) == []
    for other in ('msg', 'srv', 'action'):
        if other == namespace:
            continue
        diagnostics = validate_data(_interface(section, f'pkg/{other}/Thing'), Kind.INTERFACE)
        assert [(d.severity, d.path) for d in diagnostics] == [
            (Severity.ERROR, (section, 0, 'type'))]
        assert f'package/{namespace}/Type' in diagnostics[0].message


def test_short_form_in_a_document_is_only_a_warning() -> None:
    diagnostics = validate_data(_interface('publishers', 'std_msgs/String'), Kind.INTERFACE)
    assert [d.severity for d in diagnostics] == [Severity.WARNING]
    assert "'std_msgs/msg/String'" in diagnostics[0].message
