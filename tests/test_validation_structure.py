"""The structural check: nodl.validation.structure, an interpreter of the shipped schemas.

Messages (did you mean, enums, anyOf, required keys, key hints, the KEEP_LAST
rule), the interpreter's keywords on small inline schemas, and agreement
with the ``jsonschema`` library on the same (bundled) schemas.
"""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import jsonschema
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nodl import bundled_schema
from nodl.diagnostics import Diagnostic, Severity
from nodl.loading import check_source
from nodl.validation import Kind, validate_data
from nodl.validation.engine import FORMATS
from nodl.validation.structure import SchemaCompiler

FIXTURES = Path(__file__).parent / 'fixtures'
QOS = {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE'}


def structure(data: Any, kind: Kind) -> list[Diagnostic]:
    """Only the structural diagnostics (the schema, with format checks)."""
    out: list[Diagnostic] = []
    SchemaCompiler(FORMATS).compile_ref(f'{kind.value}.schema.json')(data, (), out)
    return out


def errors(data: Any, kind: Kind) -> list[Diagnostic]:
    return [d for d in validate_data(data, kind) if d.severity is Severity.ERROR]


def inline(schema: dict[str, Any], value: Any, formats: dict | None = None) -> list[Diagnostic]:
    out: list[Diagnostic] = []
    SchemaCompiler(formats or {}).compile(schema, 'inline')(value, ('x',), out)
    return out


def topic(**changes: Any) -> dict[str, Any]:
    entry = {'name': 'chatter', 'type': 'std_msgs/msg/String', 'description': 'd',
             'qos': dict(QOS)}
    entry.update(changes)
    return entry


# -- unknown keys ----------------------------------------------------------------

@pytest.mark.parametrize(('key', 'suggestion'), [
    ('subscribers', 'subscriptions'), ('publisher', 'publishers'), ('paramters', 'parameters'),
    ('Publishers', 'publishers'), ('service_server', 'service_servers'),
    ('action_client', 'action_clients'), ('nodl_verison', 'nodl_version'),
    ('descripton', 'description')])
def test_unknown_key_names_the_closest(key: str, suggestion: str) -> None:
    found = errors({'nodl_version': 2, key: []}, Kind.INTERFACE)
    assert [(d.path, d.anchor, d.message) for d in found] == [
        ((key,), 'key', f"unknown key '{key}'; did you mean '{suggestion}'?")]


def test_unknown_key_without_a_close_match_lists_the_keys() -> None:
    found = errors({'nodl_version': 2, 'author': 'me'}, Kind.INTERFACE)
    assert [d.message for d in found] == [
        "unknown key 'author'; expected one of: nodl_version, description, codegen, parameters, "
        'publishers, subscriptions, service_servers, service_clients, action_servers, '
        'action_clients']


@pytest.mark.parametrize(('kind', 'data', 'path', 'suggestion'), [
    (Kind.PARAMETER, {'type': 'int', 'defaultvalue': 1}, ('defaultvalue',), 'default_value'),
    (Kind.PARAMETER, {'type': 'int', 'readonly': True}, ('readonly',), 'read_only'),
    (Kind.NODE, {'nodl_version': 2, 'main': {'nodl_version': 2}, 'mixin': []}, ('mixin',),
     'mixins'),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(qos=dict(QOS, dept=1))]},
     ('publishers', 0, 'qos', 'dept'), 'depth'),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(types='x')]},
     ('publishers', 0, 'types'), 'type'),
])
def test_unknown_keys_at_every_level(kind: Kind, data: dict, path: tuple, suggestion: str) -> None:
    found = errors(data, kind)
    assert [(d.path, d.anchor) for d in found] == [(path, 'key')]
    assert found[0].message.endswith(f"did you mean '{suggestion}'?")


def test_validation_mapping_allows_any_function_name() -> None:
    # additionalProperties there is a schema (custom validators), not false.
    assert errors({'type': 'int', 'validation': {'anything_at_all': None}}, Kind.PARAMETER) == []


