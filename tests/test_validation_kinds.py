"""Detecting the kind of a document: nodl.validation.kinds."""

from __future__ import annotations

from typing import Any

import pytest

from nodl import load_schema
from nodl.loading import check_source
from nodl.validation.kinds import INTERFACE_KEYS, NODE_KEYS, Kind, detect_kind


@pytest.mark.parametrize(('data', 'kind'), [
    # No nodl_version: a parameter definition.
    ({'type': 'int'}, Kind.PARAMETER),
    ({'type': 'int', 'default_value': 1, 'description': 'x'}, Kind.PARAMETER),
    ({}, Kind.PARAMETER),
    ({'description': 'only a description'}, Kind.PARAMETER),
    ({'default_value': 3}, Kind.PARAMETER),
    # nodl_version and a node key: a node definition.
    ({'nodl_version': 2, 'main': {}}, Kind.NODE),
    ({'nodl_version': 2, 'base': 'node'}, Kind.NODE),
    ({'nodl_version': 2, 'mixins': []}, Kind.NODE),
    ({'nodl_version': 2, 'base': 'node', 'main': {}, 'mixins': [], 'publishers': []}, Kind.NODE),
    # nodl_version without node keys: an interface definition.
    ({'nodl_version': 2}, Kind.INTERFACE),
    ({'nodl_version': 2, 'publishers': []}, Kind.INTERFACE),
    ({'nodl_version': 2, 'parameters': {}}, Kind.INTERFACE),
    ({'nodl_version': 1}, Kind.INTERFACE),           # any version value counts
    ({'nodl_version': 2, 'type': 'int'}, Kind.INTERFACE),
])
def test_detect_kind(data: dict, kind: Kind) -> None:
    assert detect_kind(data) is kind


@pytest.mark.parametrize('key', INTERFACE_KEYS)
def test_interface_that_forgot_nodl_version(key: str) -> None:
    assert detect_kind({key: None}) is Kind.INTERFACE


@pytest.mark.parametrize('key', NODE_KEYS)
def test_node_that_forgot_nodl_version(key: str) -> None:
    assert detect_kind({key: None}) is Kind.NODE
    assert detect_kind({key: None, 'publishers': []}) is Kind.NODE


@pytest.mark.parametrize('key', INTERFACE_KEYS + NODE_KEYS)
def test_a_type_key_makes_it_a_parameter(key: str) -> None:
    # With 'type' and no nodl_version it is a (wrong) parameter definition.
    assert detect_kind({'type': 'int', key: None}) is Kind.PARAMETER


@pytest.mark.parametrize('data', [None, 5, 0, 'text', 'nodl_version', [], ['nodl_version'],
                                  [{'nodl_version': 2}], 1.5, True])
def test_not_a_mapping_is_never_an_error(data: Any) -> None:
    assert detect_kind(data) is Kind.PARAMETER


def test_the_keys_match_the_schemas() -> None:
    # metadata (the version, a description, code generators' settings) decides no kind
    interface = load_schema('interface')['definitions']['interface']['properties']
    assert set(INTERFACE_KEYS) == set(interface) - {'nodl_version', 'description', 'codegen'}
    node = load_schema('node')['properties']
    assert set(NODE_KEYS) == set(node) - {'nodl_version', 'codegen'}


def test_kind_values() -> None:
    assert [k.value for k in Kind] == ['parameter', 'interface', 'node']
    assert Kind('node') is Kind.NODE
    assert str(Kind.INTERFACE) == 'interface'
    assert Kind.PARAMETER == 'parameter'
    assert f'{Kind.NODE} definition' == 'node definition'


def test_forgotten_nodl_version_is_reported_as_missing() -> None:
    report = check_source('publishers:\n  - name: chatter\n    type: std_msgs/msg/String\n'
                          '    description: x\n'
                          '    qos: {history: KEEP_ALL, reliability: RELIABLE}\n')
    assert report.kind is Kind.INTERFACE
    assert [d.message for d in report.errors] == ["missing required key 'nodl_version'"]


def test_forgotten_nodl_version_in_a_node_is_reported_as_missing() -> None:
    report = check_source('base: node\nmain:\n  nodl_version: 2\n')
    assert report.kind is Kind.NODE
    assert [str(d) for d in report.errors] == [
        "<string>:1:1: error: missing required key 'nodl_version' [NODL102]"]


def test_parameter_document_is_not_told_about_nodl_version() -> None:
    report = check_source('type: int\ndefault_value: 3\ndescription: x\n')
    assert report.kind is Kind.PARAMETER
    assert report.diagnostics == []
