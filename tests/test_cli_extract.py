"""``nodl extract``: drafts printed or written (overlay layout, one file), --diff, formats, exit statuses."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from conftest import REPO

FIXTURES = REPO / 'tests' / 'fixtures' / 'extract' / 'python'


def _run(*args: str, cwd: Path = REPO) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl', 'extract', *args], cwd=cwd, text=True,
                          capture_output=True, timeout=60, env={**os.environ, 'PYTHONPATH': str(REPO)})


def test_overlay_layout_and_drafts_that_validate(tmp_path: Path) -> None:
    result = _run(str(FIXTURES / 'pkg'), '-o', str(tmp_path / 'out'))
    assert result.returncode == 0, result.stderr
    talker = tmp_path / 'out' / 'demo_pkg' / 'talker.nodl.yaml'
    assert talker.is_file() and (tmp_path / 'out' / 'demo_pkg' / 'pair__pair_server.nodl.yaml').is_file()
    text = talker.read_text(encoding='utf-8')
    assert 'by nodl extract' in text and 'nodl: generated; sha256=' in text
    check = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--strict', str(talker)], cwd=REPO,
                           text=True, capture_output=True, timeout=60)
    assert check.returncode == 0, check.stdout
    # a draft edited by the user is never replaced without --force
    talker.write_text(text + '# mine\n', encoding='utf-8')
    refused = _run(str(FIXTURES / 'pkg'), '-o', str(tmp_path / 'out'))
    assert refused.returncode == 2 and 'NODL032' in refused.stdout
    assert talker.read_text(encoding='utf-8').endswith('# mine\n')
    assert _run(str(FIXTURES / 'pkg'), '-o', str(tmp_path / 'out'), '--force').returncode == 0


def test_one_file_output_needs_one_node(tmp_path: Path) -> None:
    one = _run(str(FIXTURES / 'real' / 'demo_nodes_py__talker.py'), '-o', str(tmp_path / 'talker.nodl.yaml'))
    assert one.returncode == 0 and (tmp_path / 'talker.nodl.yaml').is_file()
    several = _run(str(FIXTURES / 'real' / 'demo_nodes_py__introspection.py'), '-o', str(tmp_path / 'x.yaml'))
    assert several.returncode == 2 and 'NODL913' in several.stdout and not (tmp_path / 'x.yaml').exists()


def test_printed_draft_and_gaps_on_stderr() -> None:
    result = _run('tests/fixtures/extract/python/real/demo_nodes_py__talker_qos.py')
    assert result.returncode == 0
    assert result.stdout.startswith('# Extracted from tests/fixtures/extract/python/real/demo_nodes_py__talker_qos.py')
    assert 'NODL903' in result.stderr and '# GAP' in result.stdout
    assert _run('tests/fixtures/extract/python/real/demo_nodes_py__talker_qos.py', '--strict').returncode == 1


def test_diff_as_json_and_sarif(tmp_path: Path) -> None:
    definition = tmp_path / 'talker.nodl.yaml'
    definition.write_text('nodl_version: 2\nmain:\n  nodl_version: 2\n  publishers:\n    - name: chatter\n'
                          '      type: std_msgs/msg/Int32\n      qos: {history: KEEP_LAST, depth: 10, '
                          'reliability: RELIABLE}\n', encoding='utf-8')
    source = str(FIXTURES / 'real' / 'demo_nodes_py__talker.py')
    result = _run(source, '--diff', str(definition), '--format', 'json')
    assert result.returncode == 1
    assert [d['code'] for d in json.loads(result.stdout) if d['severity'] == 'error'] == ['NODL922']
    sarif = json.loads(_run(source, '--diff', str(definition), '--format', 'sarif').stdout)
    assert sarif['runs'][0]['results'][0]['ruleId'] == 'NODL922'
    same = tmp_path / 'same.nodl.yaml'
    same.write_text(definition.read_text(encoding='utf-8').replace('Int32', 'String'), encoding='utf-8')
    assert _run(source, '--diff', str(same)).returncode == 0
    junit = _run(source, '--diff', str(definition), '--format', 'junit')
    assert '<testsuite' in junit.stdout and 'NODL922' in junit.stdout


def test_bad_paths_and_sources_never_a_traceback(tmp_path: Path) -> None:
    missing = _run(str(tmp_path / 'nope'))
    assert missing.returncode == 2 and 'NODL020' in missing.stderr and 'Traceback' not in missing.stderr
    broken = _run(str(FIXTURES / 'cases' / 'syntax_error.py'), str(FIXTURES / 'real' / 'demo_nodes_py__talker.py'))
    assert broken.returncode == 1 and 'NODL906' in broken.stderr and 'Traceback' not in broken.stderr
    (tmp_path / 'util.py').write_text('x = 1\n', encoding='utf-8')
    nothing = _run(str(tmp_path))
    assert nothing.returncode == 2 and 'NODL912' in nothing.stderr


# -- C++ and mixed packages, laid out from the real fixtures ---------------------------------------

EXTRACT = REPO / 'tests' / 'fixtures' / 'extract'


def _cpp_packages(root: Path) -> Path:
    """demo_nodes_cpp and composition with their real CMakeLists.txt and real sources."""
    import shutil

    layout = {
        'demo_nodes_cpp': {'src/topics/talker.cpp': 'demo_talker/talker.cpp',
                           'src/topics/listener_best_effort.cpp': 'demo_listener_best_effort/listener_best_effort.cpp',
                           'src/services/add_two_ints_server.cpp': 'demo_add_two_ints_server/add_two_ints_server.cpp'},
        'composition': {'src/talker_component.cpp': 'composition_talker/talker_component.cpp',
                        'include/composition/talker_component.hpp': 'composition_talker/talker_component.hpp'},
    }
    for package, files in layout.items():
        (root / package).mkdir(parents=True)
        shutil.copy(EXTRACT / 'cmake' / package / 'CMakeLists.txt', root / package / 'CMakeLists.txt')
        (root / package / 'package.xml').write_text(f'<package format="3"><name>{package}</name></package>\n')
        for target, source in files.items():
            (root / package / target).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(EXTRACT / 'cpp' / source, root / package / target)
    return root


def test_cpp_packages_end_to_end_in_the_overlay_layout(tmp_path: Path) -> None:
    from nodl.registry.overlay import read_folder

    sources = _cpp_packages(tmp_path / 'src')
    result = _run(str(sources), '-o', str(tmp_path / 'out'))
    assert result.returncode == 0, result.stdout + result.stderr
    out = tmp_path / 'out'
    assert sorted(str(p.relative_to(out)) for p in out.rglob('*') if p.is_file()) == [
        'composition/nodes.yaml', 'composition/talker.nodl.yaml', 'demo_nodes_cpp/add_two_ints_server.nodl.yaml',
        'demo_nodes_cpp/listener_best_effort.nodl.yaml', 'demo_nodes_cpp/nodes.yaml',
        'demo_nodes_cpp/talker.nodl.yaml']
    assert '4 nodes found, 4 drafts written; ' in result.stdout
    folder = read_folder(str(out))  # the overlay reads back clean, with what registrations record
    assert folder.diagnostics == []
    assert folder.info == {
        ('composition', 'talker'): ('composition::Talker', 'talker'),   # a component only: its snake-case key
        ('demo_nodes_cpp', 'add_two_ints_server'): ('demo_nodes_cpp::ServerNode', 'add_two_ints_server'),
        ('demo_nodes_cpp', 'listener_best_effort'): ('demo_nodes_cpp::ListenerBestEffort', 'listener'),
        ('demo_nodes_cpp', 'talker'): ('demo_nodes_cpp::Talker', 'talker')}
    talker = (out / 'demo_nodes_cpp' / 'talker.nodl.yaml').read_text(encoding='utf-8')
    assert '(demo_nodes_cpp talker, cpp)' in talker
    check = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--strict',
                            *map(str, out.rglob('*.nodl.yaml'))], cwd=REPO, text=True, capture_output=True,
                           timeout=60)
    assert check.returncode == 0, check.stdout
    # no 'no entry point' note on a C++ node CMakeLists.txt maps (the Python wording was given to all)
    printed = _run(str(sources / 'demo_nodes_cpp'), '--format', 'json')
    codes = [d['code'] for d in json.loads(printed.stdout)]
    assert 'NODL911' not in codes and 'NODL944' not in codes, codes


def test_a_component_only_class_is_noted_once(tmp_path: Path) -> None:
    sources = _cpp_packages(tmp_path / 'src')
    result = _run(str(sources / 'composition'), '--format', 'json')
    assert result.returncode == 0
    notes = [(d['code'], d['message']) for d in json.loads(result.stdout)]
    assert [c for c, _ in notes] == ['NODL944'], notes
    assert 'plugin composition::Talker of library talker_component' in notes[0][1]


def test_mixed_ament_cmake_python_package(tmp_path: Path) -> None:
    import shutil

    package = tmp_path / 'mixed_pkg'
    shutil.copytree(EXTRACT / 'packages' / 'mixed_pkg', package)
    (package / 'src').mkdir()
    shutil.copy(EXTRACT / 'cpp' / 'demo_talker' / 'talker.cpp', package / 'src' / 'talker.cpp')
    (package / 'scripts').mkdir()
    shutil.copy(FIXTURES / 'real' / 'demo_nodes_py__talker.py', package / 'scripts' / 'py_talker.py')
    shutil.copy(FIXTURES / 'real' / 'demo_nodes_py__listener.py', package / 'scripts' / 'tool.py')
    result = _run(str(package), '-o', str(tmp_path / 'out'), '--format', 'json')
    assert result.returncode == 0, result.stdout + result.stderr
    out = tmp_path / 'out' / 'mixed_pkg'
    assert sorted(p.name for p in out.iterdir()) == [
        'Listener.nodl.yaml', 'cpp_talker.nodl.yaml', 'nodes.yaml', 'py_talker.py.nodl.yaml',
        'talker_py.nodl.yaml']
    assert 'publishers:' in (out / 'cpp_talker.nodl.yaml').read_text(encoding='utf-8')
    assert '(mixed_pkg talker_py, python)' in (out / 'talker_py.nodl.yaml').read_text(encoding='utf-8')
    # a script installed elsewhere than lib/<package> is no executable of the package: noted
    notes = [d for d in json.loads(result.stdout) if d['code'] == 'NODL911']
    assert [n['file'].rsplit('/', 1)[-1] for n in notes] == ['tool.py']


def test_a_base_class_of_another_module_end_to_end(tmp_path: Path) -> None:
    """The drafts of nodes derived from bases of other modules hold the bases' entities, each
    under a comment that points into the base's file; a base the package does not hold is the one
    NODL960 warning at the class."""
    package = 'tests/fixtures/extract/packages/base_pkg'
    result = _run(package, '-o', str(tmp_path / 'out'), '--format', 'json')
    assert result.returncode == 0, result.stdout + result.stderr
    talker = (tmp_path / 'out' / 'base_pkg' / 'talker.nodl.yaml').read_text(encoding='utf-8')
    assert f'    # {package}/base_pkg/base.py:18:9\n    rate:\n' in talker
    assert f'    # {package}/base_pkg/base.py:19:23\n    - name: talker_status\n' in talker
    assert f'    # {package}/base_pkg/talker.py:14:24\n    - name: chatter\n' in talker
    managed = (tmp_path / 'out' / 'base_pkg' / 'managed.nodl.yaml').read_text(encoding='utf-8')
    assert 'base: lifecycle_node' in managed
    unread = [(d['file'].rsplit('/', 1)[-1], d['line']) for d in json.loads(result.stdout) if d['code'] == 'NODL960']
    assert sorted(unread) == [('orphans.py', 10), ('orphans.py', 16)]
    check = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--strict',
                            *map(str, (tmp_path / 'out').rglob('*.nodl.yaml'))], cwd=REPO, text=True,
                           capture_output=True, timeout=60)
    assert check.returncode == 0, check.stdout
