"""Matching launched nodes to their registered definitions (nodl.system.matching): every
definition the launch runs is read and checked before any is composed, each once."""

from __future__ import annotations

from pathlib import Path
from unittest import mock

from nodl.launch import load_launch
from nodl.launch.model import LaunchedNode
from nodl.location import Location
from nodl.registry import registrations
from nodl.system.matching import DefinitionMatcher

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]


def _records() -> list[LaunchedNode]:
    return load_launch(str(FIXTURES / 'launch' / 'checks.launch.xml'), {}, prefixes=PREFIX).nodes


def test_read_ahead_reads_every_definition_before_matching_composes_them() -> None:
    records = _records()
    assert len({(r.package, r.executable) for r in records if r.plugin is None}) >= 2
    plain = [DefinitionMatcher(None, PREFIX).match(r) for r in records if r.plugin is None]
    plain += [DefinitionMatcher(None, PREFIX).match(r) for r in records if r.plugin is not None]
    with registrations.one_run():
        matcher = DefinitionMatcher(None, PREFIX)
        with mock.patch.object(registrations.loading, 'check_source',
                               wraps=registrations.loading.check_source) as read:
            matcher.read_ahead(records)
            ahead = read.call_count
            assert ahead >= 2
            matched = [matcher.match(r) for r in records if r.plugin is None]
            assert read.call_count == ahead  # composed from what was read ahead
            matched += [matcher.match(r) for r in records if r.plugin is not None]
            assert read.call_count == ahead + 1  # (a plugin's definition: found when matched)
    assert [(m.package, m.key, m.file, m.node_name, m.how, m.origin, [str(p) for p in m.problems])
            for m in matched] == \
        [(m.package, m.key, m.file, m.node_name, m.how, m.origin, [str(p) for p in m.problems])
         for m in plain]
    assert [m.resolved is None for m in matched] == [m.resolved is None for m in plain]


def test_read_ahead_leaves_what_cannot_be_found_to_matching() -> None:
    missing = LaunchedNode('node', 'nowhere', 'nothing', 'n', '/', Location('x.launch.xml', 1, 1))
    with registrations.one_run():
        matcher = DefinitionMatcher(None, PREFIX)
        matcher.read_ahead([missing])
        assert matcher.match(missing).resolved is None