# -- x-nodl-key-hints --------------------------------------------------------------

@pytest.mark.parametrize(('key', 'value', 'hint'), [
    ('main', {'nodl_version': 2}, "'main' belongs to a node definition; an interface definition "
                                  '(and so a mixin) cannot declare one'),
    ('base', 'node', "'base' belongs to a node definition; an interface definition (and so a "
                     'mixin) cannot declare one'),
    ('mixins', [], "'mixins' belongs to a node definition; mixins are single-level and cannot "
                   'declare further mixins'),
])
def test_interface_with_node_keys_says_they_belong_to_a_node(key: str, value: Any,
                                                             hint: str) -> None:
    found = errors({'nodl_version': 2, key: value}, Kind.INTERFACE)
    assert [(d.path, d.anchor, d.message) for d in found] == [
        ((key,), 'key', f"unknown key '{key}': {hint}")]


def test_in_place_mixin_with_node_keys() -> None:
    data = {'nodl_version': 2, 'main': {'nodl_version': 2},
            'mixins': [{'nodl_version': 2, 'base': 'node', 'mixins': ['x.nodl.yaml']}]}
    found = errors(data, Kind.NODE)
    assert [d.path for d in found] == [('mixins', 0, 'base'), ('mixins', 0, 'mixins')]
    assert all('belongs to a node definition' in d.message or 'single-level' in d.message
               for d in found)


# -- enums and consts --------------------------------------------------------------

@pytest.mark.parametrize(('policy', 'value', 'allowed'), [
    ('history', 'LAST', 'KEEP_LAST, KEEP_ALL, SYSTEM_DEFAULT'),
    ('reliability', 'SOMETIMES', 'RELIABLE, BEST_EFFORT, SYSTEM_DEFAULT, BEST_AVAILABLE'),
    ('durability', 'PERSISTENT', 'TRANSIENT_LOCAL, VOLATILE, SYSTEM_DEFAULT, BEST_AVAILABLE'),
    ('liveliness', 'MANUAL', 'AUTOMATIC, MANUAL_BY_TOPIC, SYSTEM_DEFAULT, BEST_AVAILABLE'),
])
def test_enum_message_lists_the_allowed_values(policy: str, value: str, allowed: str) -> None:
    qos = dict(QOS)
    qos[policy] = value
    found = errors({'nodl_version': 2, 'publishers': [topic(qos=qos)]}, Kind.INTERFACE)
    messages = [d.message for d in found if d.path == ('publishers', 0, 'qos', policy)]
    assert len(messages) == 1
    assert messages[0].startswith(f"invalid value '{value}' for '{policy}'; expected one of: "
                                  f'{allowed}')


def test_enum_suggests_a_case_fix() -> None:
    found = errors({'nodl_version': 2, 'base': 'Lifecycle_Node', 'main': {'nodl_version': 2}},
                   Kind.NODE)
    assert [d.message for d in found] == [
        "invalid value 'Lifecycle_Node' for 'base'; expected one of: node, lifecycle_node; "
        "did you mean 'lifecycle_node'?"]


@pytest.mark.parametrize(('value', 'shown'), [(1, '1'), (3, '3'), ('2', "'2'"), (True, 'true'),
                                              (None, 'null'), (2.5, '2.5')])
def test_nodl_version_must_be_2(value: Any, shown: str) -> None:
    found = errors({'nodl_version': value}, Kind.INTERFACE)
    assert [(d.path, d.message) for d in found] == [
        (('nodl_version',), f"'nodl_version' must be 2, not {shown}")]


# -- required keys -------------------------------------------------------------------

def test_missing_required_keys_are_each_reported_at_the_parent() -> None:
    found = errors({'nodl_version': 2, 'publishers': [{'description': 'x'}]}, Kind.INTERFACE)
    assert [(d.path, d.anchor, d.message) for d in found] == [
        (('publishers', 0), 'key', f"missing required key '{key}' in item 0 of 'publishers'")
        for key in ('name', 'type', 'qos')]


