"""check_node round trips with real node processes.

full_node is described, the description written to a file and the same
node checked against it (it conforms); edited copies of that file drift in
the expected ways; a node started with a remapping conforms only when the
check is told about the remapping; a definition registered in an ament
prefix is found by (package, executable).
"""

from __future__ import annotations

import copy
import json
import os
import re
import time
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from conftest import FIXTURES, NodeProcess
from nodl import ValidationError, dump_nodl
from nodl.live.check import CheckResult, check_node, load_definition
from nodl.live.describe import describe_node, render_description
from nodl.live.report import check_report, format_check_text
from nodl.live.session import NodeNotFound
from nodl.reporting.reporters import JsonReporter, JUnitReporter


def _json(result: CheckResult) -> str:
    """The check's JSON report, as ``nodl check --format json`` writes it."""
    return JsonReporter().report(check_report(result))


def _junit(result: CheckResult) -> str:
    """The check's JUnit report, as ``nodl check --format junit`` writes it."""
    return JUnitReporter().report(check_report(result))


@pytest.fixture(scope='module')
def full() -> Iterator[NodeProcess]:
    node = NodeProcess('full_node.py', 'full', '/chk')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def remapped() -> Iterator[NodeProcess]:
    node = NodeProcess('full_node.py', 'remapped', '/chk', '--ros-args', '-r', 'commands:=cmd_in')
    try:
        yield node
    finally:
        node.stop()


@pytest.fixture(scope='module')
def described(full: NodeProcess, tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict]:
    description = describe_node(full.fqn, timeout=15)
    path = tmp_path_factory.mktemp('check') / 'full.nodl.yaml'
    path.write_text(render_description(description), encoding='utf-8')
    return path, description.definition


def _write(tmp_path: Path, definition: dict[str, Any], name: str = 'edited.nodl.yaml') -> Path:
    path = tmp_path / name
    path.write_text(dump_nodl(definition, 'yaml'), encoding='utf-8')
    return path


def _entry(definition: dict[str, Any], section: str, name: str) -> dict[str, Any]:
    return next(e for e in definition['main'][section] if e['name'] == name)


# -- round trip ------------------------------------------------------------------------------


def test_described_node_conforms_to_its_description(full: NodeProcess, described) -> None:
    path, _ = described
    result = check_node(full.fqn, path, timeout=15)
    assert isinstance(result, CheckResult)
    assert result.conforms, format_check_text(result, verbose=True)
    assert result.drift == []
    assert result.fqn == '/chk/full'
    assert result.definition == str(path)
    assert result.observed.fully_qualified_name == '/chk/full'
    # history was written as SYSTEM_DEFAULT and services carry no QoS: listed, never failing
    kinds = {d.kind for d in result.differences}
    assert kinds <= {'unverifiable'}
    text = format_check_text(result)
    assert text.splitlines()[-1].startswith(f'/chk/full conforms to {path}')


def test_check_watches_for_namesakes_while_it_works_and_says_how_long(full: NodeProcess,
                                                                      described) -> None:
    path, _ = described
    result = check_node(full.fqn, path, timeout=15, watch=1.0)
    assert result.watched is not None and result.watched >= 1.0
    text = format_check_text(result)
    assert text.splitlines()[1].startswith('/chk/full: namesakes watched for ')
    assert json.loads(_json(result))['namesakes_watched'] == round(result.watched, 2)
    # by default, past the 3 s periodic announcements: nothing more to suggest
    default = check_node(full.fqn, path, timeout=15)
    assert default.watched is not None and default.watched >= 3.5
    assert '--watch' not in format_check_text(default)


def test_hand_written_definition_conforms(full: NodeProcess) -> None:
    """An independent definition (written from full_node.py's source, not described)."""
    path = FIXTURES / 'live' / 'full_node.nodl.yaml'
    result = check_node(full.fqn, path, timeout=15)
    assert result.conforms, format_check_text(result, verbose=True)
    unverifiable = [d for d in result.differences if d.kind == 'unverifiable']
    assert all(d.severity == 'info' for d in unverifiable)
    # every declared QoS policy the middleware reports was compared and agreed; what it does not
    # report (Fast DDS: history and depth) is listed, per endpoint and policy
    status = [d for d in unverifiable if d.name == '/chk/full/status']
    observed = next(e for e in result.observed.publishers if e.name == '/chk/full/status')
    assert sorted(d.message.split(' ')[2] for d in status) == \
        sorted(f'{p}:' for p in ('history', 'depth') if p in observed.unobserved)


