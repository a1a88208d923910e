"""nodl.extract.python: rclpy nodes read with ast, checked against hand-checked expectations
of real public nodes, against the live description of the test nodes running, and on bad input."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from nodl.extract.python import MAX_SOURCE_BYTES, extract_file, extract_source

FIXTURES = Path(__file__).parent / 'fixtures' / 'extract' / 'python'
REAL = FIXTURES / 'real'
CASES = FIXTURES / 'cases'
NODES = Path(__file__).parent / 'nodes'


def _summary(node):  # type: ignore[no-untyped-def]
    out = []
    for e in node.entities:
        entry = {'section': e.section, 'name': e.name, 'type': e.type, 'line': e.location.line}
        if e.qos is not None:
            entry['qos'] = e.qos.to_dict()
        if e.is_parameter and e.has_default:
            entry['default_value'] = e.default_value
        if e.gaps:
            entry['gap'] = sorted({g.what for g in e.gaps})
        out.append(entry)
    return {'base': node.base, 'entities': out}


@pytest.mark.parametrize('source', sorted(REAL.glob('*.py')), ids=lambda p: p.stem)
def test_real_nodes_match_their_hand_checked_expectation(source: Path) -> None:
    expected = yaml.safe_load((REAL / f'{source.stem}.expected.yaml').read_text(encoding='utf-8'))['nodes']
    extraction = extract_file(str(source))
    assert not extraction.diagnostics
    assert {n.name: _summary(n) for n in extraction.nodes} == expected


def test_the_real_node_fixtures_note_origin_and_licence() -> None:
    readme = (REAL / 'README.md').read_text(encoding='utf-8')
    sources = sorted(REAL.glob('*.py'))
    assert len(sources) >= 10
    for source in sources:
        assert f'| {source.name} |' in readme
        assert 'Licensed under the Apache License' in source.read_text(encoding='utf-8')


def _node(extraction, name):  # type: ignore[no-untyped-def]
    return next(n for n in extraction.nodes if n.name == name)


def _entity(node, section, name):  # type: ignore[no-untyped-def]
    return next(e for e in node.entities if e.section == section and e.name == name)


def test_constants_helpers_and_descriptors_are_resolved() -> None:
    extraction = extract_file(str(CASES / 'constants_node.py'))
    driver = _node(extraction, 'Driver')
    assert driver.base == 'lifecycle_node' and driver.node_name == 'driver'
    scan = _entity(driver, 'publishers', '/robot/scan')  # an f-string of module constants
    assert scan.qos is not None and scan.qos.to_dict() == {
        'history': 'KEEP_LAST', 'reliability': 'BEST_EFFORT', 'depth': 5, 'durability': 'VOLATILE'}
    imu = _entity(driver, 'publishers', '~/imu')  # a helper of the module; a class attribute as depth
    assert imu.qos is not None and imu.qos.depth == 7
    assert _entity(driver, 'service_servers', '~/reset').type == 'std_srvs/srv/Trigger'
    assert _entity(driver, 'subscriptions', 'imu_in').qos.history == 'SYSTEM_DEFAULT'  # type: ignore[union-attr]
    frame = _entity(driver, 'parameters', 'frame_id')  # an instance attribute set once
    assert (frame.type, frame.default_value, frame.read_only) == ('string', 'laser', True)
    gain = _entity(driver, 'parameters', 'gain')
    assert gain.validation == {'bounds<>': [0.0, 2.0]}
    assert _entity(driver, 'parameters', 'limits.max').type == 'double'


def test_helpers_of_other_packages_make_their_entities() -> None:
    driver = _node(extract_file(str(CASES / 'constants_node.py')), 'Driver')
    helpers = {(e.section, e.name, e.helper) for e in driver.entities if e.helper}
    assert helpers == {
        ('subscriptions', '/tf', 'tf2_ros.TransformListener'),
        ('subscriptions', '/tf_static', 'tf2_ros.TransformListener'),
        ('publishers', '/tf', 'tf2_ros.TransformBroadcaster'),
        ('publishers', '/diagnostics', 'diagnostic_updater.Updater'),
        ('parameters', 'diagnostic_updater.period', 'diagnostic_updater.Updater'),
        ('subscriptions', 'imu_sync', 'message_filters.Subscriber'),
    }
    static = _entity(driver, 'subscriptions', '/tf_static')
    assert static.qos is not None and static.qos.durability == 'TRANSIENT_LOCAL'
    assert _entity(driver, 'parameters', 'diagnostic_updater.period').default_value == 2.0


def test_a_name_from_a_parameter_is_a_located_gap_never_a_guess() -> None:
    extraction = extract_file(str(CASES / 'constants_node.py'))
    driver = _node(extraction, 'Driver')
    gap = [e for e in driver.entities if e.section == 'publishers' and e.name is None]
    assert len(gap) == 1 and gap[0].type == 'sensor_msgs/msg/Imu'
    diagnostic = gap[0].gaps[0].diagnostic()
    assert (diagnostic.code, diagnostic.line, diagnostic.column) == ('NODL901', 41, 36)
    assert "parameter 'output'" in diagnostic.message
    helper_user = _node(extraction, 'helper_user')  # a node made in main(), given to a helper
    assert [e.name for e in helper_user.entities] == ['/map/clear', None]
    assert helper_user.entities[1].gaps[0].code == 'NODL901'


def test_image_transport_and_starred_arguments_are_gaps() -> None:
    text = ('import rclpy\nfrom rclpy.node import Node\nimport image_transport\n\n'
            'class Cam(Node):\n    def __init__(self, args):\n        super().__init__("cam")\n'
            '        self.pub = image_transport.Publisher(self, "image")\n'
            '        self.create_publisher(*args)\n')
    node = extract_source(text, 'cam.py').nodes[0]
    codes = sorted(g.code for g in node.gaps)
    assert codes == ['NODL909', 'NODL910']
    assert all(e.name is None for e in node.entities)


def test_generate_parameter_library_listener_reads_its_yaml(tmp_path: Path) -> None:
    (tmp_path / 'params.yaml').write_text(
        'turtle:\n  speed:\n    type: double\n    default_value: 1.5\n    description: How fast.\n',
        encoding='utf-8')
    text = ('from rclpy.node import Node\nfrom turtle_pkg.turtle_parameters import turtle\n\n'
            'class T(Node):\n    def __init__(self):\n        super().__init__("t")\n'
            '        self.listener = turtle.ParamListener(self)\n')
    found = extract_source(text, 't.py', genparam={'turtle_pkg.turtle_parameters': str(tmp_path / 'params.yaml')})
    speed = found.nodes[0].entities[0]
    assert (speed.name, speed.type, speed.default_value) == ('speed', 'double', 1.5)
    missing = extract_source(text, 't.py').nodes[0].gaps
    assert [g.code for g in missing] == ['NODL915']


@pytest.mark.parametrize(('name', 'code', 'line'), [
    ('syntax_error.py', 'NODL906', 1), ('latin1.py', 'NODL907', 1), ('generated.py', 'NODL908', 1)])
def test_bad_input_is_one_located_diagnostic(name: str, code: str, line: int) -> None:
    extraction = extract_file(str(CASES / name))
    assert [(d.code, d.line) for d in extraction.diagnostics] == [(code, line)]
    assert not extraction.nodes


def test_huge_and_deeply_nested_files_are_one_diagnostic(tmp_path: Path) -> None:
    huge = tmp_path / 'huge.py'
    with open(huge, 'wb') as handle:
        handle.truncate(MAX_SOURCE_BYTES + 1)
    assert [d.code for d in extract_file(str(huge)).diagnostics] == ['NODL907']
    deep = extract_source('x = ' + '(' * 300 + '1' + ')' * 300 + '\n' * 2 + 'y = ' + '[' * 5000 + ']' * 5000,
                          'deep.py')
    assert [d.code for d in deep.diagnostics] == ['NODL906']


def test_nothing_is_imported_or_run(tmp_path: Path) -> None:
    marker = tmp_path / 'ran'
    text = (f'open({str(marker)!r}, "w").close()\nfrom rclpy.node import Node\n'
            'class N(Node):\n    def __init__(self):\n        super().__init__("n")\n')
    assert extract_source(text, 'n.py').nodes[0].node_name == 'n'
    assert not marker.exists()


# -- the live comparison: every test node, running, against its extraction ----------------------

def _expand(name: str, node: str, namespace: str) -> str:
    from nodl.naming import expand

    return expand(name, node, namespace)


#: script -> (node names to start it with, extracted node for each).
LIVE = {
    'full_node.py': ('x_full', 'node'),
    'plain_node.py': ('x_plain', 'node'),
    'lifecycle_node.py': ('x_life', 'node'),
    'dying_node.py': ('x_dying', 'node'),
}


@pytest.mark.parametrize('script', sorted(LIVE))
def test_live_entities_are_extracted_or_located_gaps(ros_node, script: str) -> None:  # type: ignore[no-untyped-def]
    from nodl.live.describe import describe_node

    name, extracted_name = LIVE[script]
    args = ('--lifetime', '20') if script == 'dying_node.py' else ()
    process = ros_node(script, name, '/', *args)
    live = describe_node(process.fqn, timeout=15).node
    node = _node(extract_file(str(NODES / script)), extracted_name)
    assert live.base is not None and live.base.value == node.base
    _compare(live.main, node, name, '/')


def _compare(live, node, name: str, namespace: str) -> None:  # type: ignore[no-untyped-def]
    from nodl.model.interface import ENDPOINT_SECTIONS

    complete = {(e.section, _expand(e.name, name, namespace) if not e.is_parameter else e.name): e
                for e in node.entities if e.complete}
    gaps = {e.section for e in node.entities if not e.complete}
    observed = {('parameters', k): p for k, p in (live.parameters or {}).items()}
    for section in ENDPOINT_SECTIONS:
        for endpoint in getattr(live, section) or []:
            observed[(section, _expand(endpoint.name, name, namespace))] = endpoint
    for key, entity in complete.items():  # precision: nothing extracted is absent live
        assert key in observed, f'extracted but not live: {key}'
        assert observed[key].type == entity.type, key
    for key in observed:  # every live entity extracted, or its section has a located gap
        assert key in complete or key[0] in gaps, f'live but neither extracted nor a gap: {key}'
    for entity in node.entities:
        for gap in entity.gaps:
            assert gap.location.line > 0


def test_live_action_nodes_with_a_name_computed_at_run_time(ros_node) -> None:  # type: ignore[no-untyped-def]
    from nodl.live.describe import describe_node

    server = ros_node('action_nodes.py', 'x_act')
    extraction = extract_file(str(NODES / 'action_nodes.py'))
    live_server = describe_node(server.fqn, timeout=15).node
    _compare(live_server.main, _node(extraction, 'server'), 'x_act', '/')
    live_client = describe_node('/x_act_client', timeout=15).node
    client = _node(extraction, 'client')
    _compare(live_client.main, client, 'x_act_client', '/')
    assert [g.code for g in client.gaps] == ['NODL901']  # f'{args.name}/fibonacci'


def test_live_example_node_matches_its_extraction() -> None:
    import subprocess
    import sys

    from nodl.live.describe import describe_node

    example = Path(__file__).parent.parent / 'examples' / 'nodes' / 'laser_driver_node.py'
    node = _node(extract_file(str(example)), 'LaserDriver')
    assert node.node_name == 'laser_driver_node'
    # started from its own file: it takes no --name, its name is its constant
    process = subprocess.Popen([sys.executable, str(example)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    try:
        assert process.stdout is not None and process.stdout.readline().strip() == 'ready'
        live = describe_node('/laser_driver_node', timeout=15).node
        _compare(live.main, node, 'laser_driver_node', '/')
    finally:
        process.terminate()
        process.wait(timeout=10)
        for stream in (process.stdout, process.stderr):
            if stream is not None:
                stream.close()


# -- nodes whose interface the source does not hold: one located gap, never silence -----------------

GENERATE = Path(__file__).parent / 'fixtures' / 'generate'


def _whole_gap(node):  # type: ignore[no-untyped-def]
    (note,) = [d for d in node.notes if d.code == 'NODL960']
    assert note.line > 0 and note.column > 0
    return note


def _compare_opaque(live, node, name: str) -> None:  # type: ignore[no-untyped-def]
    """Nothing extracted is absent live; every live entity is covered by the node's one gap."""
    from nodl.model.interface import ENDPOINT_SECTIONS

    observed = {('parameters', k) for k in (live.parameters or {})}
    for section in ENDPOINT_SECTIONS:
        observed |= {(section, _expand(e.name, name, '/')) for e in getattr(live, section) or []}
    assert observed  # the node has an interface, and the extraction says it does not hold it
    for entity in node.entities:
        if entity.complete:
            key = (entity.section, _expand(entity.name, name, '/') if not entity.is_parameter else entity.name)
            assert key in observed, f'extracted but not live: {key}'