@pytest.mark.parametrize(('kind', 'data', 'message'), [
    (Kind.PARAMETER, {'description': 'x'}, "missing required key 'type'"),
    (Kind.INTERFACE, {'publishers': []}, "missing required key 'nodl_version'"),
    (Kind.NODE, {'nodl_version': 2}, "missing required key 'main'"),
    (Kind.NODE, {'nodl_version': 2, 'main': {}}, "missing required key 'nodl_version' in 'main'"),
])
def test_missing_required_key_messages(kind: Kind, data: dict, message: str) -> None:
    assert [d.message for d in errors(data, kind)] == [message]


def test_qos_requires_history_and_reliability() -> None:
    found = errors({'nodl_version': 2, 'publishers': [topic(qos={})]}, Kind.INTERFACE)
    assert [d.message for d in found] == [
        "missing required key 'history' in 'qos'", "missing required key 'reliability' in 'qos'"]


def test_services_and_actions_do_not_require_qos() -> None:
    data = {'nodl_version': 2,
            'service_servers': [{'name': 's', 'type': 'std_srvs/srv/Trigger'}],
            'action_servers': [{'name': 'a', 'type': 'test_msgs/action/Fibonacci'}]}
    assert errors(data, Kind.INTERFACE) == []


def test_actions_take_no_qos() -> None:
    data = {'nodl_version': 2, 'action_servers': [
        {'name': 'a', 'type': 'test_msgs/action/Fibonacci', 'qos': dict(QOS)}]}
    assert [(d.path, d.message) for d in errors(data, Kind.INTERFACE)] == [
        (('action_servers', 0, 'qos'),
         "unknown key 'qos'; expected one of: name, type, description")]


# -- wrong types ---------------------------------------------------------------------

@pytest.mark.parametrize(('key', 'value', 'message'), [
    ('publishers', {'a': 1}, "'publishers' must be a list, not a mapping"),
    ('publishers', 'chatter', "'publishers' must be a list, not a string ('chatter')"),
    ('parameters', ['gain'], "'parameters' must be a mapping, not a list (['gain'])"),
    ('description', 42, "'description' must be a string, not an integer (42)"),
    ('description', None, "'description' must be a string, not null"),
])
def test_wrong_types_at_the_top(key: str, value: Any, message: str) -> None:
    found = errors({'nodl_version': 2, key: value}, Kind.INTERFACE)
    assert [(d.path, d.anchor, d.message) for d in found] == [((key,), 'value', message)]


@pytest.mark.parametrize(('key', 'value', 'message'), [
    ('read_only', 'yes please', "'read_only' must be a boolean (true or false), not a string "
                                "('yes please')"),
    ('read_only', 1, "'read_only' must be a boolean (true or false), not an integer (1)"),
    ('description', ['a'], "'description' must be a string, not a list (['a'])"),
    ('additional_constraints', 5, "'additional_constraints' must be a string, not an integer (5)"),
    ('validation', ['bounds<>'], "'validation' must be a mapping, not a list (['bounds<>'])"),
    ('type', 5, "'type' must be a string, not an integer (5)"),
])
def test_wrong_types_in_a_parameter(key: str, value: Any, message: str) -> None:
    data = {'type': 'int', key: value}
    assert [d.message for d in errors(data, Kind.PARAMETER)] == [message]


@pytest.mark.parametrize(('value', 'message'), [
    (1.5, "'depth' must be an integer, not a number (1.5)"),
    ('10', "'depth' must be an integer, not a string ('10')"),
    (True, "'depth' must be an integer, not a boolean (true)"),
    (0, "'depth' must be at least 1, got 0"),
])
def test_depth(value: Any, message: str) -> None:
    found = errors({'nodl_version': 2, 'publishers': [topic(qos=dict(QOS, depth=value))]},
                   Kind.INTERFACE)
    assert [(d.path, d.message) for d in found] == [(('publishers', 0, 'qos', 'depth'), message)]


