"""The typed document model: nodl.model."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import pytest

from nodl.loading import (
    check_source,
    dump_nodl,
    load_interface,
    load_node,
    load_nodl,
    validate_interface,
    validate_node,
)
from nodl.model import (
    ENDPOINT_SECTIONS,
    QOS_POLICIES,
    ActionEndpoint,
    Base,
    Interface,
    Node,
    ParameterDefinition,
    QoSProfile,
    ServiceEndpoint,
    TopicEndpoint,
)
from nodl.model.parameter_types import (
    ALL_TYPE_WORDS,
    ARRAY_TYPES,
    FIXED_BASES,
    SCALAR_TYPES,
    TypeSpec,
    element_fits,
    parse_type,
    value_fits,
)

FIXTURES = Path(__file__).parent / 'fixtures'
VALID = sorted((FIXTURES / 'valid').iterdir())
QOS = {'history': 'KEEP_LAST', 'depth': 5, 'reliability': 'RELIABLE'}


# -- Interface ----------------------------------------------------------------

def test_empty_interface() -> None:
    iface = Interface(nodl_version=2)
    assert iface == Interface()
    assert iface.description is None and iface.parameters is None
    for section in ENDPOINT_SECTIONS:
        assert getattr(iface, section) is None
        assert iface.endpoints(section) == []
    assert iface.to_dict() == {'nodl_version': 2}
    assert Interface.from_dict({'nodl_version': 2}) == iface


def test_endpoints_of_an_unknown_section() -> None:
    with pytest.raises(KeyError, match='unknown section'):
        Interface().endpoints('subscribers')


def test_interface_from_dict_and_to_dict() -> None:
    data = {
        'nodl_version': 2,
        'description': 'd',
        'parameters': {'gain': {'type': 'double', 'default_value': 1.0, 'description': 'g'}},
        'publishers': [{'name': 'a', 'type': 'std_msgs/msg/String', 'description': 'x',
                        'qos': dict(QOS)}],
        'subscriptions': [],
        'service_servers': [{'name': 's', 'type': 'std_srvs/srv/Trigger'}],
        'service_clients': [{'name': 'c', 'type': 'std_srvs/srv/Trigger', 'qos': dict(QOS)}],
        'action_servers': [{'name': 'x', 'type': 'test_msgs/action/Fibonacci'}],
        'action_clients': [{'name': 'y', 'type': 'test_msgs/action/Fibonacci',
                            'description': 'z'}],
    }
    iface = Interface.from_dict(data)
    assert isinstance(iface.parameters['gain'], ParameterDefinition)
    assert iface.publishers == [TopicEndpoint('a', 'std_msgs/msg/String', QoSProfile(
        'KEEP_LAST', 'RELIABLE', depth=5), 'x')]
    assert iface.subscriptions == []          # present but empty is not absent
    assert iface.service_servers == [ServiceEndpoint('s', 'std_srvs/srv/Trigger')]
    assert iface.service_clients[0].qos == QoSProfile('KEEP_LAST', 'RELIABLE', 5)
    assert iface.action_clients == [ActionEndpoint('y', 'test_msgs/action/Fibonacci', 'z')]
    assert iface.to_dict() == data
    assert list(iface.to_dict()) == list(data)


def test_interface_to_dict_is_valid() -> None:
    iface = Interface(description='x', publishers=[
        TopicEndpoint('a', 'std_msgs/msg/String', QoSProfile('KEEP_ALL', 'RELIABLE'), 'd')])
    assert validate_interface(iface.to_dict()) == []


def test_endpoint_key_order() -> None:
    endpoint = TopicEndpoint('a', 'p/msg/T', QoSProfile('KEEP_ALL', 'RELIABLE'), 'd')
    assert list(endpoint.to_dict()) == ['name', 'type', 'description', 'qos']
    assert ServiceEndpoint('s', 'p/srv/T').to_dict() == {'name': 's', 'type': 'p/srv/T'}
    assert ActionEndpoint('s', 'p/action/T').to_dict() == {'name': 's', 'type': 'p/action/T'}


def test_origin_is_not_part_of_equality() -> None:
    a = ActionEndpoint('s', 'p/action/T')
    b = ActionEndpoint('s', 'p/action/T', origin='mixin nodl://p/x')
    assert a == b
    p = ParameterDefinition('int', origin='base')
    assert p == ParameterDefinition('int')


# -- QoS ----------------------------------------------------------------------

def test_qos_round_trip_and_order() -> None:
    data = {'history': 'KEEP_LAST', 'reliability': 'BEST_EFFORT', 'depth': 1,
            'durability': 'VOLATILE', 'deadline_ns': 5, 'lifespan_ns': 0,
            'liveliness': 'AUTOMATIC', 'liveliness_lease_duration_ns': 7}
    qos = QoSProfile.from_dict(data)
    assert qos.to_dict() == data
    assert list(qos.to_dict()) == list(QOS_POLICIES)
    assert QoSProfile('KEEP_ALL', 'RELIABLE').to_dict() == {'history': 'KEEP_ALL',
                                                           'reliability': 'RELIABLE'}
    # 0 is a value, not "unset".
    assert QoSProfile('KEEP_ALL', 'RELIABLE', lifespan_ns=0).to_dict()['lifespan_ns'] == 0


# -- ParameterDefinition --------------------------------------------------------

def test_parameter_defaults() -> None:
    param = ParameterDefinition.from_dict({'type': 'int'})
    assert param == ParameterDefinition('int', None, '', False, '', None)
    assert param.to_dict() == {'type': 'int'}


def test_parameter_round_trip() -> None:
    data = {'type': 'int', 'default_value': 3, 'description': 'd', 'read_only': True,
            'additional_constraints': 'odd', 'validation': {'bounds<>': [0, 10],
                                                            'my::f': None}}
    param = ParameterDefinition.from_dict(data)
    assert param.to_dict() == data
    assert list(param.to_dict()) == list(data)


@pytest.mark.parametrize('default', [0, False, '', [], 0.0])
def test_falsy_defaults_are_kept(default: Any) -> None:
    param = ParameterDefinition.from_dict({'type': 'int', 'default_value': default})
    assert param.to_dict() == {'type': 'int', 'default_value': default}


def test_parameter_defaults_are_left_out() -> None:
    data = {'type': 'bool', 'description': '', 'read_only': False, 'additional_constraints': ''}
    assert ParameterDefinition.from_dict(data).to_dict() == {'type': 'bool'}


def test_parameter_type_spec() -> None:
    assert ParameterDefinition('int_array_fixed_4').type_spec == TypeSpec(
        'int_array_fixed_4', 'int_array', 4)
    assert ParameterDefinition('integer').type_spec is None


# -- parameter types ---------------------------------------------------------------

@pytest.mark.parametrize('name', SCALAR_TYPES + ARRAY_TYPES)
def test_parse_plain_types(name: str) -> None:
    spec = parse_type(name)
    assert spec == TypeSpec(name, name, None)
    assert spec.is_array == name.endswith('_array')


@pytest.mark.parametrize('base', FIXED_BASES)
def test_parse_fixed_types(base: str) -> None:
    assert parse_type(f'{base}_fixed_1') == TypeSpec(f'{base}_fixed_1', base, 1)
    assert parse_type(f'{base}_fixed_250') == TypeSpec(f'{base}_fixed_250', base, 250)
    for bad in (f'{base}_fixed_0', f'{base}_fixed_01', f'{base}_fixed_', f'{base}_fixed_x',
                f'{base}_fixed_-1'):
        assert parse_type(bad) is None, bad


@pytest.mark.parametrize('name', ['bool_array_fixed_3', 'int_fixed_2', 'byte_array_fixed_2',
                                  'Int', ' int', 'int ', '', None, 5, ['int']])
def test_parse_unsupported_types(name: Any) -> None:
    assert parse_type(name) is None


@pytest.mark.parametrize(('name', 'element', 'numeric', 'category'), [
    ('bool', 'bool', False, 'bool'), ('int', 'int', True, 'int'),
    ('double', 'double', True, 'double'), ('string', 'string', False, 'string'),
    ('none', 'none', False, 'none'), ('byte_array', 'byte', True, 'byte array'),
    ('int_array', 'int', True, 'int array'), ('string_fixed_3', 'string', False, 'string'),
    ('double_array_fixed_2', 'double', True, 'double array'),
])
def test_type_spec_properties(name: str, element: str, numeric: bool, category: str) -> None:
    spec = parse_type(name)
    assert spec is not None
    assert (spec.element, spec.numeric, spec.category) == (element, numeric, category)


def test_all_type_words() -> None:
    assert ALL_TYPE_WORDS[:len(SCALAR_TYPES + ARRAY_TYPES)] == SCALAR_TYPES + ARRAY_TYPES
    assert 'string_fixed_N' in ALL_TYPE_WORDS and 'bool_array_fixed_N' not in ALL_TYPE_WORDS


@pytest.mark.parametrize(('value', 'element', 'fits'), [
    (True, 'bool', True), (1, 'bool', False), (1, 'int', True), (True, 'int', False),
    (1.0, 'int', False), (1, 'double', True), (1.5, 'double', True), (False, 'double', False),
    ('a', 'string', True), (1, 'string', False), (0, 'byte', True), (255, 'byte', True),
    (256, 'byte', False), (-1, 'byte', False), (True, 'byte', False), (None, 'none', False),
])
def test_element_fits(value: Any, element: str, fits: bool) -> None:
    assert element_fits(value, element) is fits


@pytest.mark.parametrize(('type_', 'value', 'fits'), [
    ('int', 3, True), ('int', '3', False), ('string_fixed_2', 'ab', True),
    ('string_fixed_2', 'abc', False), ('int_array', [1, 2], True), ('int_array', [1, 'a'], False),
    ('int_array', 1, False), ('int_array_fixed_2', [1, 2], True),
    ('int_array_fixed_2', [1, 2, 3], False), ('byte_array', [0, 255], True),
    ('byte_array', [256], False), ('double_array', [1, 2.5], True), ('bool_array', [], True),
])
def test_value_fits(type_: str, value: Any, fits: bool) -> None:
    spec = parse_type(type_)
    assert spec is not None
    assert value_fits(value, spec) is fits


# -- Node and Base ----------------------------------------------------------------------

def test_base_compares_equal_to_strings() -> None:
    assert Base.NODE == 'node'
    assert 'lifecycle_node' == Base.LIFECYCLE_NODE  # noqa: SIM300  (the string on the left: both directions)
    assert Base('node') is Base.NODE
    assert str(Base.LIFECYCLE_NODE) == 'lifecycle_node'
    assert {'node': 1}[Base.NODE] == 1
    assert [b.value for b in Base] == ['node', 'lifecycle_node']
    with pytest.raises(ValueError):
        Base('component')


def test_node_defaults() -> None:
    node = Node()
    assert node.main == Interface() and node.base is None and node.mixins is None
    assert node.to_dict() == {'nodl_version': 2, 'main': {'nodl_version': 2}}
    assert validate_node(node.to_dict()) == []


def test_node_with_in_place_and_referenced_mixins() -> None:
    data = {
        'nodl_version': 2,
        'base': 'lifecycle_node',
        'mixins': [
            'nodl://diagnostic_updater/diagnostics',
            {'nodl_version': 2, 'service_servers': [
                {'name': '~/reset', 'type': 'std_srvs/srv/Trigger', 'description': 'r'}]},
            '../shared/x.nodl.yaml',
        ],
        'main': {'nodl_version': 2, 'description': 'm'},
    }
    node = Node.from_dict(data)
    assert node.base is Base.LIFECYCLE_NODE and node.base == 'lifecycle_node'
    assert node.mixins[0] == 'nodl://diagnostic_updater/diagnostics'
    assert isinstance(node.mixins[1], Interface)
    assert node.mixins[1].service_servers[0].name == '~/reset'
    assert node.mixins[2] == '../shared/x.nodl.yaml'
    assert node.main.description == 'm'
    assert node.to_dict() == data
    assert list(node.to_dict()) == ['nodl_version', 'base', 'mixins', 'main']


def test_node_base_given_as_a_string() -> None:
    assert Node(base='node').to_dict()['base'] == 'node'  # type: ignore[arg-type]
    assert Node(base=Base.NODE) == Node.from_dict({'nodl_version': 2, 'base': 'node',
                                                   'main': {'nodl_version': 2}})


def test_node_without_base_or_mixins() -> None:
    node = Node.from_dict({'nodl_version': 2, 'main': {'nodl_version': 2}, 'mixins': []})
    assert node.base is None and node.mixins == []
    assert node.to_dict() == {'nodl_version': 2, 'mixins': [], 'main': {'nodl_version': 2}}


def test_from_dict_does_not_alias_the_input() -> None:
    data = {'nodl_version': 2, 'main': {'nodl_version': 2, 'publishers': [
        {'name': 'a', 'type': 'p/msg/T', 'qos': dict(QOS)}]}}
    snapshot = copy.deepcopy(data)
    node = Node.from_dict(data)
    node.main.publishers[0].name = 'changed'
    node.main.publishers.append(node.main.publishers[0])
    assert data == snapshot


# -- round trips over the fixtures ---------------------------------------------------------

@pytest.mark.parametrize('path', VALID, ids=lambda p: p.name)
@pytest.mark.parametrize('fmt', ['yaml', 'json'])
def test_load_dump_load(path: Path, fmt: str) -> None:
    first = load_nodl(path, strict=True)
    text = dump_nodl(first, format=fmt)
    second = load_nodl(text, strict=True)
    assert type(second) is type(first)
    assert second == first
    assert dump_nodl(second, format=fmt) == text


@pytest.mark.parametrize('path', VALID, ids=lambda p: p.name)
def test_model_keeps_everything_the_file_says(path: Path) -> None:
    report = check_source(path)
    model = report.model()
    assert model.to_dict() == report.data


def test_valid_fixtures_cover_every_kind_and_both_formats() -> None:
    kinds = {type(load_nodl(p)).__name__ for p in VALID}
    assert kinds == {'ParameterDefinition', 'Interface', 'Node'}
    assert any(p.suffix == '.json' for p in VALID) and any(p.suffix == '.yaml' for p in VALID)


CODEGEN = {'cpp': {'role': 'base_class', 'header': 'rclcpp/rclcpp.hpp'}, 'python': {}}


def test_codegen_of_an_interface_is_kept_as_written() -> None:
    data = {'nodl_version': 2, 'description': 'd', 'codegen': copy.deepcopy(CODEGEN),
            'publishers': []}
    iface = Interface.from_dict(data)
    assert iface.codegen == CODEGEN
    assert list(iface.to_dict()) == ['nodl_version', 'description', 'codegen', 'publishers']
    assert iface.to_dict() == data
    # A copy: changing what was read does not change the model, nor the other way round.
    data['codegen']['cpp']['role'] = 'changed'
    assert iface.codegen == CODEGEN
    iface.to_dict()['codegen']['python']['x'] = 1
    assert iface.codegen == CODEGEN
    assert load_interface(dump_nodl(iface)) == iface


def test_codegen_of_a_node_is_kept_as_written() -> None:
    data = {'nodl_version': 2, 'base': 'node', 'codegen': copy.deepcopy(CODEGEN),
            'main': {'nodl_version': 2}}
    node = Node.from_dict(data)
    assert node.codegen == CODEGEN and node.main.codegen is None
    assert node.to_dict() == data
    assert load_node(dump_nodl(node, 'json')) == node
    assert 'codegen' not in Node.from_dict({'nodl_version': 2, 'main': {'nodl_version': 2}}).to_dict()
