"""Composition (nodl.composition.compose): layers, origins, overrides and mixin errors."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl import ValidationError
from nodl.composition import (
    ComposedNode,
    ResolutionError,
    ResolveContext,
    Resolved,
    compose,
    compose_report,
)
from nodl.composition.path_resolver import PathResolver
from nodl.diagnostics import Diagnostic, Severity
from nodl.loading import check_source

COMPOSITION = FIXTURES / 'composition'
LAYERS = COMPOSITION / 'layers' / 'nodl'
ERRORS = COMPOSITION / 'errors' / 'pkg'
PREFIX = COMPOSITION / 'prefix'

NODE_BASE_PARAMETERS = {'use_sim_time', 'start_type_description_service'}


@pytest.fixture
def fixture_prefix(monkeypatch: pytest.MonkeyPatch) -> Path:
    """AMENT_PREFIX_PATH = the fixture prefix (and nothing else)."""
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(PREFIX))
    return PREFIX


def layered() -> ComposedNode:
    return compose(LAYERS / 'node.nodl.yaml')


def errors_of(exc: pytest.ExceptionInfo[ValidationError]) -> list[Diagnostic]:
    return [d for d in exc.value.diagnostics if d.severity is Severity.ERROR]


def where(d: Diagnostic) -> str:
    return f'{os.path.basename(d.file)}:{d.line}:{d.column}'


# --- layers, order and origins ---------------------------------------------------------------

def test_layers_are_base_then_mixins_in_order_then_main() -> None:
    composed = layered()
    assert [layer.label for layer in composed.layers] == [
        'base:node', 'first.nodl.yaml', 'mixins[1]', 'file://second.nodl.yaml', 'main']
    assert [layer.role for layer in composed.layers] == ['base', 'mixin', 'mixin', 'mixin', 'main']
    assert composed.layer('mixins[1]').interface.description == 'An in-place mixin.'
    with pytest.raises(KeyError):
        composed.layer('no such layer')


def test_later_layer_wins_and_origin_is_the_winning_layer() -> None:
    iface = layered().interface
    params = iface.parameters
    assert params is not None
    # rate: first (1.0) -> second (2.0) -> main (3.0)
    assert (params['rate'].default_value, params['rate'].origin) == (3.0, 'main')
    # main overrides the base
    assert (params['use_sim_time'].default_value, params['use_sim_time'].origin) == (True, 'main')
    assert params['start_type_description_service'].origin == 'base:node'
    assert params['only_first'].origin == 'first.nodl.yaml'
    assert params['in_place'].origin == 'mixins[1]'
    status = next(p for p in iface.publishers if p.name == '~/status')
    assert (status.qos.depth, status.origin) == (2, 'file://second.nodl.yaml')
    assert status.description == 'Status from the second mixin.'
    reset = next(s for s in iface.service_servers if s.name == '~/reset')
    assert (reset.type, reset.origin) == ('std_srvs/srv/Empty', 'mixins[1]')
    out = next(p for p in iface.publishers if p.name == '~/out')
    assert out.origin == 'main'
    assert next(p for p in iface.publishers if p.name == '/rosout').origin == 'base:node'
    # the merged description is main's
    assert iface.description == 'A node made of layers.'


def test_every_entity_has_exactly_one_entry_and_an_origin() -> None:
    composed = layered()
    iface = composed.interface
    labels = {layer.label for layer in composed.layers}
    for param in iface.parameters.values():
        assert param.origin in labels
    for section in ('publishers', 'subscriptions', 'service_servers', 'service_clients',
                    'action_servers', 'action_clients'):
        names = [e.name for e in getattr(iface, section) or ()]
        assert len(names) == len(set(names)), section
        for entity in getattr(iface, section) or ():
            assert entity.origin in labels


def test_composition_does_not_stamp_the_layers_themselves() -> None:
    composed = layered()
    first = composed.layer('first.nodl.yaml').interface
    assert first.parameters['rate'].origin is None
    assert first.parameters['rate'].default_value == 1.0


def test_override_is_an_info_diagnostic_naming_both_layers_at_the_winning_entity() -> None:
    composed = layered()
    infos = [d for d in composed.diagnostics if d.severity is Severity.INFO]
    notes = [d for d in composed.diagnostics if d.code in ('NODL304', 'NODL310')]
    rendered = {f'{where(d)} {d.message}' for d in notes}
    assert rendered == {
        "node.nodl.yaml:13:9 service server '~/reset' from mixins[1] changes the type of the one "
        'from first.nodl.yaml (std_srvs/srv/Trigger -> std_srvs/srv/Empty); the code behind '
        'first.nodl.yaml and this node disagree',
        "second.nodl.yaml:4:3 parameter 'rate' from file://second.nodl.yaml overrides the one "
        'from first.nodl.yaml',
        "second.nodl.yaml:9:5 publisher '~/status' from file://second.nodl.yaml overrides the one "
        'from first.nodl.yaml',
        "node.nodl.yaml:21:5 parameter 'use_sim_time' from main overrides the one from base:node",
        "node.nodl.yaml:25:5 parameter 'rate' from main overrides the one from "
        'file://second.nodl.yaml',
    }
    # diagnostics in a referenced file name that file, with its full path
    second = next(d for d in infos if 'second.nodl.yaml:4' in f'{d.file}:{d.line}')
    assert Path(second.file) == (LAYERS / 'second.nodl.yaml').resolve()
    assert not [d for d in composed.diagnostics if d.severity is Severity.ERROR]


def test_declarations_trace_every_layer_that_declares_an_entity() -> None:
    composed = layered()
    # what a generator implements is decided from these (see nodl.system): the base's
    # entities come from the client library, a mixin's from other code, main's own from main
    assert [d.layer.label for d in composed.declarations[('parameters', 'rate')]] == [
        'first.nodl.yaml', 'file://second.nodl.yaml', 'main']
    assert [d.layer.role for d in composed.declarations[('parameters', 'use_sim_time')]] == [
        'base', 'main']
    assert [d.layer.label for d in composed.declarations[('publishers', '~/out')]] == ['main']
    assert composed.declarations[('service_servers', '~/reset')][-1].path == ('service_servers', 0)
    assert not hasattr(composed, 'forward')  # replaced by the providers of the resolved node


def test_a_mixin_file_called_main_is_still_a_mixin() -> None:
    composed = compose(LAYERS / 'mixin_called_main.nodl.yaml')
    assert [(layer.label, layer.role) for layer in composed.layers] == [
        ('base:node', 'base'), ('main', 'mixin'), ('main', 'main')]
    assert composed.interface.parameters['from_file_called_main'].origin == 'main'
    roles = {name: composed.declarations[('parameters', name)][0].layer.role
             for name in ('from_file_called_main', 'own')}
    assert roles == {'from_file_called_main': 'mixin', 'own': 'main'}
    # layer('main') is the node's main, not the mixin that shares its label
    assert composed.layer('main').role == 'main'


def test_lifecycle_base_layer() -> None:
    composed = compose('nodl_version: 2\nbase: lifecycle_node\nmain: {nodl_version: 2}\n')
    assert [layer.label for layer in composed.layers] == ['base:lifecycle_node', 'main']
    names = {s.name for s in composed.interface.service_servers}
    assert '~/change_state' in names
    assert all(s.origin == 'base:lifecycle_node' for s in composed.interface.service_servers)


def test_node_without_base_has_only_mixins_and_main() -> None:
    composed = compose('nodl_version: 2\nmixins:\n  - nodl_version: 2\n'
                       '    parameters: {a: {type: int, default_value: 1, description: A.}}\n'
                       'main: {nodl_version: 2}\n')
    assert [layer.label for layer in composed.layers] == ['mixins[0]', 'main']
    assert composed.interface.parameters['a'].origin == 'mixins[0]'
    assert composed.declarations[('parameters', 'a')][0].layer.role == 'mixin'


def test_compose_report_of_a_non_node_is_an_error() -> None:
    report = check_source(REPO / 'examples' / 'diagnostics.nodl.yaml')
    composed, diagnostics = compose_report(report)
    assert composed is None
    assert [d.severity for d in diagnostics] == [Severity.ERROR]
    assert 'only a node definition can be composed' in diagnostics[0].message
    assert (diagnostics[0].line, diagnostics[0].column) == (1, 1)


def test_an_invalid_node_is_not_composed_and_keeps_its_own_diagnostics() -> None:
    with pytest.raises(ValidationError) as exc:
        compose('nodl_version: 2\nbase: nod\nmain: {nodl_version: 2}\n')
    assert [(d.line, d.column) for d in errors_of(exc)] == [(2, 7)]


# --- mixin errors: at the mixin entry, all at once -----------------------------------------

def test_every_mixin_error_is_reported_at_its_entry_all_together(fixture_prefix: Path) -> None:
    with pytest.raises(ValidationError) as exc:
        compose(ERRORS / 'all_errors.nodl.yaml')
    in_node = [d for d in errors_of(exc) if d.file.endswith('all_errors.nodl.yaml')]
    # one error per mixin entry, at the list item (line 4 + i, column 5), in order
    assert [(d.line, d.column, d.path) for d in in_node] == [
        (4 + i, 5, ('mixins', i)) for i in range(10)]
    messages = [d.message for d in in_node]

    missing = str((ERRORS / 'missing.nodl.yaml').resolve())
    assert messages[0].startswith("cannot resolve mixin 'missing.nodl.yaml': ")
    assert f'(searched: {missing})' in messages[0]

    assert "'../outside.nodl.yaml' leaves the package directory" in messages[1]
    assert str(ERRORS.resolve()) in messages[1]
    assert 'nodl://<package>/<name>' in messages[1]

    assert 'is a node definition, not an interface definition' in messages[2]
    assert 'single-level' in messages[2]

    assert 'is a parameter definition, not an interface definition' in messages[3]

    assert "mixin 'nodl/invalid.nodl.yaml'" in messages[4]
    assert 'is not a valid interface definition: 2 error(s)' in messages[4]

    assert "no resolver for the scheme 'foo'" in messages[5]
    assert 'nodl://' in messages[5]

    assert "package 'no_such_pkg' is not in the ament index" in messages[6]
    assert str(PREFIX) in messages[6]

    assert "package 'fixture_pkg' registers no interface definition 'no_such_name'" in messages[7]
    assert 'it registers: dangling, inline, inline_invalid, inline_json, relative' in messages[7]

    assert 'fixture_pkg__dangling points at' in messages[8]
    assert 'gone.nodl.yaml, which does not exist' in messages[8]

    assert "package 'empty_pkg' registers no interface definitions" in messages[9]


def test_an_invalid_mixin_file_is_followed_by_its_own_placed_diagnostics(
        fixture_prefix: Path) -> None:
    with pytest.raises(ValidationError) as exc:
        compose(ERRORS / 'all_errors.nodl.yaml')
    diagnostics = exc.value.diagnostics
    index = next(i for i, d in enumerate(diagnostics) if "mixin 'nodl/invalid.nodl.yaml'" in d.message)
    own = diagnostics[index + 1:index + 3]
    assert [(os.path.basename(d.file), d.line, d.column, d.path_text) for d in own] == [
        ('invalid.nodl.yaml', 3, 5, 'publishers[0]'),
        ('invalid.nodl.yaml', 8, 11, 'service_servers[0].type'),
    ]
    assert "missing required key 'qos'" in own[0].message
    assert 'service type' in own[1].message
    # and the next error is about the next mixin entry again
    assert diagnostics[index + 3].file.endswith('all_errors.nodl.yaml')


def test_the_error_text_is_compiler_style(fixture_prefix: Path) -> None:
    with pytest.raises(ValidationError) as exc:
        compose(ERRORS / 'all_errors.nodl.yaml')
    text = str(exc.value).splitlines()
    assert text[0].startswith(f'{ERRORS / "all_errors.nodl.yaml"}:4:5: error: cannot resolve mixin')
    assert text[0].endswith('[mixins[0]] [NODL301]')


def test_a_registered_document_that_is_invalid_is_placed_in_the_index_entry(
        fixture_prefix: Path) -> None:
    with pytest.raises(ValidationError) as exc:
        compose(COMPOSITION / 'uses_invalid_entry.nodl.yaml')
    errors = errors_of(exc)
    assert [where(d) for d in errors] == ['uses_invalid_entry.nodl.yaml:4:5',
                                          'fixture_pkg__inline_invalid:3:5']
    entry = PREFIX / 'share/ament_index/resource_index/nodl_interfaces/fixture_pkg__inline_invalid'
    assert errors[1].file == str(entry)


def test_empty_ament_prefix_path_says_to_source_the_workspace(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', '')
    with pytest.raises(ValidationError) as exc:
        compose(COMPOSITION / 'uses_index.nodl.yaml')
    errors = errors_of(exc)
    assert len(errors) == 3  # one per nodl:// mixin, all reported
    assert all('AMENT_PREFIX_PATH is empty' in d.message for d in errors)
    assert [(d.line, d.column) for d in errors] == [(4, 5), (5, 5), (6, 5)]


# --- nodl:// through the ament index ------------------------------------------------------

def test_nodl_references_resolve_relative_inline_and_one_line_entries(
        fixture_prefix: Path) -> None:
    composed = compose(COMPOSITION / 'uses_index.nodl.yaml')
    iface = composed.interface
    assert [layer.label for layer in composed.layers] == [
        'base:node', 'nodl://fixture_pkg/relative', 'nodl://fixture_pkg/inline',
        'nodl://fixture_pkg/inline_json', 'main']
    assert [(a.name, a.origin) for a in iface.action_servers] == [
        ('~/relative_action', 'nodl://fixture_pkg/relative')]
    assert iface.parameters['inline.gain'].origin == 'nodl://fixture_pkg/inline'
    assert [(s.name, s.origin) for s in iface.subscriptions] == [
        ('~/inline_in', 'nodl://fixture_pkg/inline')]
    assert [(c.name, c.origin) for c in iface.service_clients] == [
        ('~/json_client', 'nodl://fixture_pkg/inline_json')]


def test_nodl_references_resolve_in_the_prefixes_given_not_ament_prefix_path(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(FIXTURES / 'analysis' / 'prefix'))  # no fixture_pkg
    composed = compose(COMPOSITION / 'uses_index.nodl.yaml', prefixes=[str(PREFIX)])
    assert [layer.label for layer in composed.layers][1:-1] == [
        'nodl://fixture_pkg/relative', 'nodl://fixture_pkg/inline', 'nodl://fixture_pkg/inline_json']
    # the default stays AMENT_PREFIX_PATH, which does not hold the package
    with pytest.raises(ValidationError) as exc:
        compose(COMPOSITION / 'uses_index.nodl.yaml')
    assert all("package 'fixture_pkg' is not in the ament index (AMENT_PREFIX_PATH: " in d.message
               for d in errors_of(exc))
    # prefixes given: the message names them, not the variable
    with pytest.raises(ValidationError) as exc:
        compose(COMPOSITION / 'uses_index.nodl.yaml', prefixes=[str(FIXTURES / 'analysis' / 'prefix')])
    assert all('(prefixes searched: ' in d.message for d in errors_of(exc))
    with pytest.raises(ValidationError) as exc:
        compose(COMPOSITION / 'uses_index.nodl.yaml', prefixes=[])
    assert all('no ament prefix was given' in d.message for d in errors_of(exc))


def test_an_absolute_path_in_the_index_entry_is_read(tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = tmp_path / 'prefix'
    index = prefix / 'share' / 'ament_index' / 'resource_index'
    (index / 'packages').mkdir(parents=True)
    (index / 'packages' / 'abs_pkg').write_text('')
    (index / 'nodl_interfaces').mkdir()
    source = tmp_path / 'elsewhere' / 'iface.nodl.yaml'
    source.parent.mkdir()
    source.write_text('nodl_version: 2\nparameters:\n'
                      '  abs: {type: int, default_value: 3, description: From an absolute path.}\n')
    (index / 'nodl_interfaces' / 'abs_pkg__iface').write_text(str(source))
    node = tmp_path / 'node.nodl.yaml'
    node.write_text('nodl_version: 2\nmixins: [nodl://abs_pkg/iface]\nmain: {nodl_version: 2}\n')
    monkeypatch.setenv('AMENT_PREFIX_PATH', f'{tmp_path / "empty"}{os.pathsep}{prefix}')
    composed = compose(node)
    assert composed.interface.parameters['abs'].default_value == 3
    assert composed.interface.parameters['abs'].origin == 'nodl://abs_pkg/iface'

    source.unlink()  # the entry now points nowhere
    with pytest.raises(ValidationError) as exc:
        compose(node)
    [error] = errors_of(exc)
    assert (error.line, error.column) == (2, 10)
    assert f'points at {source}, which does not exist' in error.message


def test_a_registered_node_definition_is_not_a_mixin(tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    # a registered interface may not itself be a node (mixins are single-level)
    prefix = tmp_path / 'prefix'
    index = prefix / 'share' / 'ament_index' / 'resource_index' / 'nodl_interfaces'
    index.mkdir(parents=True)
    (index / 'p__n').write_text('nodl_version: 2\nbase: node\nmain: {nodl_version: 2}\n')
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    with pytest.raises(ValidationError) as exc:
        compose('nodl_version: 2\nmixins: [nodl://p/n]\nmain: {nodl_version: 2}\n')
    [error] = errors_of(exc)
    assert 'is a node definition' in error.message and 'single-level' in error.message


# --- sources without a file, and resolver plugins ----------------------------------------

def test_a_string_source_with_a_relative_mixin_is_a_clear_error() -> None:
    with pytest.raises(ValidationError) as exc:
        compose('nodl_version: 2\nbase: node\nmixins:\n  - diagnostics.nodl.yaml\n'
                'main: {nodl_version: 2}\n')
    [error] = errors_of(exc)
    assert (error.file, error.line, error.column) == ('<string>', 4, 5)
    assert 'needs the location of the node file' in error.message
    assert 'load the node definition from a file' in error.message


def test_a_string_source_named_after_a_real_file_resolves_next_to_it() -> None:
    text = (LAYERS / 'node.nodl.yaml').read_text()
    composed = compose(text, file=str(LAYERS / 'node.nodl.yaml'))
    assert composed.interface.parameters['rate'].origin == 'main'


def test_file_scheme_with_an_absolute_path_is_refused(tmp_path: Path) -> None:
    (tmp_path / 'iface.nodl.yaml').write_text('nodl_version: 2\n')
    node = tmp_path / 'node.nodl.yaml'
    node.write_text(f'nodl_version: 2\nmixins:\n  - file://{tmp_path}/iface.nodl.yaml\n'
                    'main: {nodl_version: 2}\n')
    with pytest.raises(ValidationError) as exc:
        compose(node)
    [error] = errors_of(exc)
    assert (error.line, error.column) == (3, 5)
    assert 'is an absolute path' in error.message


def test_without_a_package_xml_the_node_folder_is_the_boundary(tmp_path: Path) -> None:
    tree = tmp_path / 'tree'
    shutil.copytree(ERRORS, tree / 'pkg')
    (tree / 'pkg' / 'package.xml').unlink()
    (tree / 'pkg' / 'nodl' / 'up.nodl.yaml').write_text(
        'nodl_version: 2\nmixins: [../a_parameter.nodl.yaml]\nmain: {nodl_version: 2}\n')
    with pytest.raises(ValidationError) as exc:
        compose(tree / 'pkg' / 'nodl' / 'up.nodl.yaml')
    [error] = errors_of(exc)
    assert f'leaves the package directory {tree / "pkg" / "nodl"}' in error.message


def test_path_resolver_reads_relative_to_the_node_file() -> None:
    node = LAYERS / 'node.nodl.yaml'
    resolved = PathResolver().resolve('file://first.nodl.yaml',
                                      ResolveContext(str(node), str(LAYERS.parent)))
    assert resolved.file == str((LAYERS / 'first.nodl.yaml').resolve())
    assert resolved.text == (LAYERS / 'first.nodl.yaml').read_bytes()  # raw: the loader decodes it


def test_a_mixin_file_gets_the_same_encoding_check_as_any_document(tmp_path: Path) -> None:
    (tmp_path / 'package.xml').write_text('<package/>')
    (tmp_path / 'latin1.nodl.yaml').write_bytes('nodl_version: 2\ndescription: caf\xe9\n'.encode('latin-1'))
    node = tmp_path / 'node.nodl.yaml'
    node.write_text('nodl_version: 2\nmixins: [latin1.nodl.yaml]\nmain: {nodl_version: 2}\n')
    with pytest.raises(ValidationError) as caught:
        compose(node)
    messages = [str(d) for d in caught.value.diagnostics]
    assert any(m.startswith(f'{node}:2:10: error: mixin ') for m in messages), messages
    assert any(':2:17: error: document is not valid UTF-8' in m for m in messages), messages


def test_a_symbolic_link_may_not_lead_out_of_the_package(tmp_path: Path) -> None:
    package = tmp_path / 'pkg'
    package.mkdir()
    (package / 'package.xml').write_text('<package/>')
    (tmp_path / 'outside.nodl.yaml').write_text('nodl_version: 2\n')
    (package / 'inside.nodl.yaml').symlink_to(tmp_path / 'outside.nodl.yaml')
    node = package / 'node.nodl.yaml'
    node.write_text('nodl_version: 2\nmixins: [inside.nodl.yaml]\nmain: {nodl_version: 2}\n')
    with pytest.raises(ValidationError, match='leaves the package directory'):
        compose(node)


class _Exploding:
    def resolve(self, reference: str, context: ResolveContext) -> Resolved:
        raise RuntimeError('plugin bug')


class _Memory:
    def __init__(self) -> None:
        self.seen: list[tuple[str, ResolveContext]] = []

    def resolve(self, reference: str, context: ResolveContext) -> Resolved:
        self.seen.append((reference, context))
        if reference == 'mem://missing':
            raise ResolutionError('not in memory', ['memory slot 1', 'memory slot 2'])
        return Resolved('nodl_version: 2\nparameters:\n'
                        '  mem: {type: int, default_value: 5, description: From memory.}\n',
                        '<memory>')


def test_a_resolver_plugin_that_raises_is_reported_not_crashed() -> None:
    memory = _Memory()
    text = ('nodl_version: 2\nmixins:\n  - boom://x\n  - mem://ok\n  - mem://missing\n'
            'main: {nodl_version: 2}\n')
    with pytest.raises(ValidationError) as exc:
        compose(text, resolvers={'boom': _Exploding(), 'mem': memory})
    errors = errors_of(exc)
    assert [(d.line, d.column) for d in errors] == [(3, 5), (5, 5)]
    assert errors[0].message == ("cannot resolve mixin 'boom://x': the boom resolver failed "
                                 '(RuntimeError: plugin bug)')
    assert errors[1].message == ("cannot resolve mixin 'mem://missing': not in memory "
                                 '(searched: memory slot 1, memory slot 2)')
    assert [ref for ref, _ in memory.seen] == ['mem://ok', 'mem://missing']
    assert memory.seen[0][1] == ResolveContext(None, None)


def test_a_custom_resolver_provides_a_layer() -> None:
    composed = compose('nodl_version: 2\nmixins: [mem://ok]\nmain: {nodl_version: 2}\n',
                       resolvers={'mem': _Memory()})
    assert composed.interface.parameters['mem'].origin == 'mem://ok'


def test_with_an_explicit_resolver_set_unknown_schemes_list_the_known_ones(
        fixture_prefix: Path) -> None:
    with pytest.raises(ValidationError) as exc:
        compose(COMPOSITION / 'uses_index.nodl.yaml', resolvers={'mem': _Memory()})
    errors = errors_of(exc)
    assert len(errors) == 3
    assert "no resolver for the scheme 'nodl' (known: mem://" in errors[0].message


def test_a_relative_path_without_a_file_resolver_is_an_error() -> None:
    with pytest.raises(ValidationError) as exc:
        compose(LAYERS / 'node.nodl.yaml', resolvers={})
    errors = errors_of(exc)
    assert [(d.line, d.column) for d in errors] == [(4, 5), (16, 5)]
    assert "no resolver for the scheme 'file' (known: none" in errors[0].message


def test_files_are_the_definition_and_every_mixin_read(fixture_prefix: Path) -> None:
    """What an output must never overwrite: the node's file, then each mixin's file (a
    nested include's too), each once; in-place mixins and the built-in base are no file."""
    composed = layered()
    assert [os.path.basename(f) for f in composed.files] == [
        'node.nodl.yaml', 'first.nodl.yaml', 'second.nodl.yaml']
    assert all(os.path.isfile(f) for f in composed.files)
    assert [layer.file is None for layer in composed.layers] == [
        layer.is_base for layer in composed.layers]
    assert compose('nodl_version: 2\nmain: {nodl_version: 2}\n').files == []