@pytest.mark.parametrize('policy', ['deadline_ns', 'lifespan_ns', 'liveliness_lease_duration_ns'])
def test_durations_are_non_negative_integers(policy: str) -> None:
    for value, ok in ((0, True), (10**12, True), (-1, False), (0.5, False)):
        found = errors({'nodl_version': 2, 'publishers': [topic(qos=dict(QOS, **{policy: value}))]},
                       Kind.INTERFACE)
        assert (found == []) is ok, (policy, value, found)


def test_a_type_error_stops_the_checks_below_it() -> None:
    # 'publishers' is not a list: its items are not looked at.
    found = errors({'nodl_version': 2, 'publishers': 'x'}, Kind.INTERFACE)
    assert len(found) == 1


def test_non_string_keys() -> None:
    found = errors({'nodl_version': 2, 'parameters': {5: {'type': 'int'}}}, Kind.INTERFACE)
    assert [(d.path, d.anchor, d.message) for d in found] == [
        (('parameters', 5), 'key', 'key 5 must be a string, not an integer')]


def test_not_a_mapping() -> None:
    for kind in Kind:
        found = errors(['x'], kind)
        assert [d.message for d in found] == ["the document must be a mapping, not a list (['x'])"]


# -- anyOf ---------------------------------------------------------------------------

@pytest.mark.parametrize(('value', 'message'), [
    (3, "item 0 of 'mixins' must be a string or a mapping; got an integer (3)"),
    (None, "item 0 of 'mixins' must be a string or a mapping; got null"),
    (['a'], "item 0 of 'mixins' must be a string or a mapping; got a list (['a'])"),
])
def test_any_of_without_a_fitting_branch_names_the_expected_kinds(value: Any,
                                                                 message: str) -> None:
    data = {'nodl_version': 2, 'main': {'nodl_version': 2}, 'mixins': [value]}
    assert [(d.path, d.message) for d in errors(data, Kind.NODE)] == [(('mixins', 0), message)]


def test_any_of_reports_the_problems_of_the_branch_that_fits() -> None:
    # A mapping fits the interface branch: its own problems are reported.
    data = {'nodl_version': 2, 'main': {'nodl_version': 2},
            'mixins': [{'nodl_version': 2, 'publisher': []}]}
    assert [(d.path, d.message) for d in errors(data, Kind.NODE)] == [
        (('mixins', 0, 'publisher'), "unknown key 'publisher'; did you mean 'publishers'?")]
    # A string fits the reference branch.
    data['mixins'] = ['/abs/x.nodl.yaml']
    found = errors(data, Kind.NODE)
    assert len(found) == 1 and 'is an absolute path' in found[0].message


@pytest.mark.parametrize(('key', 'args', 'message'), [
    ('gt', [1, 2], "invalid 'gt': expected one number: [value] or value; got [1, 2]"),
    ('gt<>', 'high', "'gt<>' must be one number: [value] or value; got a string ('high')"),
    ('size_gt', -1, "invalid 'size_gt': expected one non-negative integer: [size] or size; "
                    'got -1'),
    ('size_lt<>', [1.5], "invalid 'size_lt<>': expected one non-negative integer: [size] or "
                         'size; got [1.5]'),
    ('unique<>', [1], "invalid 'unique<>': expected no arguments: null or []; got [1]"),
    ('not_empty', 0, "'not_empty' must be no arguments: null or []; got an integer (0)"),
])
def test_any_of_with_a_description_uses_it(key: str, args: Any, message: str) -> None:
    found = errors({'type': 'string_array', 'validation': {key: args}}, Kind.PARAMETER)
    # (a validator that does not apply to string arrays adds its own error)
    assert message in [d.message for d in found if d.path == ('validation', key)
                       and d.anchor == 'value']