# -- edited copies ---------------------------------------------------------------------------


@pytest.fixture(scope='module')
def edited(full: NodeProcess, described, tmp_path_factory: pytest.TempPathFactory) -> CheckResult:
    """One copy with every kind of edit, checked once against the real node."""
    _, original = described
    definition = copy.deepcopy(original)
    main = definition['main']
    # declared but not there -> missing
    main['publishers'].append({'name': '~/odom', 'type': 'nav_msgs/msg/Odometry',
                               'qos': {'history': 'KEEP_LAST', 'depth': 5, 'reliability': 'RELIABLE'}})
    # another type -> type
    _entry(definition, 'subscriptions', '/emergency_stop')['type'] = 'std_msgs/msg/String'
    # another reliability -> qos naming the policy
    _entry(definition, 'publishers', '~/status')['qos']['reliability'] = 'BEST_EFFORT'
    # a declared subscription removed -> the observed one is extra
    main['subscriptions'] = [e for e in main['subscriptions'] if e['name'] != 'commands']
    # parameters: another type, read_only, a validator the current value breaks (a warning)
    main['parameters']['rate']['type'] = 'double'
    main['parameters']['rate']['default_value'] = 10.0
    main['parameters']['frame_id']['read_only'] = False
    main['parameters']['gain']['validation'] = {'bounds<>': [0.6, 1.0]}
    main['parameters']['gain']['default_value'] = 0.7
    path = _write(tmp_path_factory.mktemp('edited'), definition)
    return check_node(full.fqn, path, timeout=15)


def test_edited_copy_drifts_with_the_right_kinds(edited: CheckResult) -> None:
    assert not edited.conforms
    drift = sorted((d.kind, d.section, d.name) for d in edited.drift)
    assert drift == [
        ('extra', 'subscriptions', '/chk/commands'),
        ('missing', 'publishers', '/chk/full/odom'),
        ('parameter_type', 'parameters', 'rate'),
        ('qos', 'publishers', '/chk/full/status'),
        ('read_only', 'parameters', 'frame_id'),
        ('type', 'subscriptions', '/emergency_stop'),
    ]
    assert all(d.layer == 'main' for d in edited.drift if d.kind != 'extra')


def test_edited_copy_qos_difference_names_the_policy(edited: CheckResult) -> None:
    qos = next(d for d in edited.drift if d.kind == 'qos')
    assert (qos.declared, qos.observed) == ('BEST_EFFORT', 'RELIABLE')
    assert 'reliability' in qos.message
    kind_type = next(d for d in edited.drift if d.kind == 'type')
    assert (kind_type.declared, kind_type.observed) == ('std_msgs/msg/String', 'std_msgs/msg/Bool')


def test_edited_copy_value_is_a_warning(edited: CheckResult) -> None:
    values = [d for d in edited.differences if d.kind == 'value']
    assert [(d.name, d.severity, d.observed) for d in values] == [('gain', 'warning', 0.5)]
    assert 'bounds<>' in values[0].message


def test_reports_of_the_edited_copy(edited: CheckResult) -> None:
    text = format_check_text(edited)
    assert text.splitlines()[-1].startswith('/chk/full drifts from ')
    assert '6 differences' in text
    assert 'warning: value:' in text
    assert 'unverifiable' not in '\n'.join(text.splitlines()[:-1])  # listed with -v only
    assert 'info: unverifiable:' in format_check_text(edited, verbose=True)

    data = json.loads(_json(edited))
    assert data['node'] == '/chk/full' and data['conforms'] is False
    assert sorted(d['kind'] for d in data['differences'] if d['severity'] == 'error') == \
        ['extra', 'missing', 'parameter_type', 'qos', 'read_only', 'type']

    suite = ET.fromstring(_junit(edited))
    assert suite.tag == 'testsuite'
    failures = {(case.get('classname'), case.get('name')): [f.get('type') for f in case.iter('failure')]
                for case in suite.iter('testcase')}
    assert int(suite.get('failures')) == sum(1 for f in failures.values() if f) == 6
    assert int(suite.get('tests')) == len(failures)
    # failures sit on the declared entity they are about
    assert failures[('publishers', '~/status')] == ['qos']
    assert failures[('publishers', '~/odom')] == ['missing']
    assert failures[('subscriptions', '/emergency_stop')] == ['type']
    assert failures[('parameters', 'rate')] == ['parameter_type']
    assert failures[('parameters', 'frame_id')] == ['read_only']
    assert failures[('subscriptions', '/chk/commands')] == ['extra']
    assert failures[('publishers', 'measurement')] == []


