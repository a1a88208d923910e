"""Generated C++ is well-formed: libclang parses it against stand-in rclcpp headers with no error.

rclcpp is not installable here, so tests/fixtures/generate/cpp_stubs/ declares
the part of its API generated code uses (callback shapes checked by
static_assert); the message, service and action headers are the real ones
the ROS wheels install.  Each generated base is parsed together with its
user subclass (the stub ``nodl new`` writes), which instantiates the class:
an unimplemented pure virtual callback, a wrong callback signature, an
unknown type or a syntax error is a parse error.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import clang.cindex as clang  # the libclang package (test extra)
import pytest

from conftest import FIXTURES
from nodl.generate import GenerateOptions, default_class_name, default_node_name, write_files
from nodl.generate.cpp import generate_cpp, plan_cpp
from nodl.generate.cpp.user import render_user_source
from nodl.system import resolve_node

GENERATE = FIXTURES / 'generate'
STUBS = GENERATE / 'cpp_stubs'
#: The example definitions: a plain node, a lifecycle node, every entity kind and parameter
#: type, and parameters without validators (nothing may be left unused under -Wextra).
DEFINITIONS = [GENERATE / f'{name}.nodl.yaml'
               for name in ('talker', 'managed_camera', 'everything', 'unvalidated')]


def compiler_include_dir() -> str:
    """The C compiler's own headers (stddef.h, ...), which the libclang wheel does not ship."""
    for compiler in ('g++', 'c++', 'clang++', 'gcc', 'cc'):
        path = shutil.which(compiler)
        if path:
            out = subprocess.run([path, '-print-file-name=include'], capture_output=True,
                                 text=True, timeout=30).stdout.strip()
            if out and Path(out, 'stddef.h').is_file():
                return out
    raise AssertionError('no C/C++ compiler found: CMake builds need one too')


def parse_errors(source: Path, include: list[Path]) -> list[str]:
    venv_include = Path(sys.prefix) / 'include'
    args = ['-x', 'c++', '-std=c++17', '-Wall', '-Wextra', '-isystem', compiler_include_dir(),
            f'-I{STUBS}'] + [f'-I{p}' for p in include]
    args += [f'-isystem{p}' for p in sorted(venv_include.iterdir())
             if p.is_dir() and not p.name.startswith('python')]
    unit = clang.Index.create().parse(str(source), args=args)
    return [f'{d.location.file}:{d.location.line}:{d.location.column}: {d.spelling}'
            for d in unit.diagnostics if d.severity >= clang.Diagnostic.Warning]


def generate_into(definition: Path, out: Path, **extra: object) -> tuple[Path, Path]:
    node = resolve_node(definition, client_library='rclcpp')
    options = GenerateOptions(default_class_name(str(definition)),
                              default_node_name(str(definition)), **extra)  # type: ignore[arg-type]
    write_files(generate_cpp(node, options), str(out))
    plan = plan_cpp(node, options)
    user = out / f'{default_node_name(str(definition))}.cpp'
    user.write_text(render_user_source(plan, options.class_name), encoding='utf-8')
    return out / f'{plan.stem}.cpp', user


@pytest.mark.parametrize('definition', DEFINITIONS, ids=lambda p: p.name)
def test_generated_base_and_user_stub_parse_without_a_diagnostic(definition: Path,
                                                                 tmp_path: Path) -> None:
    base, user = generate_into(definition, tmp_path)
    assert parse_errors(base, [tmp_path]) == []
    assert parse_errors(user, [tmp_path]) == []


def test_the_examples_parse_too(tmp_path: Path) -> None:
    from conftest import REPO

    for definition in ('laser_driver.nodl.yaml', 'camera_lifecycle.nodl.yaml'):
        base, user = generate_into(REPO / 'examples' / definition, tmp_path)
        assert parse_errors(base, [tmp_path]) == []
        assert parse_errors(user, [tmp_path]) == []


def test_a_nested_namespace(tmp_path: Path) -> None:
    base, user = generate_into(GENERATE / 'managed_camera.nodl.yaml', tmp_path,
                               namespace='vision::camera')
    assert '#ifndef VISION__CAMERA__MANAGED_CAMERA_BASE_HPP_' in \
        (tmp_path / 'managed_camera_base.hpp').read_text(encoding='utf-8')
    assert parse_errors(base, [tmp_path]) == []
    assert parse_errors(user, [tmp_path]) == []


def test_a_component_subclass_registers(tmp_path: Path) -> None:
    _, user = generate_into(GENERATE / 'talker.nodl.yaml', tmp_path, component=True)
    user.write_text(user.read_text(encoding='utf-8') +
                    'RCLCPP_COMPONENTS_REGISTER_NODE(talker::Talker)\n', encoding='utf-8')
    assert parse_errors(user, [tmp_path]) == []