# -- the KEEP_LAST -> depth rule ----------------------------------------------------------

@pytest.mark.parametrize(('qos', 'ok'), [
    ({'history': 'KEEP_LAST', 'reliability': 'RELIABLE'}, False),
    ({'history': 'KEEP_LAST', 'depth': 1, 'reliability': 'RELIABLE'}, True),
    ({'history': 'KEEP_ALL', 'reliability': 'RELIABLE'}, True),
    ({'history': 'SYSTEM_DEFAULT', 'reliability': 'RELIABLE'}, True),
    ({'history': 'KEEP_ALL', 'depth': 5, 'reliability': 'RELIABLE'}, True),
])
def test_keep_last_requires_depth(qos: dict, ok: bool) -> None:
    for section, entry in (('publishers', topic(qos=qos)),
                           ('service_clients', {'name': 's', 'type': 'std_srvs/srv/Empty',
                                                'qos': qos})):
        found = errors({'nodl_version': 2, section: [entry]}, Kind.INTERFACE)
        if ok:
            assert found == []
        else:
            assert [(d.path, d.anchor, d.message) for d in found] == [
                ((section, 0, 'qos'), 'key', "'depth' is required when history is KEEP_LAST")]


def test_depth_rule_does_not_fire_for_an_invalid_history() -> None:
    found = errors({'nodl_version': 2, 'publishers': [
        topic(qos={'history': 'keep_last', 'reliability': 'RELIABLE'})]}, Kind.INTERFACE)
    assert len(found) == 1 and found[0].message.startswith("invalid value 'keep_last'")


# -- all errors at once --------------------------------------------------------------------

def test_every_error_is_reported_not_only_the_first() -> None:
    data = {
        'nodl_version': 3,
        'base': 'Node',
        'mixins': [3, '/abs.nodl.yaml'],
        'main': {
            'nodl_version': 2,
            'subscribers': [],
            'parameters': {'gain': {'type': 'integer'}, 'x': {}},
            'publishers': [topic(name='a b', type='pkg/srv/T', qos={'history': 'KEEP_LAST',
                                                                     'reliability': 'X'})],
        },
        'extra': 1,
    }
    found = errors(data, Kind.NODE)
    paths = {d.path for d in found}
    assert paths == {
        ('nodl_version',), ('base',), ('mixins', 0), ('mixins', 1), ('main', 'subscribers'),
        ('main', 'parameters', 'gain', 'type'), ('main', 'parameters', 'x'),
        ('main', 'publishers', 0, 'name'), ('main', 'publishers', 0, 'type'),
        ('main', 'publishers', 0, 'qos'), ('main', 'publishers', 0, 'qos', 'reliability'),
        ('extra',)}


# -- the interpreter on inline schemas ---------------------------------------------------------

def test_unsupported_keywords_are_refused() -> None:
    with pytest.raises(ValueError, match=r"not supported by the validator: \['maxLength'\]"):
        SchemaCompiler({}).compile({'type': 'string', 'maxLength': 3}, 'inline')


def test_the_shipped_schemas_compile() -> None:
    compiler = SchemaCompiler(FORMATS)
    for kind in Kind:
        compiler.compile_ref(f'{kind.value}.schema.json')


def test_keyword_type_union() -> None:
    assert inline({'type': ['string', 'null']}, None) == []
    assert [d.message for d in inline({'type': ['string', 'null']}, 1)] == [
        "'x' must be a string or null, not an integer (1)"]


def test_keyword_const_and_enum_distinguish_booleans_from_numbers() -> None:
    assert [d.message for d in inline({'const': 1}, True)] == ["'x' must be 1, not true"]
    assert len(inline({'enum': [1, 'a']}, True)) == 1
    assert inline({'enum': [1, 'a']}, 1) == []


