"""Packages that ship only legacy (XML) NoDL files (nodl.registry.legacy).

A registered legacy node is converted to v2 in memory; what is said about it,
and where its entities are, points into the XML file the user wrote.
"""

from __future__ import annotations

import os
import subprocess
import sys

from conftest import FIXTURES, REPO
from nodl.composition.entities import Location
from nodl.composition.resolved import ResolvedNode
from nodl.diagnostics import Severity
from nodl.registry.legacy import compose_legacy, legacy_files, legacy_registrations
from nodl.registry.registrations import Registration
from nodl.show import show_registered
from nodl.targets.resolve import resolve_registered

PREFIX = str(FIXTURES / 'index' / 'legacy')
LEGACY_PKG = os.path.join(PREFIX, 'share', 'legacy_pkg', 'legacy_pkg.nodl.xml')
LISTENER = os.path.join(PREFIX, 'share', 'exported_pkg', 'interfaces', 'listener.nodl.xml')


def line_of(file: str, text: str) -> int:
    """The 1-based line of ``file`` holding ``text`` (once)."""
    with open(file, encoding='utf-8') as f:
        found = [n for n, line in enumerate(f, 1) if text in line]
    assert len(found) == 1, text
    return found[0]


def registration(package: str, name: str) -> Registration:
    return next(r for r in legacy_registrations(package, [PREFIX]) if r.name == name)


def test_both_ways_of_registering_are_found() -> None:
    assert legacy_files(None, [PREFIX]) == [('legacy_pkg', LEGACY_PKG), ('exported_pkg', LISTENER)]
    assert legacy_registrations(None, [PREFIX]) == [
        Registration('legacy_pkg', 'talker', 'legacy node', LEGACY_PKG),
        Registration('legacy_pkg', 'broken', 'legacy node', LEGACY_PKG),
        Registration('exported_pkg', 'listener', 'legacy node', LISTENER)]
    assert [r.name for r in legacy_registrations('exported_pkg', [PREFIX])] == ['listener']


def test_entities_are_located_at_their_xml_elements() -> None:
    composed, diagnostics = compose_legacy(registration('legacy_pkg', 'talker'))
    assert composed is not None, diagnostics
    assert composed.file == LEGACY_PKG
    main = {(e.kind.value, e.name): e.location
            for e in ResolvedNode(composed, '').entities if e.layer == 'main'}

    def at(text: str) -> Location:
        return Location(LEGACY_PKG, line_of(LEGACY_PKG, text), 5)

    assert main == {
        ('parameter', 'rate'): at('name="rate"'),
        ('publisher', 'chatter'): at('name="chatter"'),
        ('publisher', 'echo'): at('name="echo"'),  # role="both": one element, two entities
        ('subscription', 'echo'): at('name="echo"'),
        ('service_server', 'reset'): at('name="reset"'),
        ('action_server', 'fibonacci'): at('name="fibonacci"'),
    }


def test_a_node_exported_by_package_xml_is_located_in_its_file() -> None:
    composed, diagnostics = compose_legacy(registration('exported_pkg', 'listener'))
    assert composed is not None, diagnostics
    [chatter] = [e for e in ResolvedNode(composed, '').entities if e.layer == 'main']
    assert chatter.location == Location(LISTENER, line_of(LISTENER, 'name="chatter"'), 5)


def test_a_composition_error_is_placed_at_the_xml_element() -> None:
    composed, diagnostics = compose_legacy(registration('legacy_pkg', 'broken'))
    assert composed is None
    [error] = [d for d in diagnostics if d.severity is Severity.ERROR]
    assert error.code == 'NODL307' and 'use_sim_time' in error.message
    assert (error.file, error.line, error.column) == (
        LEGACY_PKG, line_of(LEGACY_PKG, 'name="use_sim_time"'), 5)
    assert error.path == ('main', 'parameters', 'use_sim_time')
    assert [r[3] for r in error.related] == ['the declaration in base:node']


def test_conversion_diagnostics_are_kept() -> None:
    _, diagnostics = compose_legacy(registration('legacy_pkg', 'talker'))
    assert [(d.code, d.line, d.column) for d in diagnostics] == [
        ('NODL811', line_of(LEGACY_PKG, 'name="talker"'), 9),  # the node name attribute
        ('NODL812', line_of(LEGACY_PKG, 'std_msgs/String"'), 24)]  # the short type attribute
    assert {d.file for d in diagnostics} == {LEGACY_PKG}


def test_nothing_points_at_an_in_memory_document() -> None:
    for name in ('talker', 'broken'):
        resolved, diagnostics, source = resolve_registered('legacy_pkg', name, prefixes=[PREFIX])
        assert source == LEGACY_PKG
        files = {d.file for d in diagnostics} | {r[0] for d in diagnostics for r in d.related}
        if resolved is not None:
            files |= {e.location.file for e in resolved.entities if e.layer == 'main'}
        assert files and not any('converted' in f for f in files), files
        assert LEGACY_PKG in files


def test_show_registered_locates_a_legacy_node_in_its_xml_file() -> None:
    shown = show_registered('legacy_pkg', 'talker', prefixes=[PREFIX])
    assert shown.ok and shown.source == LEGACY_PKG and shown.resolved is not None
    assert {e.location.file for e in shown.resolved.entities if e.layer == 'main'} == {LEGACY_PKG}


def test_nodl_show_prints_the_xml_position() -> None:
    result = subprocess.run([sys.executable, '-m', 'nodl', 'show', 'legacy_pkg', 'broken',
                             '--color', 'never'], cwd=REPO, text=True, capture_output=True,
                            env=dict(os.environ, AMENT_PREFIX_PATH=PREFIX), timeout=60)
    assert result.returncode == 1, result.stderr
    line = line_of(LEGACY_PKG, 'name="use_sim_time"')
    assert f'{LEGACY_PKG}:{line}:5: error: parameter ' in result.stderr
    assert 'converted' not in result.stderr
