"""nodl.extract.targets: packages, entry points (setup.py, setup.cfg), output paths."""

from __future__ import annotations

from pathlib import Path

from nodl.extract.targets import extract_paths, find_packages, output_paths, read_python_build

PKG = Path(__file__).parent / 'fixtures' / 'extract' / 'python' / 'pkg'


def test_setup_py_entry_points_name_the_executables() -> None:
    package = read_python_build(str(PKG / 'demo_pkg'))
    assert package is not None and package.name == 'demo_pkg'
    assert {k: (Path(v[0]).name, v[1]) for k, v in package.executables.items()} == {
        'talker': ('talker.py', 'main'), 'loud_talker': ('talker.py', 'main'), 'pair': ('pair.py', 'main')}


def test_each_executable_gets_the_nodes_its_main_starts() -> None:
    extraction = extract_paths([str(PKG)])
    found = sorted((n.executable or '', n.name) for n in extraction.nodes)
    assert found == [('', 'Unused'), ('loud_talker', 'Talker'), ('pair', 'Talker'), ('pair', 'pair_server'),
                     ('talker', 'Talker')]
    unused = next(n for n in extraction.nodes if n.name == 'Unused')
    assert [d.code for d in unused.notes] == ['NODL911']
    paths = sorted(output_paths(extraction).values())
    assert paths == ['demo_pkg/Unused.nodl.yaml', 'demo_pkg/loud_talker.nodl.yaml',
                     'demo_pkg/pair__pair_server.nodl.yaml', 'demo_pkg/pair__talker.nodl.yaml',
                     'demo_pkg/talker.nodl.yaml']


def test_setup_cfg_and_generate_parameter_module(tmp_path: Path) -> None:
    (tmp_path / 'setup.cfg').write_text('[metadata]\nname = cfg_pkg\n[options.entry_points]\nconsole_scripts =\n'
                                        '    run = cfg_pkg.node:main\n', encoding='utf-8')
    (tmp_path / 'setup.py').write_text(
        'from generate_parameter_library_py.setup_helper import generate_parameter_module\n'
        'generate_parameter_module("node_parameters", "cfg_pkg/params.yaml")\n', encoding='utf-8')
    package = read_python_build(str(tmp_path))
    assert package is not None and package.name == 'cfg_pkg'
    assert list(package.executables) == ['run']
    assert package.genparam == {'cfg_pkg.node_parameters': str(tmp_path / 'cfg_pkg' / 'params.yaml')}


def test_unreadable_paths_and_no_node(tmp_path: Path) -> None:
    packages, problems = find_packages([str(tmp_path / 'missing')])
    assert not packages and [d.code for d in problems] == ['NODL020']
    (tmp_path / 'plain.py').write_text('print(1)\n', encoding='utf-8')
    assert [d.code for d in extract_paths([str(tmp_path)]).diagnostics] == ['NODL912']


def test_registrations_record_components_and_node_names() -> None:
    from nodl.extract.model import ExtractedNode, Extraction
    from nodl.extract.targets import nodes_file_text, registrations
    from nodl.location import Location

    ours = ExtractedNode('pkg::Talker', Location('t.cpp', 3, 1), 'cpp', package='pkg', plugin='pkg::Talker',
                         node_name='talker')
    other = ExtractedNode('vendor::Camera', Location('c.cpp', 5, 1), 'cpp', package='pkg', executable='cam',
                          plugin='vendor::Camera', node_name='camera')
    loose = ExtractedNode('n', Location('n.py', 1, 1), 'python', node_name='n')
    tables, notes = registrations(Extraction(nodes=[ours, other, loose]))
    assert tables == {'pkg': {'talker': {'plugin': 'pkg::Talker', 'node_name': 'talker'},
                              'cam': {'node_name': 'camera'}}}
    assert [(d.code, d.file, d.line) for d in notes] == [('NODL961', 'c.cpp', 5)]
    assert 'talker:\n  node_name: talker\n  plugin: pkg::Talker\n' in nodes_file_text('pkg', tables['pkg'])


BASES = Path(__file__).parent / 'fixtures' / 'extract' / 'packages' / 'base_pkg'


def _by_executable(extraction):  # type: ignore[no-untyped-def]
    return {n.executable: n for n in extraction.nodes if n.executable}


def _entities(node):  # type: ignore[no-untyped-def]
    return [(e.section, e.name, e.type, Path(e.location.file).name, e.location.line, e.complete)
            for e in node.entities]


