"""The vocabulary: each table once, and every other copy (schemas, CMake, model) agreeing with it."""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path
from typing import Any

import pytest

from nodl import vocabulary as v

ROOT = Path(__file__).resolve().parent.parent
SCHEMAS = ROOT / 'nodl' / 'schemas'
CMAKE = ROOT / 'ros' / 'ament_nodl' / 'cmake' / 'ament_nodl_register.cmake'


def _schema(kind: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((SCHEMAS / f'{kind}.schema.json').read_text())
    return data


def test_section_keys_are_the_schema_sections_in_file_order() -> None:
    properties = _schema('interface')['definitions']['interface']['properties']
    arrays = [key for key, value in properties.items() if value.get('type') == 'array']
    assert list(v.SECTION_KEYS) == arrays


def test_sections_use_the_schema_type_of_their_namespace() -> None:
    properties = _schema('interface')['definitions']['interface']['properties']
    for section in v.SECTIONS:
        ref = properties[section.key]['items']['$ref']
        assert ref == f'#/definitions/{section.kind}_endpoint', section.key
        assert v.KIND_NAMESPACES[section.kind] == section.namespace


def test_section_table_is_consistent() -> None:
    assert v.ENDPOINT_KINDS == ('topic', 'service', 'action')
    assert v.TOPIC_SECTIONS + v.SERVICE_SECTIONS + v.ACTION_SECTIONS == v.SECTION_KEYS
    assert len({s.word for s in v.SECTIONS}) == len(v.SECTIONS)
    assert len({s.permission for s in v.SECTIONS}) == len(v.SECTIONS)
    for section in v.SECTIONS:
        assert v.SECTION_BY_KEY[section.key] is section
        assert v.section_for_role(section.kind, section.legacy_role) == section.key
        assert section.key.startswith(section.word.replace(' ', '_').split('_')[0])
    assert v.section_for_role('topic', 'server') is None


def test_legacy_roles_are_those_of_the_legacy_frontend() -> None:
    from nodl.frontends import legacy_xml
    from nodl.legacy import convert

    assert legacy_xml.TOPIC_ROLES == ('publisher', 'subscription')
    assert legacy_xml.SERVICE_ROLES == legacy_xml.ACTION_ROLES == ('server', 'client')
    assert convert.SECTIONS['service'] == {'server': 'service_servers', 'client': 'service_clients'}


def test_model_and_consumers_derive_their_sections() -> None:
    from nodl.live.observe import ObservedNode
    from nodl.model import ENDPOINT_SECTIONS, Interface
    from nodl.validation.interfaces import SECTIONS

    assert tuple(ENDPOINT_SECTIONS) == v.SECTION_KEYS
    assert SECTIONS == v.SECTION_WORDS
    interface_fields = [f.name for f in dataclasses.fields(Interface)]
    assert [f for f in interface_fields if f in v.SECTION_KEYS] == list(v.SECTION_KEYS)
    observed_fields = [f.name for f in dataclasses.fields(ObservedNode)]
    assert [f for f in observed_fields if f in v.SECTION_KEYS] == list(v.SECTION_KEYS)


@pytest.mark.parametrize('kind', list(v.Kind))
def test_every_kind_has_a_schema(kind: v.Kind) -> None:
    assert _schema(kind.value)['$id'] == f'urn:nodl:schema:2:{kind.value}'


def test_document_keys_match_the_schemas() -> None:
    from nodl.validation.kinds import INTERFACE_KEYS, NODE_KEYS, Kind

    assert Kind is v.Kind and INTERFACE_KEYS is v.INTERFACE_KEYS and NODE_KEYS is v.NODE_KEYS
    interface = _schema('interface')['definitions']['interface']['properties']
    # The version, a description and codegen (code generator settings, the reference
    # implementation's) say nothing about which kind a document is.
    metadata = ('nodl_version', 'description', 'codegen')
    assert list(v.INTERFACE_KEYS) == [k for k in interface if k not in metadata]
    assert set(v.NODE_KEYS) == set(_schema('node')['properties']) - set(metadata)


def test_parameter_types_match_the_schema() -> None:
    type_schema = _schema('parameter')['definitions']['parameter_type']['anyOf']
    assert tuple(type_schema[0]['enum']) == v.PARAMETER_TYPES
    assert type_schema[1]['pattern'] == f'^({"|".join(b + "_fixed" for b in v.FIXED_BASES)})_[1-9][0-9]*$'


def test_qos_keys_match_the_schema_and_the_model() -> None:
    from nodl.model import QOS_POLICIES, QoSProfile

    qos = _schema('interface')['definitions']['qos_profile']
    assert set(v.QOS_KEYS) == set(qos['properties'])
    assert tuple(qos['required']) == v.QOS_REQUIRED
    enums = {k: tuple(p['enum']) for k, p in qos['properties'].items() if 'enum' in p}
    assert enums == v.QOS_ENUMS
    assert set(v.QOS_DURATIONS) == {k for k in v.QOS_KEYS if k.endswith('_ns')}
    assert tuple(f.name for f in dataclasses.fields(QoSProfile)) == v.QOS_KEYS == QOS_POLICIES
    assert all(v.QOS_DEFAULT_VALUE in values for values in v.QOS_ENUMS.values())


def test_legacy_qos_values_are_the_v2_values_and_the_legacy_extras() -> None:
    from nodl.frontends.legacy_xml import LEGACY_ONLY_QOS_VALUES, QOS_VALUES

    for policy, values in v.QOS_ENUMS.items():
        extras = LEGACY_ONLY_QOS_VALUES.get(policy, ())
        assert QOS_VALUES[policy] == tuple(x.lower() for x in values) + extras
        assert not {x.upper() for x in extras} & set(values)


def test_cmake_registers_under_the_python_resource_types() -> None:
    text = CMAKE.read_text()
    calls = dict(re.findall(r'_ament_nodl_register\((node|interface) (\w+) ', text))
    assert calls == {kind.value: resource for kind, resource in v.RESOURCE_TYPES.items()}
    assert '${PROJECT_NAME}' + v.RESOURCE_SEPARATOR + '${key}' in text
    # every resource type the CMake functions register is one of the vocabulary's
    literal = set(re.findall(r'ament_index_register_resource\((\w+)', text)) - {'resource_type'}
    assert literal == {v.NODE_INFO_RESOURCE}
    from nodl.registry import node_info

    assert node_info.NODE_INFO_RESOURCE is v.NODE_INFO_RESOURCE


def test_python_consumers_use_the_resource_types() -> None:
    from nodl import packaging
    from nodl.registry import registrations

    assert packaging.NODE_RESOURCE == registrations.NODE_RESOURCE == v.NODE_RESOURCE
    assert packaging.INTERFACE_RESOURCE == registrations.INTERFACE_RESOURCE == v.INTERFACE_RESOURCE
    assert registrations.resource_name('pkg', 'x') == v.resource_name('pkg', 'x') == 'pkg__x'


def test_vocabulary_imports_nothing_heavy() -> None:
    import subprocess
    import sys

    code = ('import sys, nodl.vocabulary; '
            'print(sorted(m for m in sys.modules if m.startswith("nodl")))')
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                         cwd=ROOT, timeout=60, check=True).stdout
    assert out.strip() == "['nodl', 'nodl.version', 'nodl.vocabulary']"  # nodl.version: the root's


