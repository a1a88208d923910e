"""The ``nodl_schema`` compatibility package: the reference implementation's Python API on nodl.

The reference's own test suite (tests/fixtures/reference_api_suite, with only its
``ValidationError`` import changed) runs against it unchanged; the tests below cover what
the package adds or does differently: the toolkit's diagnostics, the schema, the models'
mapping, the index look-ups, and the former toolkit paths next to the reference's names.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import nodl
import nodl_schema
from conftest import REPO
from nodl_schema import ValidationError, dump_nodl, load_nodl, load_schema, parse_nodl, validate
from nodl_schema.composition import MergeError, merge_documents
from nodl_schema.models import from_toolkit, to_toolkit

SUITE = REPO / 'tests' / 'fixtures' / 'reference_api_suite'
#: The reference's __all__ (commit noted in the suite's README).
REFERENCE_ALL = [
    'AmentIndexResolver', 'ResolutionError', 'Resolver', 'dump_nodl', 'load_nodl',
    'load_nodl_with_doc_tree', 'load_schema', 'get_resolvers', 'parse_nodl', 'register_resolver',
    'resolve_document', 'resolver_registered', 'rewrite_references', 'unregister_resolver',
    'validate',
]


def _prefix(root: Path, entries: dict[tuple[str, str], str]) -> Path:
    """An ament prefix with the given index entries ((resource type, name) -> content)."""
    index = root / 'share' / 'ament_index' / 'resource_index'
    (index / 'packages').mkdir(parents=True, exist_ok=True)
    for (kind, name), content in entries.items():
        (index / kind).mkdir(parents=True, exist_ok=True)
        (index / kind / name).write_text(content)
    return root


def test_the_reference_suite_passes_with_only_its_validation_error_import_changed(
        tmp_path: Path) -> None:
    schema_tests = (SUITE / 'test_schema.py').read_text()
    assert 'from nodl_schema import ValidationError\n' in schema_tests
    assert 'jsonschema' not in ''.join(p.read_text() for p in SUITE.glob('test_*.py'))
    suite = shutil.copytree(SUITE, tmp_path / 'suite')
    (suite / 'pytest.ini').write_text('[pytest]\n')  # the suite alone, not this project's settings
    env = dict(os.environ, PYTHONPATH=str(REPO),
               AMENT_PREFIX_PATH=str(_prefix(tmp_path / 'prefix', {})))
    done = subprocess.run(
        [sys.executable, '-m', 'pytest', '-q', '-p', 'no:cacheprovider', '-W',
         'error::DeprecationWarning', '-p', 'no:randomly', '--deselect',
         'test_pyright.py::test_pyright', '.'],
        cwd=suite, env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    summary = done.stdout.strip().splitlines()[-1]
    counts = dict((kind, int(n)) for n, kind in re.findall(r'(\d+) (\w+)', summary))
    # every test but test_pyright (pyright's type check of the reference's own source tree)
    assert counts == {'passed': 152, 'deselected': 1}, summary


def test_all_is_the_references_and_validation_error() -> None:
    assert nodl_schema.__all__ == REFERENCE_ALL + ['ValidationError']
    with warnings.catch_warnings():
        warnings.simplefilter('error')  # none of these is a deprecated redirect
        for name in nodl_schema.__all__:
            assert getattr(nodl_schema, name) is not getattr(nodl, name, None), name


def test_a_reference_name_is_the_packages_own_not_nodls() -> None:
    from nodl_schema import loader

    assert nodl_schema.load_nodl is loader.load_nodl
    assert nodl_schema.dump_nodl is not nodl.dump_nodl


def test_a_former_toolkit_name_still_works_with_a_deprecation_warning() -> None:
    with pytest.warns(DeprecationWarning, match='nodl_schema.check_source moved to nodl.check_source'):
        assert nodl_schema.check_source is nodl.check_source


def test_validation_error_is_a_value_error_with_coded_diagnostics_at_file_line_col(
        tmp_path: Path) -> None:
    path = tmp_path / 'bad.nodl.yaml'
    path.write_text('nodl_version: 2\npublishers:\n  - name: /chatter\n    type: std_msgs/msg/Strin g\n'
                    '    qos: {history: KEEP_LAST, reliability: RELIABLE}\n')
    with pytest.raises(ValueError) as caught:
        load_nodl(path)
    error = caught.value
    assert isinstance(error, ValidationError) and isinstance(error, nodl.ValidationError)
    where = {(d.code, d.line, d.column) for d in error.errors}
    assert ('NODL203', 4, 11) in where  # the type name
    assert any(d.code == 'NODL102' and d.line == 5 for d in error.errors)  # KEEP_LAST needs depth
    assert str(error).startswith(f'{path}:')
    assert error.path == ('publishers', 0, 'type') and 'std_msgs/msg/Strin g' in error.message


def test_a_dict_is_validated_and_warnings_do_not_make_it_invalid() -> None:
    validate({'nodl_version': 2, 'parameters': {'p': {'type': 'int'}}})  # no description: a warning
    with pytest.raises(ValidationError) as caught:
        validate({'nodl_version': 2, 'parameters': {'p': {'type': 'int', 'default_value': 'x'}}})
    assert caught.value.errors[0].file == '<dict>'


def test_toolkit_node_syntax_is_refused_with_what_to_write_instead() -> None:
    with pytest.raises(ValidationError, match=r'include: \[\{ref: nodl://rclcpp_lifecycle'):
        validate({'nodl_version': 2, 'base': 'lifecycle_node'})
    with pytest.raises(ValidationError, match="'main' is a NoDL v2 node key"):
        validate({'nodl_version': 2, 'main': {'nodl_version': 2}})
    with pytest.raises(ValidationError, match=r"did you mean 'nodl://pkg/x'"):
        validate({'nodl_version': 2, 'include': [{'ref': 'nodl:pkg/x'}]})


def test_text_that_is_not_a_mapping_or_not_yaml_is_a_validation_error() -> None:
    with pytest.raises(ValidationError, match='mapping'):
        parse_nodl('- a list\n')
    with pytest.raises(ValidationError) as caught:
        parse_nodl('nodl_version: [2\n')
    assert caught.value.errors[0].line >= 1


def test_load_schema_is_self_contained_in_the_references_shape() -> None:
    schema = load_schema()
    assert schema is load_schema()
    assert schema['$schema'] == 'http://json-schema.org/draft-07/schema#'
    assert {'include', 'codegen', 'parameters', 'publishers', 'action_clients'} <= set(
        schema['properties'])
    assert 'main' not in schema['properties'] and schema['additionalProperties'] is False
    refs = re.findall(r'"\$ref": "([^"]*)"', json.dumps(schema))
    assert refs and all(ref.startswith('#/definitions/') for ref in refs)
    for ref in refs:
        assert ref.split('/')[-1] in schema['definitions'], ref


def test_dump_writes_validators_by_their_key_and_reads_back(tmp_path: Path) -> None:
    text = ('nodl_version: 2\nparameters:\n  rate:\n    type: double\n    description: Hz\n'
            '    validation:\n      bounds<>: [1.0, 100.0]\n')
    doc = parse_nodl(text)
    for form in ('yaml', 'json'):
        written = dump_nodl(doc, format=form)
        assert 'bounds<>' in written and 'bounds__' not in written
        assert parse_nodl(written) == doc
    with pytest.raises(ValueError, match='yaml or json'):
        dump_nodl(doc, format='toml')


def test_models_map_to_and_from_the_toolkits_model() -> None:
    doc = parse_nodl('nodl_version: 2\ndescription: d\nsubscriptions:\n  - name: /odom\n'
                     '    type: nav_msgs/msg/Odometry\n'
                     '    qos: {history: KEEP_LAST, depth: 5, reliability: BEST_EFFORT}\n')
    interface = to_toolkit(doc)
    assert isinstance(interface, nodl.Interface)
    assert interface.subscriptions[0].qos.depth == 5
    assert from_toolkit(interface) == doc
    with pytest.raises(ValueError, match='merge its includes first'):
        to_toolkit(parse_nodl('nodl_version: 2\ninclude: [{ref: nodl://a/b}]\n'))


def test_merging_refuses_a_name_declared_twice_and_says_by_whom() -> None:
    one = parse_nodl('nodl_version: 2\nservice_servers: [{name: /reset, type: std_srvs/srv/Empty}]\n')
    with pytest.raises(MergeError, match="service server '/reset' is declared twice: by the "
                                         'including document and by included document 1'):
        merge_documents([one, one])


def test_one_file_included_by_two_spellings_is_a_double_inclusion(tmp_path: Path) -> None:
    (tmp_path / 'sub').mkdir()
    (tmp_path / 'leaf.nodl.yaml').write_text('nodl_version: 2\n')
    (tmp_path / 'root.nodl.yaml').write_text(
        'nodl_version: 2\ninclude:\n  - ref: local://leaf.nodl.yaml\n'
        '  - ref: local://sub/../leaf.nodl.yaml\n')
    with pytest.raises(nodl_schema.ResolutionError, match='Double-inclusion'):
        load_nodl(tmp_path / 'root.nodl.yaml')


def test_nodl_refs_find_reference_and_toolkit_registrations(tmp_path: Path,
                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    share = tmp_path / 'prefix' / 'share' / 'tools' / 'nodl'
    share.mkdir(parents=True)
    (share / 'diag.nodl.yaml').write_text(
        'nodl_version: 2\npublishers:\n  - name: /diagnostics\n'
        '    type: diagnostic_msgs/msg/DiagnosticArray\n'
        '    qos: {history: KEEP_LAST, depth: 10, reliability: RELIABLE}\n')
    prefix = _prefix(tmp_path / 'prefix', {
        ('nodl', 'sensors__imu'): 'nodl_version: 2\nsubscriptions:\n  - name: /imu\n'
        '    type: sensor_msgs/msg/Imu\n    qos: {history: SYSTEM_DEFAULT, reliability: '
        'SYSTEM_DEFAULT}\n',
        ('nodl_interfaces', 'tools__diag'): 'nodl/diag.nodl.yaml',
    })
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    root = tmp_path / 'node.nodl.yaml'
    root.write_text('nodl_version: 2\ninclude:\n  - ref: nodl://sensors/imu\n'
                    '  - ref: nodl://tools/diag\n')
    doc = load_nodl(root)
    assert [s.name for s in doc.subscriptions or ()] == ['/imu']
    assert [p.name for p in doc.publishers or ()] == ['/diagnostics']
    with pytest.raises(nodl_schema.ResolutionError, match='nodl_interfaces/tools__absent'):
        nodl_schema.AmentIndexResolver().resolve('nodl://tools/absent')


def test_without_pydantic_the_package_imports_and_the_models_say_how_to_install() -> None:
    blocker = ('import sys\nclass Block:\n    def find_spec(self, name, path=None, target=None):\n'
               '        if name.split(".")[0] == "pydantic": raise ImportError(name)\n'
               'sys.meta_path.insert(0, Block())\n')
    done = subprocess.run(
        [sys.executable, '-c', blocker + 'import nodl_schema\nnodl_schema.validate({"nodl_version": 2})\n'
         'import nodl_schema.models'], cwd=REPO, capture_output=True, text=True, timeout=60)
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith('ImportError: nodl_schema.models needs pydantic: '
                           "pip install 'nodl-toolkit[reference]'"), done.stderr