def test_a_base_in_another_module_of_the_package_gives_its_entities() -> None:
    nodes = _by_executable(extract_paths([str(BASES)]))
    base = [('parameters', 'rate', 'double', 'base.py', 18, True),
            ('service_servers', '~/reset', 'std_srvs/srv/Trigger', 'base.py', 20, True)]
    talker = nodes['talker']  # from .base import SensorBase
    assert (talker.name, talker.base, talker.node_name) == ('Talker', 'node', 'talker')
    assert _entities(talker) == [  # the base's first, where the base creates them; the class's own after
        base[0], ('publishers', 'talker_status', 'std_msgs/msg/String', 'base.py', 19, True), base[1],
        ('publishers', 'chatter', 'std_msgs/msg/String', 'talker.py', 14, True)]
    # the base's publisher is named by the class's constant (TOPIC), as at run time
    assert talker.sources == [str(BASES / 'base_pkg' / 'talker.py'), str(BASES / 'base_pkg' / 'base.py')]
    status = ('publishers', 'status', 'std_msgs/msg/String', 'base.py', 19, True)
    counter = nodes['counter']  # import base_pkg.base as b; class Counter(b.SensorBase)
    assert _entities(counter) == [base[0], status, base[1],
                                  ('subscriptions', 'count', 'std_msgs/msg/String', 'counter.py', 12, True)]
    relay = nodes['relay']  # from base_pkg import SensorBase (re-exported by the package's __init__)
    assert _entities(relay) == [base[0], status, base[1]]
    assert relay.node_name is None  # its base's __init__ takes the name as an argument: not guessed
    deep = nodes['deep']  # from ..base import SensorBase, two folders down
    assert _entities(deep)[-1] == ('publishers', 'echo', 'std_msgs/msg/String', 'deep.py', 12, True)
    assert _entities(deep)[:3] == [base[0], status, base[1]]
    managed = nodes['managed']  # a lifecycle base of another module: its kind, and the name it gives
    assert (managed.base, managed.node_name) == ('lifecycle_node', 'managed')
    assert _entities(managed) == [('parameters', 'period', 'double', 'base.py', 32, True),
                                  ('publishers', 'out', 'std_msgs/msg/String', 'managed.py', 11, True)]
    for node in (talker, counter, relay, deep, managed):
        assert not any(d.code == 'NODL960' for d in node.notes), node.name


def test_a_base_not_in_the_package_sources_is_one_located_gap() -> None:
    extraction = extract_paths([str(BASES)])
    orphan = _by_executable(extraction)['orphans']  # from .missing import GoneBase: no such module
    (note,) = orphan.notes
    assert (note.code, Path(note.file).name, note.line, note.column) == ('NODL960', 'orphans.py', 10, 1)
    assert "base GoneBase (imported from base_pkg.missing), which is not found in the package's sources" \
        in note.message
    assert _entities(orphan) == [('publishers', 'own', 'std_msgs/msg/String', 'orphans.py', 13, True)]
    stranger = next(n for n in extraction.nodes if n.name == 'Stranger')  # a base of another package
    assert [d.code for d in stranger.notes] == ['NODL960', 'NODL911'] and stranger.entities == []
    assert 'ExternalBase (imported from other_pkg.nodes)' in stranger.notes[0].message


def test_a_base_module_is_read_once_more_at_most(tmp_path: Path) -> None:
    """A module is kept parsed only while it is needed: a base module read for another module
    before its own turn is not read again; one whose turn is past is read once more (not once
    per node class derived from it)."""
    import shutil

    from nodl.extract import python

    package = tmp_path / 'base_pkg'
    shutil.copytree(BASES, package)
    reads: list[str] = []
    real = python.read_source

    def counting(path: str):  # type: ignore[no-untyped-def]
        reads.append(Path(path).name)
        return real(path)

    python.read_source = counting  # type: ignore[assignment]
    try:
        extract_paths([str(package)])
    finally:
        python.read_source = real  # type: ignore[assignment]
    from collections import Counter

    assert Counter(reads) == {**{p.name: 1 for p in package.rglob('*.py')},  # setup.py too
                              '__init__.py': 3, 'base.py': 2}  # two __init__.py: the package's read twice


def test_a_package_s_entities_the_validator_refuses_are_gaps(tmp_path: Path) -> None:
    """The validator's checks run once every file of the package is read: an invalid name the
    source fixes is still a gap (NODL914), in every module."""
    pkg = tmp_path / 'bad_pkg'
    (pkg / 'bad_pkg').mkdir(parents=True)
    (pkg / 'setup.py').write_text("from setuptools import setup\nsetup(name='bad_pkg')\n")
    node = ('from rclpy.node import Node\nfrom std_msgs.msg import String\n\n\nclass {0}(Node):\n'
            '    def __init__(self):\n        super().__init__("{1}")\n'
            '        self.create_publisher(String, "{2}", 10)\n')
    (pkg / 'bad_pkg' / 'a.py').write_text(node.format('A', 'a', 'bad name!'))
    (pkg / 'bad_pkg' / 'b.py').write_text(node.format('B', 'b', 'good'))
    (pkg / 'bad_pkg' / 'c.py').write_text(node.format('C', 'c', '2bad'))
    gaps = {n.name: [g.code for g in n.gaps] for n in extract_paths([str(pkg)]).nodes}
    assert gaps == {'A': ['NODL914'], 'B': [], 'C': ['NODL914']}


def test_an_extraction_leaves_no_reference_cycle() -> None:
    """Each module's tree is freed as soon as the module is read: nothing the extraction makes
    refers to itself (a cycle would keep trees alive until the collector finds them, and slow
    every extraction that follows)."""
    import gc

    extract_paths([str(BASES)])  # imports done, caches warm
    gc.collect()
    gc.set_debug(gc.DEBUG_SAVEALL)
    try:
        extract_paths([str(BASES)])
        extract_paths([str(PKG)])
        gc.collect()
        assert gc.garbage == []
    finally:
        gc.set_debug(0)
        gc.garbage.clear()
