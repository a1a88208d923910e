"""The public load/validate/dump API: nodl.loading.

Includes the golden diagnostics of every invalid fixture: for
``tests/fixtures/invalid/NAME.nodl.yaml`` (or ``.nodl.json``) the expected
output is ``tests/fixtures/invalid/NAME.expected``, one diagnostic per line,
with the file named relative to the repository root.
"""

from __future__ import annotations

import io
import json
from pathlib import Path
from typing import Any

import pytest
import yaml

import nodl
from nodl import ValidationError
from nodl.diagnostics import Diagnostic, Severity
from nodl.loading import (
    CheckedSource,
    check_source,
    dump_nodl,
    load_interface,
    load_node,
    load_nodl,
    load_parameter,
    model_from_data,
    validate_interface,
    validate_node,
    validate_parameter,
)
from nodl.model import Base, Interface, Node, ParameterDefinition
from nodl.validation import Kind

FIXTURES = Path(__file__).parent / 'fixtures'
REPO = Path(__file__).resolve().parent.parent
INVALID = sorted(p for p in (FIXTURES / 'invalid').iterdir() if '.nodl.' in p.name)
VALID = sorted((FIXTURES / 'valid').iterdir())
MODELS = {Kind.PARAMETER: ParameterDefinition, Kind.INTERFACE: Interface, Kind.NODE: Node}


def expected_file(path: Path) -> Path:
    return path.with_name(path.name.split('.nodl.')[0] + '.expected')


# -- golden diagnostics of the invalid fixtures ------------------------------------

@pytest.mark.parametrize('path', INVALID, ids=lambda p: p.name)
def test_invalid_fixture_diagnostics(path: Path, golden: Any) -> None:
    relative = path.resolve().relative_to(REPO).as_posix()
    report = check_source(path, file=relative)
    assert report.diagnostics, f'{path.name} has nothing to report'
    for diagnostic in report.diagnostics:
        assert diagnostic.file == relative
        assert diagnostic.line > 0 and diagnostic.column > 0, str(diagnostic)
        assert '\n' not in diagnostic.message
    golden.check(''.join(f'{d}\n' for d in report.diagnostics), expected_file(path))


def test_every_expected_file_has_its_fixture() -> None:
    expected = sorted((FIXTURES / 'invalid').glob('*.expected'))
    assert sorted(expected_file(p) for p in INVALID) == expected
    assert len(INVALID) >= 30


def test_golden_output_is_deterministic() -> None:
    path = FIXTURES / 'invalid' / 'many_errors.nodl.yaml'
    runs = {''.join(f'{d}\n' for d in check_source(path, file='x').diagnostics)
            for _ in range(3)}
    assert len(runs) == 1


# -- valid fixtures ----------------------------------------------------------------

@pytest.mark.parametrize('path', VALID, ids=lambda p: p.name)
def test_valid_fixtures_have_nothing_to_report(path: Path) -> None:
    report = check_source(path)
    assert report.diagnostics == []
    assert report.kind is not None
    assert not report.has_errors(strict=True)
    model = load_nodl(path, strict=True)
    assert type(model) is MODELS[report.kind]


@pytest.mark.parametrize(('name', 'cls'), [
    ('parameter_max_speed.nodl.yaml', ParameterDefinition),
    ('parameter_mode.nodl.json', ParameterDefinition),
    ('interface_empty.nodl.yaml', Interface),
    ('interface_teleop.nodl.json', Interface),
    ('node_minimal.nodl.yaml', Node),
    ('node_camera_lifecycle.nodl.json', Node),
])
def test_load_nodl_detects_the_kind(name: str, cls: type) -> None:
    assert type(load_nodl(FIXTURES / 'valid' / name)) is cls


def test_loaded_content() -> None:
    node = load_node(FIXTURES / 'valid' / 'node_camera_lifecycle.nodl.json')
    assert node.base is Base.LIFECYCLE_NODE
    assert node.mixins[0] == '../shared/diagnostics.nodl.yaml'
    assert isinstance(node.mixins[1], Interface)
    assert node.main.parameters['fps'].default_value == 30
    assert node.main.parameters['fps'].validation == {'bounds<>': [1, 120]}
    assert node.main.publishers[0].qos.depth == 1
    param = load_parameter(FIXTURES / 'valid' / 'parameter_max_speed.nodl.yaml')
    assert param.type == 'double' and param.default_value == 0.5