def test_live_generated_node_is_one_gap_at_its_class(ros_node, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    import shutil

    from nodl.live.describe import describe_node

    shutil.copy(GENERATE / 'python' / 'talker_base.py', tmp_path / 'talker_base.py')
    process = ros_node('generated_node.py', 'x_gen', '/', '--module-dir', str(tmp_path), '--kind', 'talker')
    live = describe_node(process.fqn, timeout=15).node
    extraction = extract_file(str(NODES / 'generated_node.py'))
    assert sorted(n.name for n in extraction.nodes) == ['Camera', 'Everything', 'Talker']
    talker = _node(extraction, 'Talker')
    note = _whole_gap(talker)
    assert (note.line, note.column) == (22, 5) and 'module.TalkerBase' in note.message
    assert live.base is not None and live.base.value == talker.base
    _compare_opaque(live.main, talker, 'x_gen')


def test_live_runtime_node_is_one_gap_at_its_making(ros_node) -> None:  # type: ignore[no-untyped-def]
    from nodl.live.describe import describe_node

    process = ros_node('runtime_node.py', 'x_rt', '/', '--definition', str(GENERATE / 'talker.nodl.yaml'),
                       '--kind', 'talker')
    live = describe_node(process.fqn, timeout=15).node
    extraction = extract_file(str(NODES / 'runtime_node.py'))
    assert sorted((n.name, n.base) for n in extraction.nodes) == [
        ('Camera', 'lifecycle_node'), ('Everything', 'node'), ('node', 'node')]
    made = _node(extraction, 'node')  # NodlNode(definition, name, ...) in build()
    note = _whole_gap(made)
    assert note.line == 40 and 'NodlNode reads when it starts (definition)' in note.message
    _compare_opaque(live.main, made, 'x_rt')


def test_a_class_of_an_unknown_base_is_a_node_only_when_it_acts_as_one() -> None:
    text = ('import rclpy\nfrom helpers import Mixin, TalkerBase\n\n\nclass Plain(Mixin):\n    pass\n\n\n'
            'class Talker(TalkerBase):\n    pass\n\n\nclass Worker(Mixin):\n'
            '    def on_configure(self, state):\n        return super().on_configure(state)\n')
    found = {n.name: [d.code for d in n.notes] for n in extract_source(text, 'x.py').nodes}
    assert found == {'Talker': ['NODL960'], 'Worker': ['NODL960']}


PACKAGES = Path(__file__).parent / 'fixtures' / 'extract' / 'packages'


def _sources(root: Path):  # type: ignore[no-untyped-def]
    from nodl.extract.python import PackageSources

    return PackageSources(str(root), [str(p) for p in sorted(root.rglob('*.py'))])


def test_package_sources_name_modules_and_find_bases_through_reexports() -> None:
    root = PACKAGES / 'base_pkg'
    sources = _sources(root)
    assert sources.path('base_pkg') == str(root / 'base_pkg' / '__init__.py')
    assert sources.path('base_pkg.nodes.deep') == str(root / 'base_pkg' / 'nodes' / 'deep.py')
    assert sources.path('setup') == str(root / 'setup.py') and sources.path('base_pkg.missing') is None
    alone = extract_file(str(root / 'base_pkg' / 'relay.py'), package='base_pkg')
    assert [d.code for d in _node(alone, 'Relay').notes] == ['NODL960']  # without the package: a gap
    relay = _node(extract_file(str(root / 'base_pkg' / 'relay.py'), package='base_pkg', sources=sources), 'Relay')
    assert [(e.name, Path(e.location.file).name) for e in relay.entities] == [
        ('rate', 'base.py'), ('status', 'base.py'), ('~/reset', 'base.py')] and relay.notes == []


def test_bases_of_each_other_across_modules_end(tmp_path: Path) -> None:
    pkg = tmp_path / 'loop_pkg'
    pkg.mkdir()
    (pkg / '__init__.py').write_text('')
    (pkg / 'a.py').write_text('from rclpy.node import Node\nfrom std_msgs.msg import String\n\n'
                              'from .b import B\n\n\nclass A(B, Node):\n    def __init__(self):\n'
                              '        self.create_publisher(String, self.topic, 1)\n')
    (pkg / 'b.py').write_text('from .a import A\n\n\nclass B(A):\n    pass\n')
    extraction = extract_file(str(pkg / 'a.py'), package='loop_pkg', sources=_sources(tmp_path))
    assert not extraction.diagnostics  # bases that are each other's (Python refuses them): no endless reading
    (node,) = extraction.nodes
    assert node.name == 'A' and [(e.name, [g.code for g in e.gaps]) for e in node.entities] == [
        (None, ['NODL901'])]


def test_live_node_of_a_base_in_another_module(ros_node) -> None:  # type: ignore[no-untyped-def]
    from nodl.live.describe import describe_node

    root = PACKAGES / 'base_pkg'
    process = ros_node('package_node.py', 'x_base', '/', '--root', str(root), '--module', 'base_pkg.talker',
                       '--class', 'Talker')
    live = describe_node(process.fqn, timeout=15).node
    node = _node(extract_file(str(root / 'base_pkg' / 'talker.py'), package='base_pkg', sources=_sources(root)),
                 'Talker')
    assert all(e.complete for e in node.entities) and len(node.entities) == 4
    assert live.base is not None and live.base.value == node.base
    _compare(live.main, node, 'x_base', '/')  # the base's entities live too, under the class's names


def test_a_byte_order_mark_is_not_counted_in_a_bad_byte_place(tmp_path: Path) -> None:
    source = tmp_path / 'bom.py'
    source.write_bytes(b'\xef\xbb\xbfimport rclpy\nname = "\xff"\n')
    (problem,) = extract_file(str(source)).diagnostics
    assert (problem.code, problem.line, problem.column) == ('NODL907', 2, 9)
    assert 'byte 0xff' in problem.message
    source.write_bytes(b'\xef\xbb\xbf' + (CASES / 'constants_node.py').read_bytes())
    assert [n.name for n in extract_file(str(source)).nodes] == [
        n.name for n in extract_file(str(CASES / 'constants_node.py')).nodes]
