"""The built-in bases node and lifecycle_node (nodl_schema.composition.bases)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from nodl_schema import load_interface
from nodl_schema.composition.bases import BASES_DIR, base_file, base_layer
from nodl_schema.model import Base, Interface

SECTIONS = ('publishers', 'subscriptions', 'service_servers', 'service_clients',
            'action_servers', 'action_clients')

LIFECYCLE_SERVICES = {
    '~/change_state': 'lifecycle_msgs/srv/ChangeState',
    '~/get_state': 'lifecycle_msgs/srv/GetState',
    '~/get_available_states': 'lifecycle_msgs/srv/GetAvailableStates',
    '~/get_available_transitions': 'lifecycle_msgs/srv/GetAvailableTransitions',
    '~/get_transition_graph': 'lifecycle_msgs/srv/GetAvailableTransitions',
}


def load(base: str) -> Interface:
    return load_interface(Path(base_file(base)), strict=True)


def entities(iface: Interface) -> dict[tuple[str, str], object]:
    out: dict[tuple[str, str], object] = {('parameter', n): p for n, p in (iface.parameters or {}).items()}
    for section in SECTIONS:
        for e in getattr(iface, section) or ():
            out[(section, e.name)] = e
    return out


@pytest.mark.parametrize('base', ['node', 'lifecycle_node'])
def test_each_base_is_a_strictly_valid_interface_definition(base: str) -> None:
    path = Path(base_file(base))
    assert path.parent == Path(BASES_DIR)
    assert path.name == f'{base}.nodl.yaml'
    iface = load(base)  # strict: warnings would fail too
    assert iface.nodl_version == 2
    assert iface.description


def test_base_file_accepts_the_enum_and_refuses_unknown_bases() -> None:
    assert base_file(Base.LIFECYCLE_NODE) == base_file('lifecycle_node')
    with pytest.raises(ValueError):
        base_file('component')


def test_node_base_content() -> None:
    iface = load('node')
    assert set(iface.parameters) == {'use_sim_time', 'start_type_description_service'}
    assert iface.parameters['use_sim_time'].type == 'bool'
    assert iface.parameters['use_sim_time'].default_value is False
    assert iface.parameters['start_type_description_service'].read_only is True
    assert [p.name for p in iface.publishers] == ['/rosout', '/parameter_events']
    names = [s.name for s in iface.service_servers]
    assert names == ['~/describe_parameters', '~/get_parameter_types', '~/get_parameters',
                     '~/list_parameters', '~/set_parameters', '~/set_parameters_atomically',
                     '~/get_type_description']
    rosout = iface.publishers[0]
    assert (rosout.type, rosout.qos.durability, rosout.qos.depth) == (
        'rcl_interfaces/msg/Log', 'TRANSIENT_LOCAL', 1000)
    for section in ('subscriptions', 'service_clients', 'action_servers', 'action_clients'):
        assert not getattr(iface, section), section


def test_lifecycle_base_is_the_node_base_plus_lifecycle_entities() -> None:
    node, lifecycle = entities(load('node')), entities(load('lifecycle_node'))
    for key, entity in node.items():
        assert key in lifecycle, key
        assert lifecycle[key] == entity, key
    extra = {key: lifecycle[key] for key in lifecycle.keys() - node.keys()}
    expected = {('service_servers', name) for name in LIFECYCLE_SERVICES} | {
        ('publishers', '~/transition_event')}
    assert set(extra) == expected
    for name, type_ in LIFECYCLE_SERVICES.items():
        assert extra[('service_servers', name)].type == type_, name
    assert extra[('publishers', '~/transition_event')].type == 'lifecycle_msgs/msg/TransitionEvent'


def test_get_transition_graph_really_is_get_available_transitions() -> None:
    lifecycle = load('lifecycle_node')
    graph = next(s for s in lifecycle.service_servers if s.name == '~/get_transition_graph')
    assert graph.type == 'lifecycle_msgs/srv/GetAvailableTransitions'


@pytest.mark.parametrize('base', ['node', 'lifecycle_node'])
def test_base_layer(base: str) -> None:
    layer = base_layer(base)
    assert (layer.label, layer.role, layer.is_base) == (f'base:{base}', 'base', True)
    assert layer.interface == load(base)
    # diagnostics about the base are placed in its file
    from nodl_schema.diagnostics import Diagnostic, Severity

    placed = layer.place(Diagnostic(Severity.INFO, 'x', ('publishers', 0)))
    lines = Path(base_file(base)).read_text().splitlines()
    rosout = lines.index('  - name: /rosout') + 1
    assert (placed.file, placed.line, placed.column) == (base_file(base), rosout, 5)


def test_the_installed_package_ships_the_bases(tmp_path: Path) -> None:
    # run outside the source tree so that the installed copy is imported
    code = ('import nodl_schema.composition.bases as b, os; '
            "print(b.BASES_DIR); print(sorted(os.listdir(b.BASES_DIR)))")
    result = subprocess.run([sys.executable, '-c', code], cwd=tmp_path, text=True,
                            capture_output=True, timeout=60,
                            env={k: v for k, v in os.environ.items() if k != 'PYTHONPATH'})
    assert result.returncode == 0, result.stderr
    folder, listing = result.stdout.splitlines()
    assert 'site-packages' in folder
    assert listing == "['lifecycle_node.nodl.yaml', 'node.nodl.yaml']"