# -- remapping -------------------------------------------------------------------------------


def test_remapped_node_conforms_with_the_remap(remapped: NodeProcess, described) -> None:
    path, _ = described
    result = check_node(remapped.fqn, path, timeout=15, remaps=['commands:=cmd_in'])
    assert result.conforms, format_check_text(result)
    assert '/chk/cmd_in' in {e.name for e in result.observed.subscriptions}


def test_remapped_node_drifts_without_the_remap(remapped: NodeProcess, described) -> None:
    path, _ = described
    result = check_node(remapped.fqn, path, timeout=15)
    assert sorted((d.kind, d.name) for d in result.drift) == \
        [('extra', '/chk/cmd_in'), ('missing', '/chk/commands')]


# -- ament index -----------------------------------------------------------------------------


def _prefix(tmp_path: Path, package: str, executable: str, definition: Path) -> Path:
    prefix = tmp_path / 'install'
    index = prefix / 'share' / 'ament_index' / 'resource_index'
    (index / 'nodl_nodes').mkdir(parents=True)
    (index / 'packages').mkdir(parents=True)
    (index / 'nodl_nodes' / f'{package}__{executable}').write_text(str(definition.resolve()),
                                                                   encoding='utf-8')
    (index / 'packages' / package).write_text('', encoding='utf-8')
    return prefix


def test_check_by_package_and_executable(full: NodeProcess, described, tmp_path: Path,
                                         monkeypatch: pytest.MonkeyPatch) -> None:
    path, _ = described
    prefix = _prefix(tmp_path, 'chk_pkg', 'full_node', path)
    existing = os.environ.get('AMENT_PREFIX_PATH', '')
    monkeypatch.setenv('AMENT_PREFIX_PATH', os.pathsep.join(p for p in (str(prefix), existing) if p))
    result = check_node(full.fqn, ('chk_pkg', 'full_node'), timeout=15)
    assert result.conforms, format_check_text(result)
    assert result.definition == str(path.resolve())

    with pytest.raises(ValidationError) as caught:
        load_definition(('chk_pkg', 'other_node'))
    assert "registers no node definition for 'other_node' (it has: full_node)" in str(caught.value)
    with pytest.raises(ValidationError, match="package 'no_such_pkg' is not in the ament index"):
        load_definition(('no_such_pkg', 'x'))


# -- errors before or instead of observing ---------------------------------------------------


def test_invalid_definition_raises_before_observing(tmp_path: Path) -> None:
    bad = tmp_path / 'bad.nodl.yaml'
    bad.write_text('nodl_version: 2\nmain:\n  nodl_version: 2\n  publishers:\n    - name: x\n',
                   encoding='utf-8')
    start = time.monotonic()
    with pytest.raises(ValidationError) as caught:
        check_node('/chk/not_running', bad, timeout=30)
    assert time.monotonic() - start < 5
    assert all(d.file == str(bad) and d.line for d in caught.value.diagnostics)


def test_malformed_remap_raises_value_error() -> None:
    with pytest.raises(ValueError, match='invalid remapping'):
        check_node('/chk/not_running', FIXTURES / 'live' / 'drive_node.nodl.yaml',
                   remaps=['commands=cmd_in'], timeout=30)


def test_node_not_running_is_not_found_within_the_timeout() -> None:
    start = time.monotonic()
    with pytest.raises(NodeNotFound):
        check_node('/chk/not_running', FIXTURES / 'live' / 'drive_node.nodl.yaml', timeout=1.0)
    assert time.monotonic() - start < 1.0 + 3


_LATE_NODE = '''
import sys
import time

import rclpy
from std_msgs.msg import String

argv = sys.argv[1:]
rclpy.init()
node = rclpy.create_node(argv[argv.index('--name') + 1],
                         namespace=argv[argv.index('--namespace') + 1])
print('ready', flush=True)
try:
    end = time.monotonic() + 0.6
    while time.monotonic() < end:
        rclpy.spin_once(node, timeout_sec=0.05)
    node.create_subscription(String, 'late_commands', lambda m: None, 10)  # set up late
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
'''