# -- kind enforcement ------------------------------------------------------------------

PARAMETER_TEXT = 'type: int\ndescription: x\n'
INTERFACE_TEXT = 'nodl_version: 2\n'
NODE_TEXT = 'nodl_version: 2\nmain:\n  nodl_version: 2\n'


@pytest.mark.parametrize(('loader', 'text', 'cls'), [
    (load_parameter, PARAMETER_TEXT, ParameterDefinition),
    (load_interface, INTERFACE_TEXT, Interface),
    (load_node, NODE_TEXT, Node),
])
def test_loaders_accept_their_kind(loader: Any, text: str, cls: type) -> None:
    assert type(loader(text)) is cls


@pytest.mark.parametrize(('loader', 'text', 'message'), [
    (load_parameter, INTERFACE_TEXT,
     'expected a parameter definition, but this is an interface definition (it has nodl_version '
     'and no base, main or mixins)'),
    (load_parameter, NODE_TEXT,
     'expected a parameter definition, but this is a node definition (it has base, main or '
     'mixins)'),
    (load_interface, PARAMETER_TEXT,
     'expected an interface definition, but this is a parameter definition (it has no '
     'nodl_version)'),
    (load_interface, NODE_TEXT,
     'expected an interface definition, but this is a node definition (it has base, main or '
     'mixins)'),
    (load_node, PARAMETER_TEXT,
     'expected a node definition, but this is a parameter definition (it has no nodl_version)'),
    (load_node, INTERFACE_TEXT,
     'expected a node definition, but this is an interface definition (it has nodl_version and '
     'no base, main or mixins)'),
])
def test_loaders_refuse_other_kinds_clearly(loader: Any, text: str, message: str) -> None:
    with pytest.raises(ValidationError) as info:
        loader(text)
    assert [(d.severity, d.line, d.column, d.message) for d in info.value.diagnostics] == [
        (Severity.ERROR, 1, 1, message)]


def test_check_source_takes_a_kind_by_name_or_enum() -> None:
    assert check_source(NODE_TEXT, kind='node').kind is Kind.NODE
    assert check_source(NODE_TEXT, kind=Kind.NODE).errors == []
    assert check_source(NODE_TEXT, kind='interface').has_errors()
    with pytest.raises(ValueError):
        check_source(NODE_TEXT, kind='nodes')


# -- validate_* on plain dicts -----------------------------------------------------------

def test_validate_returns_the_warnings_of_a_valid_dict() -> None:
    assert validate_parameter({'type': 'int', 'description': 'x'}) == []
    found = validate_interface({'nodl_version': 2, 'parameters': {'gain': {'type': 'int'}}})
    assert [(d.severity, d.file, d.line, d.column, d.path_text, d.message) for d in found] == [
        (Severity.WARNING, '<dict>', 0, 0, 'parameters.gain',
         "parameter 'gain' has no description")]
    assert validate_node({'nodl_version': 2, 'main': {'nodl_version': 2}}) == []


BAD_NODE: dict[str, Any] = {
    'nodl_version': 2,
    'base': 'nod',
    'main': {
        'nodl_version': 2,
        'parameters': {'gain': {'type': 'int', 'default_value': 'high'}},
        'publishers': [{'name': 'a b', 'type': 'std_msgs/String',
                        'qos': {'history': 'KEEP_LAST', 'reliability': 'RELIABLE'}}],
    },
}


def test_validate_raises_once_with_every_diagnostic() -> None:
    with pytest.raises(ValidationError) as info:
        validate_node(BAD_NODE)
    error = info.value
    summary = sorted((d.severity.value, d.path_text) for d in error.diagnostics)
    assert summary == [
        ('error', 'base'),
        ('error', 'main.parameters.gain.default_value'),
        ('error', 'main.publishers[0].name'),
        ('error', 'main.publishers[0].qos'),
        ('warning', 'main.parameters.gain'),
        ('warning', 'main.publishers[0]'),
        ('warning', 'main.publishers[0].type'),
    ]
    assert all(d.file == '<dict>' and d.line == 0 and d.column == 0 for d in error.diagnostics)
    assert [d.severity for d in error.errors] == [Severity.ERROR] * 4
    # The message of the exception lists the errors, one per line.
    lines = str(error).splitlines()
    assert len(lines) == 4
    assert all(': error: ' in line for line in lines)
    assert isinstance(error, ValueError)


