"""Checks across one interface definition: nodl.validation.interfaces."""

from __future__ import annotations

from typing import Any

import pytest

from nodl import load_schema
from nodl.diagnostics import Diagnostic, Severity
from nodl.validation import Kind, validate_data
from nodl.validation.interfaces import SECTIONS, check_interface

QOS = {'history': 'KEEP_ALL', 'reliability': 'RELIABLE'}
TYPES = {'publishers': 'std_msgs/msg/String', 'subscriptions': 'std_msgs/msg/String',
         'service_servers': 'std_srvs/srv/Trigger', 'service_clients': 'std_srvs/srv/Trigger',
         'action_servers': 'test_msgs/action/Fibonacci',
         'action_clients': 'test_msgs/action/Fibonacci'}


def entry(section: str, name: str, description: str | None = 'd') -> dict[str, Any]:
    out: dict[str, Any] = {'name': name, 'type': TYPES[section]}
    if description is not None:
        out['description'] = description
    if section in ('publishers', 'subscriptions'):
        out['qos'] = dict(QOS)
    return out


def errors(data: Any, kind: Kind = Kind.INTERFACE) -> list[Diagnostic]:
    return [d for d in validate_data(data, kind) if d.severity is Severity.ERROR]


def warnings(data: Any, kind: Kind = Kind.INTERFACE) -> list[Diagnostic]:
    return [d for d in validate_data(data, kind) if d.severity is Severity.WARNING]


def test_sections_match_the_schema() -> None:
    properties = load_schema('interface')['definitions']['interface']['properties']
    assert set(SECTIONS) == {k for k, v in properties.items() if v.get('type') == 'array'}


@pytest.mark.parametrize(('section', 'word'), list(SECTIONS.items()))
def test_duplicate_names_within_a_section(section: str, word: str) -> None:
    data = {'nodl_version': 2, section: [entry(section, 'x'), entry(section, 'y'),
                                         entry(section, 'x')]}
    found = errors(data)
    assert [(d.path, d.anchor, d.message) for d in found] == [
        ((section, 2, 'name'), 'value',
         f"duplicate {word} 'x' (already declared at {section}[0]); a name appears once per "
         'section')]


def test_every_repetition_points_at_the_first() -> None:
    data = {'nodl_version': 2, 'publishers': [entry('publishers', 'x') for _ in range(3)]}
    found = errors(data)
    assert [d.path for d in found] == [('publishers', 1, 'name'), ('publishers', 2, 'name')]
    assert all('already declared at publishers[0]' in d.message for d in found)


def test_the_same_name_in_different_sections_is_fine() -> None:
    data = {'nodl_version': 2}
    for section in SECTIONS:
        data[section] = [entry(section, 'state')]
    assert validate_data(data, Kind.INTERFACE) == []


def test_names_are_compared_exactly() -> None:
    data = {'nodl_version': 2, 'publishers': [entry('publishers', 'state'),
                                              entry('publishers', '/state'),
                                              entry('publishers', 'State'),
                                              entry('publishers', '~/state')]}
    assert validate_data(data, Kind.INTERFACE) == []


def test_duplicates_in_a_node_carry_the_full_path() -> None:
    data = {'nodl_version': 2,
            'main': {'nodl_version': 2, 'service_servers': [entry('service_servers', 's'),
                                                            entry('service_servers', 's')]},
            'mixins': [{'nodl_version': 2, 'action_clients': [entry('action_clients', 'a'),
                                                              entry('action_clients', 'a')]}]}
    found = errors(data, Kind.NODE)
    assert [(d.path, d.message) for d in found] == [
        (('main', 'service_servers', 1, 'name'),
         "duplicate service server 's' (already declared at main.service_servers[0]); a name "
         'appears once per section'),
        (('mixins', 0, 'action_clients', 1, 'name'),
         "duplicate action client 'a' (already declared at mixins[0].action_clients[0]); a name "
         'appears once per section'),
    ]


def test_main_and_a_mixin_may_share_a_name() -> None:
    # Composition decides what a collision between layers means.
    data = {'nodl_version': 2,
            'main': {'nodl_version': 2, 'publishers': [entry('publishers', 'x')]},
            'mixins': [{'nodl_version': 2, 'publishers': [entry('publishers', 'x')]}]}
    assert validate_data(data, Kind.NODE) == []