def test_endpoint_created_after_start_up_is_found(ros_node, tmp_path: Path) -> None:
    """check looks again for declared endpoints it has not seen: no false `missing`."""
    script = tmp_path / 'late_node.py'
    script.write_text(_LATE_NODE, encoding='utf-8')
    definition = _write(tmp_path, {'nodl_version': 2, 'base': 'node', 'main': {
        'nodl_version': 2,
        'subscriptions': [{'name': 'late_commands', 'type': 'std_msgs/msg/String',
                           'qos': {'history': 'KEEP_LAST', 'depth': 10, 'reliability': 'RELIABLE'}}]}})
    node = ros_node(str(script), 'late', '/chk')
    result = check_node(node.fqn, definition, timeout=15)
    assert result.conforms, format_check_text(result)


def test_node_renamed_by_its_rules_conforms_with_them(described) -> None:
    """__node/__ns rules made NODE what it is; node-scoped rules match that final name (rcl)."""
    rules = ['__node:=renamed', '__ns:=/chk2', 'renamed:commands:=cmd_in',
             'full:commands:=not_this_node']
    node = NodeProcess('full_node.py', 'full', '/chk', '--ros-args',
                       *[part for rule in rules for part in ('-r', rule)])
    try:
        path, _ = described
        result = check_node('/chk2/renamed', path, timeout=15, remaps=rules)
        assert result.conforms, format_check_text(result)
        assert '/chk2/cmd_in' in {e.name for e in result.observed.subscriptions}
        assert result.fqn == '/chk2/renamed'
    finally:
        node.stop()


# -- client libraries and the resolved node ----------------------------------------------------


def test_the_rclcpp_base_is_checked_when_asked_for(full: NodeProcess, described) -> None:
    # full_node is an rclpy node: checked as rclcpp, it lacks the time source's subscription
    path, _ = described
    result = check_node(full.fqn, path, timeout=15, client_library='rclcpp')
    assert not result.conforms
    assert [(d.kind, d.section, d.name, d.layer) for d in result.drift] == [
        ('missing', 'subscriptions', '/parameter_events', 'base:node')]
    assert result.client_library == ('rclcpp', 'as requested')
    assert format_check_text(result).splitlines()[0] == (
        '/chk/full: client library: rclcpp (as requested)')
    assert json.loads(_json(result))['client_library'] == {
        'name': 'rclcpp', 'reason': 'as requested'}
    # the difference points at the declaration, in the rclcpp part of the base
    location = result.drift[0].location
    assert location is not None and location.file.endswith(os.path.join('rclcpp', 'node.nodl.yaml'))
    assert (result.drift[0].file, result.drift[0].line) == (location.file, location.line)
    default = check_node(full.fqn, path, timeout=15)
    assert default.conforms
    assert default.client_library == ('rclpy', 'the default; choose with --client-library')


def test_load_definition_returns_the_resolved_node(described) -> None:
    from nodl.system import EntityKind, Provider, ResolvedNode

    path, _ = described
    resolved = load_definition(path)
    assert isinstance(resolved, ResolvedNode)
    rosout = resolved.entity(EntityKind.PUBLISHER, '/rosout')
    assert rosout.provider is Provider.CLIENT_LIBRARY
    assert all(e.layer == 'main' for e in resolved.implementation_entities())


# -- coded diagnostics: locations and overrides -------------------------------------------------


def _line_of(path: Path, text: str) -> int:
    """The 1-based number of the only line of ``path`` that contains ``text``."""
    found = [n for n, line in enumerate(path.read_text(encoding='utf-8').splitlines(), 1)
             if text in line]
    assert len(found) == 1, (text, found)
    return found[0]