def test_validation_error_diagnostic_fields() -> None:
    with pytest.raises(ValidationError) as info:
        validate_node(BAD_NODE)
    default = next(d for d in info.value.diagnostics
                   if d.path == ('main', 'parameters', 'gain', 'default_value'))
    assert default.to_dict() == {
        'file': '<dict>', 'line': 0, 'column': 0, 'path': 'main.parameters.gain.default_value',
        'severity': 'error', 'code': 'NODL209', 'related': [],
        'message': "default_value of an int parameter must be an integer, not a string ('high')"}


@pytest.mark.parametrize(('validate', 'kind'), [
    (validate_parameter, 'parameter'), (validate_interface, 'interface'), (validate_node, 'node')])
@pytest.mark.parametrize('data', [[], 'type: int', None, 3])
def test_validate_refuses_what_is_not_a_mapping(validate: Any, kind: str, data: Any) -> None:
    with pytest.raises(ValidationError) as info:
        validate(data)
    expected_kind = {list: 'a list', str: 'a string', type(None): 'null', int: 'an integer'}[type(data)]
    assert [d.message for d in info.value.diagnostics] == [
        f"{'an' if kind == 'interface' else 'a'} {kind} definition is a mapping, not {expected_kind}"]


def test_validate_does_not_detect_the_kind() -> None:
    with pytest.raises(ValidationError) as info:
        validate_interface({'nodl_version': 2, 'main': {'nodl_version': 2}})
    assert "'main' belongs to a node definition" in str(info.value)


def test_model_from_data() -> None:
    assert isinstance(model_from_data({'type': 'int'}), ParameterDefinition)
    assert isinstance(model_from_data({'nodl_version': 2}), Interface)
    node = model_from_data({'nodl_version': 2, 'base': 'node', 'main': {'nodl_version': 2}})
    assert isinstance(node, Node) and node.base is Base.NODE
    with pytest.raises(ValidationError):
        model_from_data({'nodl_version': 2, 'main': {}})


# -- positions ---------------------------------------------------------------------------

YAML_TEXT = """\
# A comment first.
nodl_version: 2
main:
  nodl_version: 2
  parameters:
    gain: {type: int, default_value: 1.5, description: g}
    pid.kp:
      type: double
      default_value: x
  publishers:
    - type: std_msgs/msg/String
      description: no name
      qos: {history: KEEP_ALL, reliability: RELIABLE}
    -   name: 'bad name'
        type: std_msgs/msg/String
        description: x
        qos:
          history: KEEP_ALL
          reliability: RELIABLE
          extra: 1
  subscribers: []
"""


def _where(report: CheckedSource) -> list[tuple[int, int, str, str]]:
    return [(d.line, d.column, d.severity.value, d.path_text) for d in report.diagnostics]


def test_positions_in_yaml() -> None:
    report = check_source(YAML_TEXT, file='node.nodl.yaml')
    assert _where(report) == [
        (6, 38, 'error', 'main.parameters.gain.default_value'),        # the value 1.5
        (7, 5, 'warning', 'main.parameters["pid.kp"]'),                # the key pid.kp
        (9, 22, 'error', 'main.parameters["pid.kp"].default_value'),   # the value x
        (11, 7, 'error', 'main.publishers[0]'),                        # the item missing 'name'
        (14, 15, 'error', 'main.publishers[1].name'),                  # the quoted value
        (20, 11, 'error', 'main.publishers[1].qos.extra'),             # the unknown key
        (21, 3, 'error', 'main.subscribers'),                          # the unknown key
    ]
    assert all(d.file == 'node.nodl.yaml' for d in report.diagnostics)
    assert report.diagnostics[3].message == "missing required key 'name' in item 0 of 'publishers'"


JSON_TEXT = """\
{
  "nodl_version": 2,
  "main": {
    "nodl_version": 2,
    "parameters": {
      "gain": {"type": "int", "default_value": "high", "description": "Gain."}
    },
    "publishers": [
      {"name": "a b", "type": "std_msgs/msg/String", "description": "Bad name.",
       "qos": {"history": "KEEP_LAST", "reliability": "RELIABLE"}}
    ],
    "subscribers": []
  },
  "base": "Node"
}
"""