def test_every_table_keyed_by_parameter_type_covers_the_vocabulary() -> None:
    """Per-language and per-ROS tables keyed by parameter type: none missing, none extra."""
    from rcl_interfaces.msg import ParameterType

    from nodl.generate.cpp.text import CPP_TYPES
    from nodl.generate.python import _PY_TYPES
    from nodl.live.observe import _PARAMETER_TYPES
    from nodl.plan.parameter_plan import ROS_TYPES

    assert set(ROS_TYPES) == set(_PY_TYPES) == set(v.PARAMETER_TYPES)
    # a C++ field of type none is an rclcpp::ParameterValue (generate/cpp/parameter_code.py)
    assert set(CPP_TYPES) == set(v.PARAMETER_TYPES) - {'none'}
    # the numbers the live observation reads are rcl_interfaces' constants of those names
    assert {getattr(ParameterType, ROS_TYPES[word]): word for word in ROS_TYPES} == _PARAMETER_TYPES


def test_tables_beside_the_validator_table_name_its_rows() -> None:
    from nodl.plan.parameter_plan import _RANGE_VALIDATORS
    from nodl.validation.parameters import _CONFLICTS
    from nodl.validation.validators import VALIDATORS

    named = set(_RANGE_VALIDATORS) | {name for pair in _CONFLICTS for name in (pair[0], *pair[1])}
    assert named <= set(VALIDATORS), named - set(VALIDATORS)


def test_ros_parameter_types_are_rcl_interfaces_constants() -> None:
    """One table of ParameterType names and numbers; the by-name and by-number views derive."""
    from rcl_interfaces.msg import ParameterType

    assert set(v.ROS_PARAMETER_TYPES) == set(v.PARAMETER_TYPES)
    for word, (name, number) in v.ROS_PARAMETER_TYPES.items():
        assert getattr(ParameterType, name) == number, word
    assert {n: w for w, (_, n) in v.ROS_PARAMETER_TYPES.items()} == v.PARAMETER_TYPE_BY_NUMBER
    assert {w: name for w, (name, _) in v.ROS_PARAMETER_TYPES.items()} == v.ROS_PARAMETER_TYPE_NAMES
