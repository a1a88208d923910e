"""The nodl.generators extension point, default names, and writing generated files."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl.generate import (
    GeneratedFile,
    GenerateOptions,
    GenerationError,
    GeneratorExtension,
    check_options,
    default_class_name,
    default_node_name,
    generate,
    load_generators,
    write_files,
)
from nodl.plugins import EXTENSION_POINTS
from nodl.targets import resolve_target
from nodl.writing import WriteError

FIXTURES = Path(__file__).parent / 'fixtures' / 'generate'


def test_generators_are_extensions_by_language() -> None:
    assert EXTENSION_POINTS['nodl.generators'].base_class() is GeneratorExtension
    generators = load_generators()
    assert generators['python'].CLIENT_LIBRARY == 'rclpy'
    assert isinstance(generators['python'], GeneratorExtension)


def test_an_unknown_language_is_a_generation_error() -> None:
    node = resolve_target(str(FIXTURES / 'talker.nodl.yaml')).node
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


def test_write_files_writes_changes_only(tmp_path: Path) -> None:
    files = [GeneratedFile('a/b.py', 'one\n'), GeneratedFile('c.py', 'two\n')]
    assert write_files(files, str(tmp_path), check=True) == [str(tmp_path / 'a/b.py'), str(tmp_path / 'c.py')]
    assert not (tmp_path / 'c.py').exists()
    assert len(write_files(files, str(tmp_path))) == 2
    assert write_files(files, str(tmp_path)) == []  # the same: not touched
    marked = (tmp_path / 'c.py').read_text()
    assert marked.startswith('# nodl: generated; sha256=') and marked.endswith('\ntwo\n')
    (tmp_path / 'c.py').write_text('changed\n')  # the user's now: no marker
    with pytest.raises(WriteError) as refused:
        write_files(files, str(tmp_path))
    assert refused.value.diagnostic.code == 'NODL031'
    assert (tmp_path / 'c.py').read_text() == 'changed\n'
    assert write_files(files, str(tmp_path), force=True) == [str(tmp_path / 'c.py')]
    assert (tmp_path / 'c.py').read_text() == marked


def test_write_files_refuses_edited_files_before_writing_any(tmp_path: Path) -> None:
    files = [GeneratedFile('a.py', 'one\n'), GeneratedFile('b.py', 'two\n')]
    write_files(files, str(tmp_path))
    (tmp_path / 'b.py').write_text((tmp_path / 'b.py').read_text() + '# my fix\n')
    newer = [GeneratedFile('a.py', 'uno\n'), GeneratedFile('b.py', 'dos\n')]
    assert write_files(newer, str(tmp_path), check=True) == [str(tmp_path / 'a.py'), str(tmp_path / 'b.py')]
    with pytest.raises(WriteError) as refused:
        write_files(newer, str(tmp_path))
    assert refused.value.diagnostic.code == 'NODL032'
    assert refused.value.diagnostic.file == str(tmp_path / 'b.py')
    assert (tmp_path / 'a.py').read_text().endswith('\none\n')  # nothing written
    assert (tmp_path / 'b.py').read_text().endswith('# my fix\n')


@pytest.mark.parametrize('path', ['../escape.py', '/tmp/absolute.py', 'a/../../escape.py', '.', ''])
def test_write_files_never_writes_outside_the_folder(tmp_path: Path, path: str) -> None:
    out = tmp_path / 'out'
    with pytest.raises(WriteError) as refused:
        write_files([GeneratedFile(path, 'x = 1\n')], str(out))
    assert refused.value.diagnostic.code == 'NODL708'
    assert not (tmp_path / 'escape.py').exists() and not out.exists()


@pytest.mark.parametrize(('options', 'language', 'wrong'), [
    (GenerateOptions('Talker', '../talker'), 'python', '--node-name'),
    (GenerateOptions('Talker', 'my node'), 'cpp', '--node-name'),
    (GenerateOptions('Talker', ''), 'python', '--node-name'),
    (GenerateOptions('Talker(object): pass\nimport os\nclass X', 'talker'), 'python', '--class-name'),
    (GenerateOptions('None', 'talker'), 'python', '--class-name'),
    (GenerateOptions('class', 'talker'), 'cpp', '--class-name'),
    (GenerateOptions('Tälker', 'talker'), 'cpp', '--class-name'),
    (GenerateOptions('Talker', 'talker', namespace='a::int'), 'cpp', '--namespace'),
    (GenerateOptions('Talker', 'talker', namespace='a; b'), 'cpp', '--namespace'),
])
def test_check_options_refuses_what_is_not_a_name(options: GenerateOptions, language: str,
                                                  wrong: str) -> None:
    problems = check_options(options, language)
    assert [d.code for d in problems] == ['NODL707']
    assert problems[0].message.startswith(wrong)


def test_check_options_accepts_names() -> None:
    assert check_options(GenerateOptions('Talker', 'talker', namespace='demo::nodes'), 'cpp') == []
    assert check_options(GenerateOptions('class_', 'for_'), 'python') == []