def test_positions_in_json() -> None:
    report = check_source(JSON_TEXT, file='node.nodl.json')
    assert _where(report) == [
        (6, 48, 'error', 'main.parameters.gain.default_value'),   # "high"
        (9, 16, 'error', 'main.publishers[0].name'),              # "a b"
        (10, 8, 'error', 'main.publishers[0].qos'),               # the key "qos" (KEEP_LAST)
        (12, 5, 'error', 'main.subscribers'),                     # the key "subscribers"
        (14, 11, 'error', 'base'),                                # "Node"
    ]


def test_missing_key_at_the_root_points_at_the_first_key() -> None:
    report = check_source('# header\n\ndescription: x\npublishers: []\n')
    assert [(d.line, d.column, d.message) for d in report.diagnostics] == [
        (3, 1, "missing required key 'nodl_version'")]


def test_positions_of_keys_and_values_differ() -> None:
    text = 'type: int\ndefault_value: 3\ndescription: x\nvalidation:\n  bonds<>: [0, 1]\n' \
           '  lt<>: nope\n'
    report = check_source(text)
    assert [(d.line, d.column, d.severity.value) for d in report.diagnostics] == [
        (5, 3, 'warning'),   # a key: the validator name
        (6, 9, 'error'),     # a value: the argument
    ]


def test_diagnostics_come_in_source_order() -> None:
    report = check_source(YAML_TEXT)
    places = [(d.line, d.column) for d in report.diagnostics]
    assert places == sorted(places)


# -- strict ---------------------------------------------------------------------------------

WARNING_ONLY = ('nodl_version: 2\npublishers:\n  - name: chatter\n    type: std_msgs/String\n'
                '    description: x\n    qos: {history: KEEP_ALL, reliability: RELIABLE}\n')


def test_strict_fails_on_warnings() -> None:
    iface = load_interface(WARNING_ONLY)
    assert iface.publishers[0].type == 'std_msgs/String'
    with pytest.raises(ValidationError) as info:
        load_interface(WARNING_ONLY, strict=True)
    assert [(d.severity, d.line, d.column) for d in info.value.diagnostics] == [
        (Severity.WARNING, 4, 11)]
    assert info.value.errors == []
    assert 'omits the interface namespace' in str(info.value)
    with pytest.raises(ValidationError):
        load_nodl(WARNING_ONLY, strict=True)


def test_report_strictness() -> None:
    report = check_source(WARNING_ONLY)
    assert not report.has_errors()
    assert report.has_errors(strict=True)
    assert report.errors == [] and len(report.warnings) == 1
    assert isinstance(report.model(), Interface)


def test_report_of_an_invalid_document_has_no_model() -> None:
    report = check_source(YAML_TEXT)
    assert report.has_errors()
    with pytest.raises(ValidationError) as info:
        report.model()
    assert info.value.diagnostics == report.diagnostics


def test_load_raises_with_every_diagnostic_placed() -> None:
    with pytest.raises(ValidationError) as info:
        load_nodl(YAML_TEXT)
    assert len(info.value.diagnostics) == 7
    assert len(info.value.errors) == 6
    assert all(d.file == '<string>' and d.line > 0 for d in info.value.diagnostics)


# -- accepted inputs ----------------------------------------------------------------------

def _names(report: CheckedSource) -> set[str]:
    return {d.file for d in report.diagnostics}


def test_input_str() -> None:
    assert isinstance(load_nodl(NODE_TEXT), Node)
    assert _names(check_source(WARNING_ONLY)) == {'<string>'}


@pytest.mark.parametrize('convert', [bytes, bytearray, memoryview])
def test_input_bytes(convert: Any) -> None:
    assert isinstance(load_nodl(convert(NODE_TEXT.encode())), Node)
    assert _names(check_source(convert(WARNING_ONLY.encode()))) == {'<bytes>'}


def test_input_bytes_with_a_bom() -> None:
    assert isinstance(load_nodl(b'\xef\xbb\xbf' + NODE_TEXT.encode()), Node)


def test_input_text_and_binary_streams() -> None:
    assert isinstance(load_nodl(io.StringIO(NODE_TEXT)), Node)
    assert isinstance(load_nodl(io.BytesIO(NODE_TEXT.encode())), Node)
    assert _names(check_source(io.StringIO(WARNING_ONLY))) == {'<stream>'}


def test_input_open_files(tmp_path: Path) -> None:
    path = tmp_path / 'iface.nodl.yaml'
    path.write_text(WARNING_ONLY, encoding='utf-8')
    with open(path, encoding='utf-8') as f:
        assert _names(check_source(f)) == {str(path)}
    with open(path, 'rb') as f:
        assert isinstance(load_interface(f), Interface)