def test_keyword_items_min_and_max() -> None:
    schema = {'type': 'array', 'items': {'type': 'integer'}, 'minItems': 1, 'maxItems': 2}
    assert [d.message for d in inline(schema, [])] == ["'x' needs at least 1 item, got 0"]
    assert [(d.path, d.message) for d in inline(schema, ['a', 1, 2])] == [
        (('x',), "'x' takes at most 2 items, got 3"),
        (('x', 0), "item 0 of 'x' must be an integer, not a string ('a')")]


def test_keyword_min_length() -> None:
    assert [d.message for d in inline({'minLength': 1}, '')] == ["'x' must not be empty"]
    assert [d.message for d in inline({'minLength': 3}, 'ab')] == [
        "'x' must be at least 3 characters long"]
    assert inline({'minLength': 3}, 'abc') == []


def test_keyword_pattern_properties_and_additional_properties() -> None:
    schema = {'type': 'object', 'properties': {'b': {}},
              'patternProperties': {'^a': {'type': 'integer'}}, 'additionalProperties': False}
    found = inline(schema, {'a1': 's', 'b': 1, 'c': 2})
    assert [(d.path, d.anchor) for d in found] == [(('x', 'a1'), 'value'), (('x', 'c'), 'key')]


def test_keyword_property_names_points_at_the_key() -> None:
    found = inline({'propertyNames': {'pattern': '^[a-z]+$'}}, {'ok': 1, 'Bad': 2})
    assert [(d.path, d.anchor) for d in found] == [(('x', 'Bad'), 'key')]


def test_keyword_if_then_else() -> None:
    schema = {'if': {'type': 'string'}, 'then': {'minLength': 2}, 'else': {'minimum': 3}}
    assert [d.message for d in inline(schema, 'a')] == ["'x' must be at least 2 characters long"]
    assert [d.message for d in inline(schema, 1)] == ["'x' must be at least 3, got 1"]
    assert inline(schema, 'ab') == [] and inline(schema, 5) == []


def test_keyword_all_of() -> None:
    schema = {'allOf': [{'minimum': 0}, {'type': 'integer'}]}
    assert len(inline(schema, -1.5)) == 2


def test_keyword_one_of_needs_exactly_one_branch() -> None:
    schema = {'oneOf': [{'type': 'number'}, {'type': 'integer'}]}
    assert inline(schema, 1.5) == []            # a number, not an integer: one branch
    found = inline(schema, 1)                    # both branches
    assert len(found) == 1 and 'more than one' in found[0].message
    assert len(inline(schema, 'a')) == 1         # no branch


def test_keyword_any_of_accepts_several_branches() -> None:
    assert inline({'anyOf': [{'type': 'number'}, {'type': 'integer'}]}, 1) == []


def test_x_nodl_message_replaces_the_message() -> None:
    found = inline({'type': 'string', 'pattern': '^a', 'x-nodl-message': 'custom words'}, 'b')
    assert [d.message for d in found] == ['custom words']


def test_format_checks_replace_the_schema() -> None:
    calls: list[Any] = []

    def fmt(value: Any, path: Any, out: list) -> None:
        calls.append(value)

    # The pattern would fail; the format check alone decides.
    assert inline({'type': 'string', 'format': 'f', 'pattern': '^a'}, 'b', {'f': fmt}) == []
    assert calls == ['b']


# -- agreement with jsonschema ---------------------------------------------------------------

def _fixture_documents() -> list[tuple[str, Kind, Any]]:
    docs = []
    for path in sorted((FIXTURES / 'valid').iterdir()) + sorted((FIXTURES / 'invalid').iterdir()):
        if '.nodl.' not in path.name:
            continue
        report = check_source(path)
        if report.kind is None:  # not parsed (syntax error, not a mapping, ...)
            continue
        docs.append((f'{path.parent.name}/{path.name}', report.kind, report.data))
    return docs


FIXTURE_DOCUMENTS = _fixture_documents()

