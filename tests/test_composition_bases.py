"""The built-in bases node and lifecycle_node (nodl.composition.bases)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from nodl import load_interface
from nodl.composition.bases import (
    BASES_DIR,
    CLIENT_LIBRARIES,
    base_file,
    base_files,
    base_layer,
)
from nodl.model import Base, Interface

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


@pytest.mark.parametrize('part', ['node', 'lifecycle_node', 'rclcpp/node'])
def test_each_base_part_is_a_strictly_valid_interface_definition(part: str) -> None:
    path = Path(BASES_DIR, f'{part}.nodl.yaml')
    iface = load_interface(path, strict=True)  # strict: warnings would fail too
    assert iface.nodl_version == 2
    assert iface.description


def test_base_files_are_shared_parts_then_the_library_additions() -> None:
    names = {(base, library): [os.path.relpath(f, BASES_DIR) for f in base_files(base, library)]
             for base in ('node', 'lifecycle_node') for library in CLIENT_LIBRARIES}
    assert names == {
        ('node', 'rclpy'): ['node.nodl.yaml'],
        ('node', 'rclcpp'): ['node.nodl.yaml', 'rclcpp/node.nodl.yaml'],
        ('lifecycle_node', 'rclpy'): ['node.nodl.yaml', 'lifecycle_node.nodl.yaml'],
        ('lifecycle_node', 'rclcpp'): ['node.nodl.yaml', 'lifecycle_node.nodl.yaml',
                                       'rclcpp/node.nodl.yaml'],
    }
    with pytest.raises(ValueError, match="unknown client library 'rclc'; expected one of: rclpy, "
                                         'rclcpp'):
        base_files('node', 'rclc')


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
    node = entities(base_layer('node').interface)
    lifecycle = entities(base_layer('lifecycle_node').interface)
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


@pytest.mark.parametrize('base', ['node', 'lifecycle_node'])
def test_rclcpp_adds_the_time_source_parameter_events_subscription(base: str) -> None:
    rclpy = entities(base_layer(base, 'rclpy').interface)
    rclcpp = entities(base_layer(base, 'rclcpp').interface)
    assert set(rclcpp) - set(rclpy) == {('subscriptions', '/parameter_events')}
    assert all(rclcpp[key] == entity for key, entity in rclpy.items())
    sub = rclcpp[('subscriptions', '/parameter_events')]
    assert sub.type == 'rcl_interfaces/msg/ParameterEvent'
    assert (sub.qos.depth, sub.qos.reliability, sub.qos.durability) == (1000, 'RELIABLE', 'VOLATILE')
    # the rclcpp additions say they are derived from documentation, not observed
    assert 'derived from rclcpp' in load_interface(Path(BASES_DIR, 'rclcpp', 'node.nodl.yaml')).description


def test_get_transition_graph_really_is_get_available_transitions() -> None:
    lifecycle = load('lifecycle_node')
    graph = next(s for s in lifecycle.service_servers if s.name == '~/get_transition_graph')
    assert graph.type == 'lifecycle_msgs/srv/GetAvailableTransitions'


@pytest.mark.parametrize('base', ['node', 'lifecycle_node'])
@pytest.mark.parametrize('library', CLIENT_LIBRARIES)
def test_base_layer(base: str, library: str) -> None:
    layer = base_layer(base, library)
    assert (layer.label, layer.role, layer.is_base) == (f'base:{base}', 'base', True)
    if (base, library) == ('node', 'rclpy'):
        assert layer.interface == load(base)
    # diagnostics about the base are placed in the part file that declares the entity
    from nodl.diagnostics import Diagnostic, Severity

    def line_of(part: str, text: str) -> int:
        return Path(BASES_DIR, f'{part}.nodl.yaml').read_text().splitlines().index(text) + 1

    placed = layer.place(Diagnostic(Severity.INFO, 'x', ('publishers', 0)))
    assert (placed.file, placed.line, placed.column) == (
        base_file('node'), line_of('node', '  - name: /rosout'), 5)
    iface = layer.interface
    if base == 'lifecycle_node':
        index = [s.name for s in iface.service_servers].index('~/change_state')
        placed = layer.place(Diagnostic(Severity.INFO, 'x', ('service_servers', index, 'type')))
        assert (placed.file, placed.line) == (
            base_file('lifecycle_node'), line_of('lifecycle_node', '  - name: ~/change_state') + 1)
    if library == 'rclcpp':
        placed = layer.place(Diagnostic(Severity.INFO, 'x', ('subscriptions', 0)))
        assert (placed.file, placed.line) == (
            str(Path(BASES_DIR, 'rclcpp', 'node.nodl.yaml')),
            line_of('rclcpp/node', '  - name: /parameter_events'))


def test_base_layers_are_copies() -> None:
    layer = base_layer('node')
    layer.interface.parameters['use_sim_time'].description = 'changed'
    assert base_layer('node').interface.parameters['use_sim_time'].description != 'changed'


def test_the_installed_package_ships_the_bases(tmp_path: Path) -> None:
    # run outside the source tree so that the installed copy is imported
    code = ('import nodl.composition.bases as b, os; '
            "print(b.BASES_DIR); print(sorted(os.path.relpath(os.path.join(d, f), b.BASES_DIR) "
            "for d, _, fs in os.walk(b.BASES_DIR) for f in fs))")
    result = subprocess.run([sys.executable, '-c', code], cwd=tmp_path, text=True,
                            capture_output=True, timeout=60,
                            env={k: v for k, v in os.environ.items() if k != 'PYTHONPATH'})
    assert result.returncode == 0, result.stderr
    folder, listing = result.stdout.splitlines()
    assert 'site-packages' in folder
    assert listing == "['lifecycle_node.nodl.yaml', 'node.nodl.yaml', 'rclcpp/node.nodl.yaml']"
