"""The nodl.generators extension point, default names, and writing generated files."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl_schema.generate import (
    GeneratedFile, GenerateOptions, GenerationError, GeneratorExtension, default_class_name,
    default_node_name, generate, load_generators, write_files)
from nodl_schema.generate.definition import resolve_target, target_name
from nodl_schema.plugins import EXTENSION_POINTS

FIXTURES = Path(__file__).parent / 'fixtures' / 'generate'


def test_generators_are_extensions_by_language() -> None:
    assert EXTENSION_POINTS['nodl.generators'].base_class() is GeneratorExtension
    generators = load_generators()
    assert generators['python'].CLIENT_LIBRARY == 'rclpy'
    assert isinstance(generators['python'], GeneratorExtension)


def test_an_unknown_language_is_a_generation_error() -> None:
    node, _, _ = resolve_target(str(FIXTURES / 'talker.nodl.yaml'))
    assert node is not None

    class Echo(GeneratorExtension):
        LANGUAGE = 'echo'

        def generate(self, node, options):  # type: ignore[no-untyped-def]
            return [GeneratedFile('x.txt', options.class_name)]

    assert generate(node, 'echo', GenerateOptions('A', 'a'), {'echo': Echo()}) == [GeneratedFile('x.txt', 'A')]
    with pytest.raises(GenerationError, match="no generator for language 'cobol'"):
        generate(node, 'cobol', GenerateOptions('A', 'a'), {'echo': Echo()})


def test_default_names() -> None:
    assert default_node_name('dir/laser_driver.nodl.yaml') == 'laser_driver'
    assert default_node_name('camera.json') == 'camera'
    assert default_class_name('laser_driver.nodl.yaml') == 'LaserDriver'
    assert default_class_name('my-node') == 'MyNode'
    assert target_name(['pkg', 'exe']) == 'exe'


def test_write_files_writes_changes_only(tmp_path: Path) -> None:
    files = [GeneratedFile('a/b.py', 'one\n'), GeneratedFile('c.py', 'two\n')]
    assert write_files(files, str(tmp_path), check=True) == [str(tmp_path / 'a/b.py'), str(tmp_path / 'c.py')]
    assert not (tmp_path / 'c.py').exists()
    assert len(write_files(files, str(tmp_path))) == 2
    (tmp_path / 'c.py').write_text('changed\n')
    assert write_files(files, str(tmp_path)) == [str(tmp_path / 'c.py')]
    assert (tmp_path / 'c.py').read_text() == 'two\n'


def test_resolve_target_errors(tmp_path: Path) -> None:
    with pytest.raises(OSError):
        resolve_target(str(tmp_path / 'missing.nodl.yaml'))
    bad = tmp_path / 'bad.nodl.yaml'
    bad.write_text('nodl_version: 2\nbase: nope\nmain: {nodl_version: 2}\n')
    node, diagnostics, source = resolve_target(str(bad))
    assert node is None and diagnostics and source == str(bad)