# Fixtures whose only errors are beyond any JSON Schema: the schema accepts
# them, and so do our structural checks; the semantic checks reject them.
SEMANTIC_ONLY = {
    'invalid/duplicate_endpoints.nodl.yaml',
    'invalid/parameter_byte_array_range.nodl.yaml',
    'invalid/parameter_conflicting_validators.nodl.yaml',
    'invalid/parameter_default_breaks_validators.nodl.yaml',
    'invalid/parameter_default_wrong_type.nodl.yaml',
    'invalid/parameter_fixed_size_exceeded.nodl.yaml',
    'invalid/parameter_null_default.nodl.yaml',
    'invalid/parameter_validator_does_not_fit.nodl.yaml',
}
# Fixtures our format checks reject where the schema has no pattern to match
# (parameter names are a 'format' only).
FORMAT_ONLY = {
    'invalid/parameter_names.nodl.yaml',
}
# Fixtures with warnings only: valid for everyone.
WARNINGS_ONLY = {
    'invalid/missing_descriptions.nodl.yaml',
    'invalid/parameter_none_with_default.nodl.yaml',
    'invalid/short_type_form.nodl.yaml',
}


def _validator(kind: Kind) -> jsonschema.Draft7Validator:
    return jsonschema.Draft7Validator(bundled_schema(kind.value))


def test_agreement_corpus_is_complete() -> None:
    names = {name for name, _, _ in FIXTURE_DOCUMENTS}
    assert names >= SEMANTIC_ONLY | FORMAT_ONLY | WARNINGS_ONLY
    assert len([n for n in names if n.startswith('valid/')]) >= 10
    assert len([n for n in names if n.startswith('invalid/')]) >= 25


@pytest.mark.parametrize(('name', 'kind', 'data'), FIXTURE_DOCUMENTS,
                         ids=[name for name, _, _ in FIXTURE_DOCUMENTS])
def test_structure_agrees_with_jsonschema(name: str, kind: Kind, data: Any) -> None:
    theirs = [e.message for e in _validator(kind).iter_errors(data)]
    ours = [d for d in structure(data, kind) if d.severity is Severity.ERROR]
    full = errors(data, kind)
    if name.startswith('valid/') or name in WARNINGS_ONLY:
        assert theirs == [] and ours == [] and full == []
    elif name in SEMANTIC_ONLY:
        assert theirs == [] and ours == [] and full != []
    elif name in FORMAT_ONLY:
        assert theirs == [] and ours != []
    else:
        # A structural problem: both reject.
        assert theirs != [], 'jsonschema accepts a document the structural check rejects'
        assert ours != [], f'jsonschema rejects what we accept: {theirs}'


# Documents at the edges of the two validators' semantics.  Where JSON Schema
# is looser (a float with an integral value is an "integer"; formats are not
# asserted), we are stricter, never the other way round.
EDGE_CASES: list[tuple[Kind, Any, bool, bool]] = [
    # (kind, document, jsonschema accepts, we accept)
    (Kind.INTERFACE, {'nodl_version': 2.0}, True, False),
    (Kind.INTERFACE, {'nodl_version': True}, False, False),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(qos=dict(QOS, depth=2.0))]},
     True, False),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(name='{foo}')]}, True, False),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(name='a/1b')]}, True, False),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(name='1b')]}, False, False),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(type='std_msgs/String')]},
     True, True),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(type='std_msgs/srv/String')]},
     False, False),
    (Kind.INTERFACE, {'nodl_version': 2, 'publishers': [topic(type='std__msgs/msg/S')]},
     True, False),
    (Kind.NODE, {'nodl_version': 2, 'main': {'nodl_version': 2}, 'mixins': ['/abs']},
     True, False),
    (Kind.NODE, {'nodl_version': 2, 'main': {'nodl_version': 2}, 'mixins': ['']}, False, False),
    (Kind.NODE, {'nodl_version': 2, 'main': {'nodl_version': 2}, 'mixins': [' ']}, True, False),
    (Kind.PARAMETER, {'type': 'string_fixed_0'}, False, False),
    (Kind.PARAMETER, {'type': 'bool_array_fixed_2'}, False, False),
    (Kind.PARAMETER, {'type': 'int', 'validation': {'bad-name': None}}, False, False),
    (Kind.PARAMETER, {'type': 'int', 'validation': {'size_gt': [2.0]}}, True, False),
    (Kind.PARAMETER, {'type': 'int', 'validation': {'ns::f': {}}}, False, False),
    (Kind.PARAMETER, {'type': 'int', 'default_value': 'x'}, True, False),
]