@pytest.mark.parametrize('breakage, expected', [
    # a callback of the wrong shape: the message as a mutable pointer
    (('[this](const std_msgs::msg::String::ConstSharedPtr & msg)',
      '[this](const std_msgs::msg::String::SharedPtr & msg)'), 'subscription callback'),
    # a QoS policy rclcpp does not have
    (('rclcpp::ReliabilityPolicy::Reliable', 'rclcpp::ReliabilityPolicy::Sometimes'), 'Sometimes'),
    # a parameter read as a type rclcpp cannot give
    (('get_value<double>()', 'get_value<float>()'), 'parameter value'),
])
def test_the_check_finds_broken_code(tmp_path: Path, breakage: tuple[str, str],
                                     expected: str) -> None:
    base, _ = generate_into(GENERATE / 'talker.nodl.yaml', tmp_path)
    text = base.read_text(encoding='utf-8')
    assert breakage[0] in text
    base.write_text(text.replace(breakage[0], breakage[1], 1), encoding='utf-8')
    errors = parse_errors(base, [tmp_path])
    assert any(expected in e for e in errors), errors


def test_a_missing_callback_implementation_is_found(tmp_path: Path) -> None:
    _, user = generate_into(GENERATE / 'everything.nodl.yaml', tmp_path)
    text = user.read_text(encoding='utf-8')
    start = text.index('  void on_in(')
    end = text.index('  }\n', start) + 4
    user.write_text(text[:start] + text[end:], encoding='utf-8')
    errors = parse_errors(user, [tmp_path])
    assert any('abstract' in e for e in errors), errors



def test_hostile_text_in_comments_and_literals_still_parses(tmp_path: Path) -> None:
    """Text holding control and bidi characters, trigraphs, comment ends and backslashes (as a
    running node's descriptors or an ignored check let through), written by the generator's
    comment and literal writers, holds none of them raw and libclang parses it as intended."""
    from nodl.generate.cpp.text import comment_lines, string_literal
    from nodl.text_safety import first_unsafe

    hostile = 'node \u202e */ ??/ \x1b[2J \x00 \x85 \u2066 end \\'
    source = '\n'.join(comment_lines(hostile) + [f'const char * text = {string_literal(hostile)};',
                                                  'int after = 1;']) + '\n'
    assert first_unsafe(source) == -1 and '??' not in source.split('\n')[0]
    path = tmp_path / 'hostile.cpp'
    path.write_text(source, encoding='utf-8')
    assert parse_errors(path, []) == []
    unit = clang.Index.create().parse(str(path), args=['-x', 'c++', '-std=c++14', '-trigraphs'])
    declared = [c.spelling for c in unit.cursor.get_children()]
    assert declared == ['text', 'after'] and not list(unit.diagnostics)


def test_a_whole_node_with_hostile_descriptions_parses(tmp_path: Path) -> None:
    """A node whose descriptions hold control and bidi characters, line separators, comment
    ends, trigraphs and backslashes (its validation errors NODL219/NODL220 bypassed, as a
    running node's descriptors would give them): the generated header, source and user stub
    hold none of them raw, and libclang parses them with no diagnostic."""
    from nodl.composition.resolved import resolve_report
    from nodl.loading import CheckedSource, check_source
    from nodl.text_safety import UNSAFE
    from nodl.validation.kinds import Kind

    definition = FIXTURES / 'scaffold' / 'hostile_text.nodl.yaml'
    path = tmp_path / 'hostile.nodl.yaml'
    path.write_text(definition.read_text(encoding='utf-8').replace(
        '"Required \\u202D label"', '"Required \\u202D label ??/ ??= */ /* \\\\"'), encoding='utf-8')
    report = check_source(path, kind=Kind.NODE, file=str(path))
    assert {d.code for d in report.diagnostics} == {'NODL219', 'NODL220'}
    node, _ = resolve_report(CheckedSource(str(path), Kind.NODE, report.data, []), client_library='rclcpp')
    assert node is not None
    options = GenerateOptions('Hostile', 'hostile')
    out = tmp_path / 'out'
    write_files(generate_cpp(node, options), str(out))
    plan = plan_cpp(node, options)
    user = out / 'hostile.cpp'
    user.write_text(render_user_source(plan, options.class_name), encoding='utf-8')
    written = sorted(out.iterdir())
    assert len(written) >= 3
    for generated in written:
        text = generated.read_text(encoding='utf-8')
        assert UNSAFE.search(text) is None and '\u2028' not in text, generated.name
    assert 'Required' in (out / f'{plan.stem}.hpp').read_text(encoding='utf-8')
    assert parse_errors(out / f'{plan.stem}.cpp', [out]) == []
    assert parse_errors(user, [out]) == []