def test_drift_diagnostics_point_at_the_declarations(edited: CheckResult) -> None:
    from nodl.diagnostics import Severity

    path = Path(edited.definition)
    by_kind = {d.kind: d for d in edited.differences
               if d.kind != 'unverifiable'}
    assert {k: d.code for k, d in by_kind.items()} == {
        'extra': 'NODL402', 'missing': 'NODL401', 'type': 'NODL403', 'qos': 'NODL404',
        'parameter_type': 'NODL405', 'read_only': 'NODL406', 'value': 'NODL407'}
    # an endpoint: its list item; a parameter: its key; an extra entity: main's section
    assert (by_kind['type'].file, by_kind['type'].line) == \
        (str(path), _line_of(path, 'name: /emergency_stop'))
    assert (by_kind['missing'].file, by_kind['missing'].line) == \
        (str(path), _line_of(path, 'name: ~/odom'))
    assert (by_kind['parameter_type'].file, by_kind['parameter_type'].line) == \
        (str(path), _line_of(path, '    rate:'))
    assert by_kind['parameter_type'].column == 5
    assert (by_kind['extra'].file, by_kind['extra'].line) == \
        (str(path), _line_of(path, '  subscriptions:'))
    assert by_kind['value'].severity is Severity.WARNING
    assert all(d.line > 0 and d.column > 0 for d in edited.diagnostics)
    for difference, diagnostic in zip(edited.differences, edited.diagnostics, strict=True):
        in_base = (difference.layer or '').startswith('base:')
        assert (diagnostic.file == str(path)) is not in_base, diagnostic


def test_drift_in_a_mixin_and_an_override_are_located_in_their_layers(full: NodeProcess) -> None:
    located = FIXTURES / 'live' / 'located'
    path, mixin = located / 'full_located.nodl.yaml', located / 'full_mixin.nodl.yaml'
    result = check_node(full.fqn, path, timeout=15)
    found = {(d.kind, d.name): d for d in result.differences
             if d.kind != 'unverifiable'}
    assert sorted(found) == [('extra', '/chk/measurement'), ('missing', '/chk/full/heartbeat'),
                             ('value', 'gain')]
    missing = found[('missing', '/chk/full/heartbeat')]
    assert (Path(missing.file), missing.line) == (mixin, _line_of(mixin, 'name: ~/heartbeat'))
    assert missing.layer == 'full_mixin.nodl.yaml'
    assert 'declared in full_mixin.nodl.yaml' in missing.headline()
    value = found[('value', 'gain')]
    assert (Path(value.file), value.line) == (path, _line_of(path, '    gain:'))
    assert [(Path(f), line, text) for f, line, _, text in value.related] == [
        (mixin, _line_of(mixin, '  gain:'), 'overrides the declaration in full_mixin.nodl.yaml')]
    extra = found[('extra', '/chk/measurement')]
    assert (Path(extra.file), extra.line) == (path, _line_of(path, '  publishers:'))


def test_overrides_decide_conformance(edited: CheckResult) -> None:
    from nodl.overrides import Overrides

    drift_codes = ['NODL401', 'NODL402', 'NODL403', 'NODL404', 'NODL405', 'NODL406']
    quiet = edited.with_overrides(Overrides(ignore=drift_codes))
    assert quiet.conforms and quiet.drift == []
    assert len(quiet.ignored) == 6 and not edited.ignored  # the original is unchanged
    assert [d.kind for d in quiet.differences if d.severity == 'warning'] == ['value']
    assert '6 ignored' in format_check_text(quiet).splitlines()[-1]
    assert json.loads(_json(quiet))['ignored'] == 6
    # a promoted warning is drift; the command line (stronger) wins over what came before
    strict = quiet.with_overrides(Overrides(error=['NODL407']))
    assert not strict.conforms
    assert [(d.kind, d.severity, d.code) for d in strict.drift] == [('value', 'error', 'NODL407')]
    assert strict.diagnostics[[d.kind for d in strict.differences].index('value')].severity.value \
        == 'error'
    assert re.fullmatch(r'/chk/full drifts from .*: 1 difference '
                        r'\((\d+ unverifiable, listed with -v; )?6 ignored\)',
                        format_check_text(strict).splitlines()[-1])
    assert not edited.with_overrides(Overrides(ignore=drift_codes[:5])).conforms


def test_unverifiable_fails_only_when_promoted(full: NodeProcess, described) -> None:
    from nodl.overrides import Overrides

    path, _ = described
    result = check_node(full.fqn, path, timeout=15, overrides=Overrides(error=['NODL408']))
    unverifiable = [d for d in result.differences if d.kind == 'unverifiable']
    assert unverifiable  # what the description writes as SYSTEM_DEFAULT cannot be compared
    assert not result.conforms and result.drift == unverifiable
    assert result.with_overrides(Overrides(ignore=['NODL408'])).conforms