def test_input_path(tmp_path: Path) -> None:
    path = tmp_path / 'iface.nodl.yaml'
    path.write_text(WARNING_ONLY, encoding='utf-8')
    assert isinstance(load_nodl(path), Interface)
    report = check_source(path)
    assert _names(report) == {str(path)}
    assert _names(check_source(path, file='shown.yaml')) == {'shown.yaml'}
    assert isinstance(load_nodl(FIXTURES / 'valid' / 'interface_teleop.nodl.json'), Interface)


def test_a_str_is_text_not_a_file_name(tmp_path: Path) -> None:
    path = tmp_path / 'node.nodl.yaml'
    path.write_text(NODE_TEXT, encoding='utf-8')
    with pytest.raises(ValidationError):
        load_nodl(str(path))  # a YAML scalar, not a mapping


def test_missing_file_raises_os_error(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        load_nodl(tmp_path / 'missing.nodl.yaml')


def test_unsupported_source_type() -> None:
    with pytest.raises(TypeError, match='cannot read a NoDL document from int'):
        load_nodl(42)  # type: ignore[arg-type]


def test_undecodable_bytes_give_a_report_without_a_kind() -> None:
    report = check_source(b'nodl_version: 2\ndescription: caf\xe9\n', file='bad.nodl.yaml')
    assert report.kind is None and report.data is None
    assert [(d.file, d.line, d.column, d.severity) for d in report.diagnostics] == [
        ('bad.nodl.yaml', 2, 17, Severity.ERROR)]
    assert 'not valid UTF-8' in report.diagnostics[0].message
    with pytest.raises(ValidationError):
        report.model()


def test_parse_problems_are_validation_errors() -> None:
    with pytest.raises(ValidationError) as info:
        load_nodl('nodl_version: 2\nnodl_version: 2\n')
    assert [(d.line, d.column) for d in info.value.diagnostics] == [(2, 1)]
    assert 'duplicate key' in info.value.diagnostics[0].message
    with pytest.raises(ValidationError, match='document is empty'):
        load_nodl('')


# -- dumping ---------------------------------------------------------------------------

def test_dump_json() -> None:
    node = load_node(FIXTURES / 'valid' / 'node_laser_driver.nodl.yaml')
    text = dump_nodl(node, format='json')
    assert text.endswith('}\n')
    assert json.loads(text) == node.to_dict()
    assert load_node(text) == node


def test_dump_yaml_is_the_default() -> None:
    iface = load_interface(FIXTURES / 'valid' / 'interface_teleop.nodl.json')
    text = dump_nodl(iface)
    assert text == dump_nodl(iface, format='yaml')
    assert not text.lstrip().startswith('{')
    assert yaml.safe_load(text) == iface.to_dict()
    assert text.splitlines()[0] == 'nodl_version: 2'   # file order, not sorted
    assert load_interface(text) == iface


def test_dump_keeps_strings_that_look_like_other_things() -> None:
    param = ParameterDefinition('string', 'off', 'd', validation={'one_of<>': [['on', 'off', '~',
                                                                               'null', '1.0']]})
    for fmt in ('yaml', 'json'):
        assert load_parameter(dump_nodl(param, format=fmt)) == param


def test_dump_a_plain_dict() -> None:
    data = {'type': 'int', 'default_value': 3}
    assert json.loads(dump_nodl(data, format='json')) == data
    assert yaml.safe_load(dump_nodl(data)) == data


@pytest.mark.parametrize('fmt', ['toml', 'YAML', 'yml', ''])
def test_dump_unknown_format(fmt: str) -> None:
    with pytest.raises(ValueError, match="expected 'yaml' or 'json'"):
        dump_nodl(ParameterDefinition('int'), format=fmt)


# -- the package namespace ----------------------------------------------------------------

def test_public_names() -> None:
    assert nodl.load_nodl is load_nodl
    assert nodl.ValidationError is ValidationError
    assert nodl.Diagnostic is Diagnostic
    assert nodl.Kind is Kind
    for name in nodl.__all__:
        assert getattr(nodl, name) is not None
    with pytest.raises(AttributeError):
        nodl.no_such_name  # noqa: B018


def test_dump_refuses_an_invalid_document() -> None:
    with pytest.raises(ValidationError) as caught:
        dump_nodl(ParameterDefinition('int', default_value='three'))
    assert 'must be an integer' in str(caught.value)
    assert dump_nodl({'type': 'int', 'default_value': 'x'}, validate=False)


def test_a_path_given_as_str_says_to_pass_a_path() -> None:
    with pytest.raises(ValidationError) as caught:
        load_nodl('examples/laser_driver.nodl.yaml')
    [error] = caught.value.diagnostics
    assert "pathlib.Path('examples/laser_driver.nodl.yaml')" in error.message


# -- the reference implementation's schema suite -------------------------------------------

REFERENCE_SUITE = FIXTURES / 'reference_schema_suite'
#: Documents the reference's schema accepts and the toolkit rejects, and why (see the README
#: of the fixture folder).  Nothing the reference rejects is accepted here.
STRICTER = {
    'include_scheme_specific_shape_is_not_the_schemas_business__0.yaml':
        "nodl://pkg names no document: NODL217 at the reference (the reference's resolver "
        'fails later, when it looks the document up)',
    'include_scheme_specific_shape_is_not_the_schemas_business__1.yaml':
        'nodl://pkg/nested/name: a registered name holds no /, NODL217 at the reference',
}


def _suite(verdict: str) -> list[Path]:
    return sorted((REFERENCE_SUITE / verdict).glob('*.yaml'))


def test_the_reference_suite_is_all_here() -> None:
    # 34 documents its tests expect to be valid, 34 invalid (commit 915a4da).
    assert (len(_suite('valid')), len(_suite('invalid'))) == (34, 34)
    assert set(STRICTER) <= {p.name for p in _suite('valid')}


@pytest.mark.parametrize('path', _suite('valid'), ids=lambda p: p.stem)
def test_documents_the_reference_accepts(path: Path) -> None:
    report = check_source(path)
    if path.name in STRICTER:
        assert [d.code for d in report.errors] == ['NODL217'], report.diagnostics
        assert report.errors[0].path_text == 'include[0].ref'
    else:
        assert not report.errors, report.errors


@pytest.mark.parametrize('path', _suite('invalid'), ids=lambda p: p.stem)
def test_documents_the_reference_rejects(path: Path) -> None:
    report = check_source(path)
    assert report.errors, f'{path.name} is accepted; the reference rejects it'
    for error in report.errors:  # each at a place in the file, none a traceback
        assert error.line >= 1 and error.code


@pytest.mark.parametrize(('name', 'code', 'where'), [
    ('codegen_non_object_rejected', 'NODL103', 'codegen'),
    ('codegen_non_object_value_rejected', 'NODL103', 'codegen.cpp'),
    ('include_non_uri_ref_rejected__1', 'NODL818', 'include[0].ref'),  # a bare path
    ('include_non_uri_ref_rejected__2', 'NODL818', 'include[0].ref'),  # ./path
    ('include_non_uri_ref_rejected__5', 'NODL818', 'include[0].ref'),  # ://pkg/name
    ('include_non_uri_ref_rejected__6', 'NODL818', 'include[0].ref'),  # nodl:/pkg/name
    ('include_non_uri_ref_rejected__7', 'NODL818', 'include[0].ref'),  # has space://
])
def test_the_reference_rejects_for_the_same_reason(name: str, code: str, where: str) -> None:
    [error] = check_source(REFERENCE_SUITE / 'invalid' / f'{name}.yaml').errors
    assert (error.code, error.path_text) == (code, where)


@pytest.mark.parametrize('text', ['line\u2028separator', 'para\u2029graph', '\u2028', 'a \u2028 b\u2029',
                                  'x' * 95 + ' \u2028 ' + 'y' * 30, 'nel\x85x', 'rlo\u202ex é'])
def test_line_separators_and_unsafe_characters_survive_a_dump_and_load(text: str) -> None:
    from nodl.text_safety import first_unsafe

    for format in ('yaml', 'json'):
        dumped = dump_nodl({'type': 'string', 'description': text}, format, validate=False)
        assert first_unsafe(dumped) == -1 and '\u2028' not in dumped and '\u2029' not in dumped
        assert check_source(dumped, file=f'x.{format}').data['description'] == text


def test_the_former_name_report_still_works_with_a_deprecation_warning() -> None:
    import nodl

    with pytest.warns(DeprecationWarning, match='nodl.Report is now nodl.CheckedSource'):
        assert nodl.Report is CheckedSource