@pytest.mark.parametrize(('kind', 'data', 'theirs_ok', 'ours_ok'), EDGE_CASES)
def test_edge_cases_against_jsonschema(kind: Kind, data: Any, theirs_ok: bool,
                                       ours_ok: bool) -> None:
    assert _validator(kind).is_valid(data) is theirs_ok
    assert (errors(data, kind) == []) is ours_ok


# Property: mutate valid documents at random; whenever jsonschema rejects the
# result, so does our structural check.

_VALUES = st.sampled_from([
    None, True, False, 0, 1, -1, 2, 1.5, 256, '', 'x', 'a b', '~', '~/x', '/a', '{node}',
    'KEEP_LAST',
    'std_msgs/msg/String', 'std_msgs/String', 'std_srvs/srv/Trigger', 'pkg/action/A', 'int',
    'string_fixed_3', 'bool_array_fixed_3', 'node', 'nodl://pkg/x', 'nodl://Bad', [], [1],
    [1, 2], [[1]], [0, 10], {}, {'nodl_version': 2}, {'type': 'int'},
    {'history': 'KEEP_LAST', 'reliability': 'RELIABLE'}, {'history': 'KEEP_ALL',
                                                          'reliability': 'RELIABLE'}])
_KEYS = st.sampled_from([
    'nodl_version', 'description', 'parameters', 'publishers', 'base', 'main', 'mixins', 'type',
    'default_value', 'validation', 'bounds<>', 'lt', 'one_of<>', 'not_empty<>', 'ns::f',
    'bad key', 'depth', 'qos', 'name', 'history', 'gain', '1bad', 'unique', 'x<>'])


def _paths(node: Any, prefix: tuple = ()) -> list[tuple]:
    found = [prefix]
    if isinstance(node, dict):
        for key, value in node.items():
            found += _paths(value, prefix + (key,))
    elif isinstance(node, list):
        for index, value in enumerate(node):
            found += _paths(value, prefix + (index,))
    return found


@st.composite
def mutants(draw: st.DrawFn) -> tuple[Kind, Any]:
    valid = [(kind, data) for name, kind, data in FIXTURE_DOCUMENTS if name.startswith('valid/')]
    kind, doc = draw(st.sampled_from(valid))
    doc = copy.deepcopy(doc)
    for _ in range(draw(st.integers(1, 3))):
        path = draw(st.sampled_from(_paths(doc)))
        target = doc
        for part in path[:-1]:
            target = target[part]
        action = draw(st.sampled_from(['replace', 'delete', 'add']))
        if action == 'replace' and path:
            target[path[-1]] = copy.deepcopy(draw(_VALUES))
        elif action == 'delete' and path and isinstance(target, dict):
            del target[path[-1]]
        else:
            node = target[path[-1]] if path else doc
            if isinstance(node, dict):
                node[draw(_KEYS)] = copy.deepcopy(draw(_VALUES))
            elif isinstance(node, list):
                node.append(copy.deepcopy(draw(_VALUES)))
    return kind, doc


@settings(max_examples=400, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(mutants())
def test_property_whatever_jsonschema_rejects_we_reject(mutant: tuple[Kind, Any]) -> None:
    kind, data = mutant
    theirs = [e.message for e in _validator(kind).iter_errors(data)]
    if theirs:
        assert [d for d in structure(data, kind) if d.severity is Severity.ERROR], theirs
    if not errors(data, kind):
        assert theirs == []
