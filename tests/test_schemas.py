"""The shipped JSON Schemas: nodl.schemas."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import jsonschema
import pytest

from nodl.loading import check_source
from nodl.schemas import KINDS, bundled_schema, load_schema, schema_path
from nodl.validation.engine import FORMATS
from nodl.validation.parameters import BUILTIN_VALIDATORS

FIXTURES = Path(__file__).parent / 'fixtures'


def _walk(node: Any) -> Iterator[dict[str, Any]]:
    if isinstance(node, dict):
        yield node
        for value in node.values():
            yield from _walk(value)
    elif isinstance(node, list):
        for value in node:
            yield from _walk(value)


def _resolve(schema: dict[str, Any], pointer: str) -> Any:
    node: Any = schema
    for part in [p for p in pointer.split('/') if p]:
        node = node[part.replace('~1', '/').replace('~0', '~')]
    return node


def test_kinds() -> None:
    assert KINDS == ('parameter', 'interface', 'node')


@pytest.mark.parametrize('kind', KINDS)
def test_shipped_schema_is_a_valid_draft7_schema(kind: str) -> None:
    schema = load_schema(kind)
    assert schema['$schema'] == 'http://json-schema.org/draft-07/schema#'
    jsonschema.Draft7Validator.check_schema(schema)


@pytest.mark.parametrize('kind', KINDS)
def test_stable_id(kind: str) -> None:
    assert load_schema(kind)['$id'] == f'urn:nodl:schema:2:{kind}'
    assert bundled_schema(kind)['$id'] == f'urn:nodl:schema:2:{kind}'


@pytest.mark.parametrize('kind', KINDS)
def test_schema_path_and_file_content(kind: str) -> None:
    path = schema_path(kind)
    assert path.name == f'{kind}.schema.json'
    assert path.is_file()
    assert json.loads(path.read_text(encoding='utf-8')) == load_schema(kind)


@pytest.mark.parametrize('kind', ['nodes', '', 'Node', 'schema'])
def test_unknown_kind(kind: str) -> None:
    with pytest.raises(ValueError, match='unknown schema kind'):
        schema_path(kind)
    with pytest.raises(ValueError):
        load_schema(kind)


def test_load_schema_returns_a_fresh_copy() -> None:
    first = load_schema('node')
    first['properties'].clear()
    first['definitions'] = 'changed'
    assert load_schema('node')['properties']
    assert 'definitions' not in load_schema('node')
    bundled = bundled_schema('node')
    bundled['definitions'].clear()
    assert bundled_schema('node')['definitions']


@pytest.mark.parametrize('kind', KINDS)
def test_bundled_schema_has_no_external_reference(kind: str) -> None:
    bundled = bundled_schema(kind)
    refs = [node['$ref'] for node in _walk(bundled) if isinstance(node.get('$ref'), str)]
    assert refs, 'a schema without references?'
    assert all(ref.startswith('#') for ref in refs), refs
    for ref in refs:  # each one resolves inside the bundle
        assert isinstance(_resolve(bundled, ref[1:]), dict), ref


@pytest.mark.parametrize('kind', KINDS)
def test_bundled_schema_is_a_valid_draft7_schema(kind: str) -> None:
    jsonschema.Draft7Validator.check_schema(bundled_schema(kind))


def test_bundled_schemas_carry_their_dependencies() -> None:
    node = bundled_schema('node')['definitions']
    assert {'interface', 'topic_endpoint', 'qos_profile', 'parameter_definition',
            'validation'} <= set(node)
    interface = bundled_schema('interface')['definitions']
    assert {'interface', 'parameter_definition', 'bounds_validator'} <= set(interface)
    # The parameter schema has nothing to import.
    assert bundled_schema('parameter') == load_schema('parameter')


@pytest.mark.parametrize('kind', ['interface', 'node'])
def test_bundling_keeps_every_definition_unchanged(kind: str) -> None:
    bundled = bundled_schema(kind)['definitions']
    for source in KINDS:
        for name, definition in load_schema(source).get('definitions', {}).items():
            if name in bundled:
                text = json.dumps(definition).replace('parameter.schema.json#', '#') \
                    .replace('interface.schema.json#', '#')
                assert json.loads(text) == bundled[name], name


def test_shipped_refs_point_at_existing_definitions() -> None:
    for kind in KINDS:
        for node in _walk(load_schema(kind)):
            ref = node.get('$ref')
            if not isinstance(ref, str):
                continue
            file_name, _, pointer = ref.partition('#')
            target = load_schema(file_name.split('.')[0]) if file_name else load_schema(kind)
            assert isinstance(_resolve(target, pointer), dict), (kind, ref)


def test_every_format_is_checked_by_the_validator() -> None:
    formats = {node['format'] for kind in KINDS for node in _walk(load_schema(kind))
               if isinstance(node.get('format'), str)}
    assert formats == set(FORMATS)


def test_interface_schema_forbids_node_keys() -> None:
    interface = load_schema('interface')['definitions']['interface']
    assert interface['additionalProperties'] is False
    for key in ('base', 'main', 'mixins'):
        assert key not in interface['properties']
        assert key in interface['x-nodl-key-hints']
    validator = jsonschema.Draft7Validator(bundled_schema('interface'))
    for key, value in (('base', 'node'), ('main', {'nodl_version': 2}), ('mixins', [])):
        assert not validator.is_valid({'nodl_version': 2, key: value}), key
    assert validator.is_valid({'nodl_version': 2})


def test_node_schema_shape() -> None:
    node = load_schema('node')
    assert node['required'] == ['nodl_version', 'main']
    assert node['properties']['base']['enum'] == ['node', 'lifecycle_node']
    assert node['additionalProperties'] is False
    validator = jsonschema.Draft7Validator(bundled_schema('node'))
    assert validator.is_valid({'nodl_version': 2, 'main': {'nodl_version': 2}})
    assert not validator.is_valid({'nodl_version': 2})
    assert not validator.is_valid({'nodl_version': 2, 'main': {'nodl_version': 2},
                                   'base': 'component'})


def test_parameter_schema_shape() -> None:
    validator = jsonschema.Draft7Validator(bundled_schema('parameter'))
    assert validator.is_valid({'type': 'int'})
    assert validator.is_valid({'type': 'string_array_fixed_12'})
    for bad in ({}, {'type': 'integer'}, {'type': 'bool_array_fixed_2'}, {'type': 'int_fixed_2'},
                {'type': 'string_fixed_0'}, {'type': 'int', 'extra': 1}):
        assert not validator.is_valid(bad), bad


def test_parameter_schema_has_every_builtin_validator_with_and_without_brackets() -> None:
    properties = load_schema('parameter')['definitions']['validation']['properties']
    expected = set(BUILTIN_VALIDATORS) | {name + '<>' for name in BUILTIN_VALIDATORS}
    assert set(properties) == expected
    for name in BUILTIN_VALIDATORS:
        assert properties[name] == properties[name + '<>']


def _valid_fixtures() -> list[Path]:
    return sorted((FIXTURES / 'valid').iterdir())


@pytest.mark.parametrize('path', _valid_fixtures(), ids=lambda p: p.name)
def test_bundled_schema_accepts_the_valid_fixtures(path: Path) -> None:
    report = check_source(path)
    assert report.kind is not None
    jsonschema.validate(report.data, bundled_schema(report.kind.value),
                        cls=jsonschema.Draft7Validator)
