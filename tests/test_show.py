"""`show`: a node's whole interface, resolved (nodl.show)."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl import dump_nodl, load_interface
from nodl.diagnostics import Severity
from nodl.model import Interface
from nodl.show import Shown, render, show_file, show_registered

EXAMPLES = REPO / 'examples'
GOLDEN = FIXTURES / 'show'
INDEX = FIXTURES / 'index'
SECTIONS = ('publishers', 'subscriptions', 'service_servers', 'service_clients',
            'action_servers', 'action_clients')


def shown(path: Path) -> Shown:
    result = show_file(os.path.relpath(path, REPO) if path.is_relative_to(REPO) else str(path))
    assert result.ok, [str(d) for d in result.diagnostics]
    return result


def origins(iface: Interface) -> list[tuple[str, str, str | None]]:
    out = [('parameters', name, p.origin) for name, p in (iface.parameters or {}).items()]
    for section in SECTIONS:
        out += [(section, e.name, e.origin) for e in getattr(iface, section) or ()]
    return out


@pytest.fixture(autouse=True)
def _in_repo(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(REPO)


# --- show_file -----------------------------------------------------------------------------

def test_show_file_composes_a_node() -> None:
    result = shown(EXAMPLES / 'laser_driver.nodl.yaml')
    assert result.source == 'examples/laser_driver.nodl.yaml'
    iface = result.interface
    assert iface.parameters['use_sim_time'].origin == 'base:node'
    assert iface.parameters['diagnostics.period'].origin == 'diagnostics.nodl.yaml'
    assert iface.parameters['port'].origin == 'main'
    assert {s.name: s.origin for s in iface.service_servers}['~/self_test'] == 'diagnostics.nodl.yaml'
    assert not [d for d in result.diagnostics if d.severity is Severity.ERROR]


def test_show_file_of_an_interface_labels_entities_with_the_file_name() -> None:
    result = shown(EXAMPLES / 'diagnostics.nodl.yaml')
    assert {o for _, _, o in origins(result.interface)} == {'diagnostics.nodl.yaml'}
    assert result.interface.description == 'Health reporting shared by all device drivers.'


def test_show_file_of_a_parameter_definition_is_an_error() -> None:
    result = show_file('examples/max_speed.nodl.yaml')
    assert not result.ok and result.interface is None
    [error] = result.diagnostics
    assert (error.severity, error.file, error.line, error.column) == (
        Severity.ERROR, 'examples/max_speed.nodl.yaml', 1, 1)
    assert 'a parameter definition has no interface to show' in error.message


def test_show_file_of_an_invalid_file_returns_its_diagnostics() -> None:
    result = show_file('examples/mistakes/typos.yaml')
    assert not result.ok
    errors = [d for d in result.diagnostics if d.severity is Severity.ERROR]
    assert len(errors) == 7
    assert all(d.file == 'examples/mistakes/typos.yaml' and d.line > 0 for d in errors)


def test_show_file_of_a_node_whose_mixins_fail(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(FIXTURES / 'composition' / 'prefix'))
    result = show_file('tests/fixtures/composition/errors/pkg/all_errors.nodl.yaml')
    assert not result.ok
    assert len([d for d in result.diagnostics if d.severity is Severity.ERROR]) == 12


# --- show_registered -----------------------------------------------------------------------

def test_show_registered_composes_across_prefixes(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', os.pathsep.join([str(INDEX / 'first'),
                                                             str(INDEX / 'second')]))
    result = show_registered('beta', 'node')
    assert result.ok, [str(d) for d in result.diagnostics]
    assert result.source == str(INDEX / 'second' / 'share' / 'beta' / 'nodl' / 'node.nodl.yaml')
    pubs = {p.name: p.origin for p in result.interface.publishers}
    assert pubs['~/status'] == 'nodl://beta/status'
    assert pubs['chatter'] == 'nodl://alpha/chatter'
    assert pubs['~/transition_event'] == 'base:lifecycle_node'
    talker = show_registered('alpha', 'talker')
    assert talker.interface.description == 'The talker of the FIRST prefix.'
    inline = show_registered('alpha', 'inline')
    assert inline.interface.description == 'A node definition held in the index entry itself.'


def test_show_registered_not_found(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(INDEX / 'first'))
    result = show_registered('alpha', 'nope')
    assert not result.ok
    [error] = result.diagnostics
    assert str(error) == ("alpha/nope: error: package 'alpha' registers no node definition for "
                          "'nope' (it has: inline, talker) [NODL306]")


def test_show_registered_dangling_entry_says_what_is_missing(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(INDEX / 'first'))
    result = show_registered('delta', 'dangling')
    assert not result.ok
    [error] = result.diagnostics
    assert error.file == 'delta/dangling'
    assert 'gone.nodl.yaml, which does not exist (is the package fully installed?)' in error.message


# --- render --------------------------------------------------------------------------------

@pytest.mark.parametrize('example', ['laser_driver', 'camera_lifecycle'])
def test_render_yaml_with_layers_golden(example: str, golden) -> None:
    result = shown(EXAMPLES / f'{example}.nodl.yaml')
    golden.check(render(result.interface, 'yaml', layers=True, client_library=result.client_library),
                 GOLDEN / f'{example}.layers.yaml')


@pytest.mark.parametrize('example', ['laser_driver', 'camera_lifecycle'])
def test_render_yaml_golden(example: str, golden) -> None:
    result = shown(EXAMPLES / f'{example}.nodl.yaml')
    golden.check(render(result.interface, 'yaml', client_library=result.client_library),
                 GOLDEN / f'{example}.yaml')


def test_render_json_with_layers_golden(golden) -> None:
    result = shown(EXAMPLES / 'camera_lifecycle.nodl.yaml')
    golden.check(render(result.interface, 'json', layers=True, client_library=result.client_library),
                 GOLDEN / 'camera_lifecycle.layers.json')


@pytest.mark.parametrize('example', ['laser_driver', 'camera_lifecycle', 'diagnostics'])
def test_yaml_with_layers_is_itself_a_valid_interface_definition(example: str) -> None:
    iface = shown(EXAMPLES / f'{example}.nodl.yaml').interface
    text = render(iface, 'yaml', layers=True)
    again = load_interface(text, strict=True)
    assert again == iface
    # one "# layer:" comment per entity, right above it, in order
    comments = [line.strip()[len('# layer: '):] for line in text.splitlines()
                if line.strip().startswith('# layer: ')]
    assert comments == [o for _, _, o in origins(iface)]


@pytest.mark.parametrize('example', ['laser_driver', 'camera_lifecycle'])
def test_plain_renderings_round_trip(example: str) -> None:
    iface = shown(EXAMPLES / f'{example}.nodl.yaml').interface
    yaml_text = render(iface, 'yaml')
    assert yaml_text == dump_nodl(iface, 'yaml')
    assert '# layer' not in yaml_text
    assert load_interface(yaml_text) == iface
    json_text = render(iface, 'json')
    assert json.loads(json_text) == iface.to_dict()
    assert load_interface(json_text) == iface


def test_json_with_layers_lists_each_entitys_layer() -> None:
    iface = shown(EXAMPLES / 'camera_lifecycle.nodl.yaml').interface
    data = json.loads(render(iface, 'json', layers=True))
    assert set(data) == {'interface', 'layers'}
    assert load_interface(json.dumps(data['interface'])) == iface
    assert [(layer['section'], layer['name'], layer['layer']) for layer in data['layers']] == origins(iface)
    assert {'section': 'service_servers', 'name': '~/set_camera_info',
            'layer': 'mixins[0]'} in data['layers']
    assert {'section': 'publishers', 'name': '~/transition_event',
            'layer': 'base:lifecycle_node'} in data['layers']


def test_non_ascii_text_is_kept_in_every_format(tmp_path: Path) -> None:
    node = tmp_path / 'node.nodl.yaml'
    node.write_text('nodl_version: 2\nmain:\n  nodl_version: 2\n  description: Größe – 大きさ\n',
                    encoding='utf-8')
    iface = show_file(str(node)).interface
    for fmt in ('yaml', 'json'):
        for layers in (False, True):
            assert 'Größe – 大きさ' in render(iface, fmt, layers), (fmt, layers)


def test_render_refuses_an_unknown_format() -> None:
    iface = shown(EXAMPLES / 'diagnostics.nodl.yaml').interface
    with pytest.raises(ValueError, match="unsupported format 'toml'"):
        render(iface, 'toml')
    with pytest.raises(ValueError, match="unsupported format 'toml'"):
        render(iface, 'toml', layers=True)


def test_render_of_an_empty_interface() -> None:
    assert render(Interface(nodl_version=2), 'yaml', layers=True) == 'nodl_version: 2\n'
    assert json.loads(render(Interface(nodl_version=2), 'json', layers=True)) == {
        'interface': {'nodl_version': 2}, 'layers': []}


# --- client libraries and the resolved node ----------------------------------------------------

def test_show_file_states_the_client_library_and_uses_its_base() -> None:
    default = shown(EXAMPLES / 'laser_driver.nodl.yaml')
    assert default.client_library == ('rclpy', 'the default; choose with --client-library')
    assert default.resolved is not None and default.resolved.client_library == 'rclpy'
    assert not default.interface.subscriptions or all(
        s.name != '/parameter_events' for s in default.interface.subscriptions)
    rclcpp = show_file('examples/laser_driver.nodl.yaml', 'rclcpp')
    assert rclcpp.client_library == ('rclcpp', 'as requested')
    subscription = {s.name: s for s in rclcpp.interface.subscriptions}['/parameter_events']
    assert subscription.origin == 'base:node'
    text = render(rclcpp.interface, 'yaml', client_library=rclcpp.client_library)
    assert text.startswith('# client library: rclcpp (as requested)\n')
    load_interface(text, strict=True)  # the statement is a comment: still a valid definition
    with pytest.raises(ValueError, match='unknown client library'):
        show_file('examples/laser_driver.nodl.yaml', 'rclc')


def test_an_interface_or_a_node_without_base_states_no_client_library() -> None:
    assert shown(EXAMPLES / 'diagnostics.nodl.yaml').client_library is None


def test_show_refuses_a_node_that_redefines_its_base() -> None:
    result = show_file(str(FIXTURES / 'composition' / 'overrides' / 'base_redefined.nodl.yaml'))
    assert not result.ok
    assert [d.code for d in result.diagnostics if d.severity is Severity.ERROR] == [
        'NODL307', 'NODL307']


def test_a_statement_cannot_break_out_of_its_comment() -> None:
    from nodl.composition.client_library import ClientLibraryChoice

    text = render(Interface(nodl_version=2), 'yaml',
                  client_library=ClientLibraryChoice('rclpy', "package 'x\nnodl_version: 3' ..."))
    assert text.splitlines()[0].startswith('# client library: rclpy')
    assert load_interface(text).nodl_version == 2