@pytest.mark.parametrize(('section', 'word'), list(SECTIONS.items()))
@pytest.mark.parametrize('description', [None, ''])
def test_missing_description_of_an_endpoint(section: str, word: str,
                                            description: str | None) -> None:
    data = {'nodl_version': 2, section: [entry(section, 'ok'), entry(section, 'x', description)]}
    found = validate_data(data, Kind.INTERFACE)
    assert [(d.severity, d.path, d.anchor, d.message) for d in found] == [
        (Severity.WARNING, (section, 1), 'key', f"{word} 'x' has no description")]


def test_missing_description_of_an_unnamed_endpoint() -> None:
    found = warnings({'nodl_version': 2, 'publishers': [{'type': 'std_msgs/msg/String',
                                                         'qos': dict(QOS)}]})
    assert [d.message for d in found] == ['publisher has no description']


@pytest.mark.parametrize('description', [None, ''])
def test_missing_description_of_a_parameter(description: str | None) -> None:
    param: dict[str, Any] = {'type': 'int'}
    if description is not None:
        param['description'] = description
    data = {'nodl_version': 2, 'parameters': {'gain': param, 'ok': {'type': 'int',
                                                                    'description': 'x'}}}
    found = validate_data(data, Kind.INTERFACE)
    assert [(d.severity, d.path, d.anchor, d.message) for d in found] == [
        (Severity.WARNING, ('parameters', 'gain'), 'key', "parameter 'gain' has no description")]


def test_interface_description_is_optional() -> None:
    assert validate_data({'nodl_version': 2, 'parameters': {}, 'publishers': []},
                         Kind.INTERFACE) == []


def test_parameters_are_checked() -> None:
    data = {'nodl_version': 2, 'parameters': {'gain': {
        'type': 'int', 'default_value': 500, 'description': 'x',
        'validation': {'bounds<>': [0, 10]}}}}
    found = errors(data)
    assert [(d.path, d.message) for d in found] == [
        (('parameters', 'gain', 'default_value'),
         'default_value 500 breaks bounds<> [0, 10]: it is outside [0, 10]')]


def test_in_place_mixins_are_checked_like_interfaces() -> None:
    data = {'nodl_version': 2, 'main': {'nodl_version': 2},
            'mixins': ['ref.nodl.yaml', {'nodl_version': 2, 'parameters': {'p': {'type': 'int'}},
                                         'publishers': [entry('publishers', 'x', None)]}]}
    found = warnings(data, Kind.NODE)
    assert [d.path for d in found] == [('mixins', 1, 'parameters', 'p'),
                                       ('mixins', 1, 'publishers', 0)]


@pytest.mark.parametrize('data', [None, 5, 'x', [], {'parameters': ['a']},
                                  {'parameters': {'p': 'int'}},
                                  {'publishers': 'x'}, {'publishers': ['x', 3, None]},
                                  {'publishers': [{'name': 5}]}])
def test_malformed_input_is_left_to_the_structural_check(data: Any) -> None:
    out: list[Diagnostic] = []
    check_interface(data, (), out)
    assert all(d.severity is Severity.WARNING for d in out)


def test_check_interface_prefixes_paths() -> None:
    out: list[Diagnostic] = []
    check_interface({'publishers': [entry('publishers', 'a'), entry('publishers', 'a')]},
                    ('mixins', 3), out)
    assert [d.path for d in out] == [('mixins', 3, 'publishers', 1, 'name')]
    assert 'already declared at mixins[3].publishers[0]' in out[0].message


def test_keep_all_with_a_depth_is_a_warning() -> None:
    qos = {'history': 'KEEP_ALL', 'depth': 5, 'reliability': 'RELIABLE'}
    data = {'nodl_version': 2, 'publishers': [
        {'name': 'a', 'type': 'std_msgs/msg/String', 'description': 'x', 'qos': qos}]}
    found = [d for d in validate_data(data, Kind.INTERFACE) if d.code == 'NODL230']
    assert [(d.severity, d.path) for d in found] == [
        (Severity.WARNING, ('publishers', 0, 'qos', 'depth'))]
    del qos['depth']
    assert not [d for d in validate_data(data, Kind.INTERFACE) if d.code == 'NODL230']
