"""nodl_schema.extract.targets: packages, entry points (setup.py, setup.cfg), output paths."""

from __future__ import annotations

from pathlib import Path

from nodl_schema.extract.targets import extract_paths, find_packages, output_paths, read_python_build

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
    from nodl_schema.extract.model import ExtractedNode, Extraction, Location
    from nodl_schema.extract.targets import nodes_file_text, registrations

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
