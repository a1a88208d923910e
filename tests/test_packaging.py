"""Registration from Python packages (nodl.packaging), with real pip installs."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl.packaging import INTERFACE_RESOURCE, NODE_RESOURCE, NodlBuildError, nodl_data_files, relative_mixins

PACKAGES = FIXTURES / 'python_packages'
INDEX = Path('share') / 'ament_index' / 'resource_index'


def pip_install(source: Path, prefix: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, '-m', 'pip', 'install', '--no-deps', '--no-build-isolation',
         '--no-index', '--disable-pip-version-check', '--prefix', str(prefix), str(source)],
        cwd=source.parent, text=True, capture_output=True, timeout=120,
        env={k: v for k, v in os.environ.items() if k != 'PIP_REQUIRE_VIRTUALENV'})


def nodl(prefix: Path, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, '-m', 'nodl', *args], cwd=REPO,
                          env=dict(os.environ, AMENT_PREFIX_PATH=str(prefix)), text=True,
                          capture_output=True, timeout=60)


@pytest.fixture(scope='module')
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """py_talker (setup.py helper) and py_recipe (plain pyproject recipe) in one prefix."""
    root = tmp_path_factory.mktemp('pip')
    prefix = root / 'prefix'
    for name in ('py_talker', 'py_recipe'):
        shutil.copytree(PACKAGES / name, root / name)
        result = pip_install(root / name, prefix)
        assert result.returncode == 0, result.stdout + result.stderr
    return prefix


# --- real installs -------------------------------------------------------------------------

def test_helper_package_installs_the_index_layout(installed: Path) -> None:
    index = installed / INDEX
    assert (index / 'packages' / 'py_talker').is_file()
    assert (index / NODE_RESOURCE / 'py_talker__talker').read_text() == 'nodl/talker.nodl.yaml'
    assert (index / INTERFACE_RESOURCE / 'py_talker__chatter').read_text() == 'nodl/chatter.nodl.yaml'
    share = installed / 'share' / 'py_talker'
    assert sorted(p.name for p in (share / 'nodl').iterdir()) == ['chatter.nodl.yaml',
                                                                  'talker.nodl.yaml']
    for name in ('chatter.nodl.yaml', 'talker.nodl.yaml'):
        assert (share / 'nodl' / name).read_bytes() == (PACKAGES / 'py_talker' / 'nodl' / name).read_bytes()
    assert (share / 'package.xml').is_file()


def test_the_staging_index_is_not_installed(installed: Path) -> None:
    assert not [p for p in installed.rglob('*') if 'stage' in p.name or 'nodl_index' in p.name]
    entries = sorted(str(p.relative_to(installed / INDEX)) for p in (installed / INDEX).glob('nodl_*/*'))
    assert entries == ['nodl_interfaces/py_talker__chatter', 'nodl_nodes/py_recipe__listener',
                       'nodl_nodes/py_talker__talker']


def test_plain_recipe_installs_the_same_layout(installed: Path) -> None:
    index = installed / INDEX
    assert (index / 'packages' / 'py_recipe').is_file()
    assert (index / NODE_RESOURCE / 'py_recipe__listener').read_text() == 'nodl/listener.nodl.yaml'
    assert (installed / 'share' / 'py_recipe' / 'nodl' / 'listener.nodl.yaml').is_file()


def test_nodl_list_finds_both_packages(installed: Path) -> None:
    result = nodl(installed, 'list')
    assert result.returncode == 0, result.stderr
    share = lambda pkg, f: str(installed / 'share' / pkg / 'nodl' / f)  # noqa: E731
    assert [tuple(line.split()) for line in result.stdout.splitlines()] == [
        # package, kind, name, origin (the ament index here), file
        ('py_recipe', 'node', 'listener', 'index', share('py_recipe', 'listener.nodl.yaml')),
        ('py_talker', 'interface', 'chatter', 'index', share('py_talker', 'chatter.nodl.yaml')),
        ('py_talker', 'node', 'talker', 'index', share('py_talker', 'talker.nodl.yaml')),
    ]


def test_nodl_show_an_installed_python_node(installed: Path) -> None:
    result = nodl(installed, 'show', 'py_talker', 'talker', '--layers')
    assert result.returncode == 0, result.stderr
    layers = {line.strip() for line in result.stdout.splitlines() if '# layer:' in line}
    assert layers == {'# layer: base:node', '# layer: nodl://py_talker/chatter', '# layer: main'}
    assert '  # layer: nodl://py_talker/chatter\n  - name: chatter\n' in result.stdout
    assert '  # layer: main\n  period:\n' in result.stdout
    listener = nodl(installed, 'show', 'py_recipe', 'listener')
    assert listener.returncode == 0, listener.stderr
    assert 'subscriptions:\n- name: chatter\n' in listener.stdout


def test_an_invalid_definition_fails_the_pip_install(tmp_path: Path) -> None:
    package = tmp_path / 'py_talker'
    shutil.copytree(PACKAGES / 'py_talker', package)
    talker = package / 'nodl' / 'talker.nodl.yaml'
    talker.write_text(talker.read_text().replace('type: double', 'type: dubble'))
    chatter = package / 'nodl' / 'chatter.nodl.yaml'
    chatter.write_text(chatter.read_text().replace(
        '    qos: {history: KEEP_LAST, depth: 10, reliability: RELIABLE}\n', ''))
    prefix = tmp_path / 'prefix'
    result = pip_install(package, prefix)
    out = result.stdout + result.stderr
    assert result.returncode != 0, out
    # every invalid file, with FILE:LINE:COL
    assert "nodl/talker.nodl.yaml:9:13: error: unknown parameter type 'dubble'" in out, out
    assert "nodl/chatter.nodl.yaml:4:5: error: missing required key 'qos'" in out, out
    assert 'py_talker: invalid NoDL definitions: nodl/chatter.nodl.yaml, nodl/talker.nodl.yaml' in out
    assert not (prefix / INDEX).exists()


def test_relative_mixins_are_installed_and_resolve(tmp_path: Path) -> None:
    package = tmp_path / 'py_relative'
    shutil.copytree(PACKAGES / 'py_relative', package)
    prefix = tmp_path / 'prefix'
    result = pip_install(package, prefix)
    assert result.returncode == 0, result.stdout + result.stderr
    share = prefix / 'share' / 'py_relative'
    for path in ('nodl/sensor_node.nodl.yaml', 'nodl/diagnostics.yaml',
                 'nodl/common/limits.nodl.yaml', 'shared/heartbeat.nodl.yaml'):
        assert (share / path).read_bytes() == (PACKAGES / 'py_relative' / path).read_bytes(), path
    # only the node is registered; its mixins are files next to it
    assert sorted(str(p.relative_to(prefix / INDEX)) for p in (prefix / INDEX).glob('nodl_*/*')) == [
        'nodl_nodes/py_relative__sensor_node']
    shown = nodl(prefix, 'show', 'py_relative', 'sensor_node', '--layers')
    assert shown.returncode == 0, shown.stderr
    assert {line.strip() for line in shown.stdout.splitlines() if '# layer:' in line} == {
        '# layer: base:node', '# layer: diagnostics.yaml', '# layer: file://common/limits.nodl.yaml',
        '# layer: ../shared/heartbeat.nodl.yaml', '# layer: main'}


# --- relative_mixins() and nodl_data_files() directly ----------------------------------------

def test_relative_mixins_lists_files_of_the_package_only(tmp_path: Path) -> None:
    node = tmp_path / 'n.nodl.yaml'
    node.write_text('nodl_version: 2\nbase: node\nmixins:\n'
                    '  - nodl://other/thing\n  - ./a.yaml\n  - file://sub/../b.yaml\n'
                    '  - a.yaml\n  - {nodl_version: 2}\n  - ../up/c.yaml\n'
                    'main: {nodl_version: 2}\n')
    assert relative_mixins(node) == ['a.yaml', 'b.yaml', '../up/c.yaml']
    assert relative_mixins(str(node)) == ['a.yaml', 'b.yaml', '../up/c.yaml']


@pytest.mark.parametrize('text', ['nodl_version: 2\npublishers: []\n', 'not: [valid\n', ''])
def test_relative_mixins_of_other_documents_are_none(tmp_path: Path, text: str) -> None:
    path = tmp_path / 'x.yaml'
    path.write_text(text)
    assert relative_mixins(path) == []
    assert relative_mixins(tmp_path / 'missing.yaml') == []


def test_relative_mixins_get_data_files_entries(tmp_path: Path,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    root = tmp_path / 'pkg'
    shutil.copytree(PACKAGES / 'py_relative', root)
    monkeypatch.chdir(root)
    entries = dict(nodl_data_files('py_relative', nodes={'sensor_node': 'nodl/sensor_node.nodl.yaml'}))
    assert entries['share/py_relative/nodl'] == ['nodl/sensor_node.nodl.yaml', 'nodl/diagnostics.yaml']
    assert entries['share/py_relative/nodl/common'] == ['nodl/common/limits.nodl.yaml']
    assert entries['share/py_relative/shared'] == ['shared/heartbeat.nodl.yaml']


def test_a_relative_mixin_that_would_leave_the_share_folder_is_refused(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    root = tmp_path / 'pkg'
    (root / 'a' / 'b').mkdir(parents=True)
    (root / 'package.xml').write_text('<package/>')
    (root / 'top.yaml').write_text('nodl_version: 2\n')
    (root / 'a' / 'b' / 'n.nodl.yaml').write_text(
        'nodl_version: 2\nbase: node\nmixins: [../../top.yaml]\nmain: {nodl_version: 2}\n')
    monkeypatch.chdir(root)
    with pytest.raises(SystemExit) as exc:
        nodl_data_files('p', nodes={'n': 'a/b/n.nodl.yaml'})
    assert str(exc.value).startswith("nodl_data_files: a/b/n.nodl.yaml: mixin '../../top.yaml' "
                                     'would be installed outside share/p;')


def test_a_relative_mixin_colliding_with_a_registered_file_is_refused(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    root = tmp_path / 'pkg'
    shutil.copytree(PACKAGES / 'py_relative', root)
    (root / 'other').mkdir()
    (root / 'other' / 'diagnostics.yaml').write_text('nodl_version: 2\n')
    monkeypatch.chdir(root)
    with pytest.raises(SystemExit) as exc:
        nodl_data_files('py_relative', nodes={'sensor_node': 'nodl/sensor_node.nodl.yaml'},
                        interfaces={'diag': 'other/diagnostics.yaml'})
    assert str(exc.value) == ('nodl_data_files: other/diagnostics.yaml and nodl/diagnostics.yaml '
                              'would both be installed as share/py_relative/nodl/diagnostics.yaml; '
                              'rename one')


# --- nodl_data_files() directly ------------------------------------------------------------

@pytest.fixture
def pkg(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A copy of py_talker's files; the current directory is its root (like setup.py's)."""
    root = tmp_path / 'pkg'
    shutil.copytree(PACKAGES / 'py_talker', root)
    monkeypatch.chdir(root)
    return root


def test_entries_and_markers(pkg: Path) -> None:
    entries = nodl_data_files('py_talker', nodes={'talker': 'nodl/talker.nodl.yaml'},
                              interfaces={'chatter': 'nodl/chatter.nodl.yaml'})
    stage = 'build/nodl_index/share/ament_index/resource_index'
    assert entries == [
        ('share/ament_index/resource_index/nodl_interfaces',
         [f'{stage}/nodl_interfaces/py_talker__chatter']),
        ('share/ament_index/resource_index/nodl_nodes', [f'{stage}/nodl_nodes/py_talker__talker']),
        ('share/py_talker/nodl', ['nodl/chatter.nodl.yaml', 'nodl/talker.nodl.yaml']),
    ]
    assert (pkg / stage / 'nodl_nodes' / 'py_talker__talker').read_text() == 'nodl/talker.nodl.yaml'
    assert (pkg / stage / 'nodl_interfaces' / 'py_talker__chatter').read_text() == \
        'nodl/chatter.nodl.yaml'


def test_one_file_may_serve_two_keys(pkg: Path) -> None:
    entries = dict(nodl_data_files('py_talker', nodes={'a': 'nodl/talker.nodl.yaml',
                                                       'b': 'nodl/talker.nodl.yaml'},
                                   interfaces={'chatter': 'nodl/chatter.nodl.yaml'}))
    assert entries['share/py_talker/nodl'] == ['nodl/chatter.nodl.yaml', 'nodl/talker.nodl.yaml']
    assert [os.path.basename(m) for m in entries['share/ament_index/resource_index/nodl_nodes']] == [
        'py_talker__a', 'py_talker__b']


def test_a_file_serving_two_keys_is_reported_once(pkg: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(NodlBuildError) as exc:
        nodl_data_files('py_talker', nodes={'a': 'nodl/talker.nodl.yaml',
                                            'b': 'nodl/talker.nodl.yaml'})
    lines = str(exc.value).splitlines()
    assert lines[-1] == 'py_talker: invalid NoDL definitions: nodl/talker.nodl.yaml'
    assert [line for line in lines if ': error: ' in line] == [str(d) for d in exc.value.diagnostics]
    assert len(exc.value.diagnostics) == 1
    assert capsys.readouterr() == ('', '')  # the library prints nothing: the exception says it


def test_a_custom_staging_dir(pkg: Path) -> None:
    entries = dict(nodl_data_files('py_talker', interfaces={'chatter': 'nodl/chatter.nodl.yaml'},
                                   staging_dir='out/markers'))
    [marker] = entries['share/ament_index/resource_index/nodl_interfaces']
    assert marker == 'out/markers/share/ament_index/resource_index/nodl_interfaces/py_talker__chatter'
    assert (pkg / marker).read_text() == 'nodl/chatter.nodl.yaml'


def test_duplicate_basenames_are_refused(pkg: Path) -> None:
    (pkg / 'other').mkdir()
    shutil.copy(pkg / 'nodl' / 'chatter.nodl.yaml', pkg / 'other' / 'talker.nodl.yaml')
    with pytest.raises(SystemExit) as exc:
        nodl_data_files('py_talker', nodes={'talker': 'nodl/talker.nodl.yaml'},
                        interfaces={'chatter': 'other/talker.nodl.yaml'})
    assert str(exc.value) == ('nodl_data_files: nodl/talker.nodl.yaml and other/talker.nodl.yaml '
                              'would both be installed as share/py_talker/nodl/talker.nodl.yaml; '
                              'rename one')
    assert not (pkg / 'build').exists()  # nothing written


def test_missing_files_and_bad_names_are_all_reported(pkg: Path) -> None:
    with pytest.raises(SystemExit) as exc:
        nodl_data_files('py_talker', nodes={'talker': 'nodl/none.nodl.yaml',
                                            'bad name': 'nodl/talker.nodl.yaml'},
                        interfaces={'chatter': 'nodl/gone.nodl.yaml'})
    assert str(exc.value).splitlines() == [
        "nodl_data_files: nodl/none.nodl.yaml: no such file (registered as 'talker')",
        "nodl_data_files: 'bad name' is not a valid name (letters, digits, '_', '.', '-')",
        "nodl_data_files: nodl/gone.nodl.yaml: no such file (registered as 'chatter')",
    ]


def test_validation_resolves_the_packages_own_interfaces(pkg: Path,
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv('AMENT_PREFIX_PATH', '/nonexistent/prefix')
    nodl_data_files('py_talker', nodes={'talker': 'nodl/talker.nodl.yaml'},
                    interfaces={'chatter': 'nodl/chatter.nodl.yaml'})
    assert os.environ['AMENT_PREFIX_PATH'] == '/nonexistent/prefix'  # restored


def test_validation_failure_reports_positions(pkg: Path, capsys: pytest.CaptureFixture[str],
                                              monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv('AMENT_PREFIX_PATH', raising=False)
    # the node's mixin nodl://py_talker/chatter is not registered
    with pytest.raises(NodlBuildError) as exc:
        nodl_data_files('py_talker', nodes={'talker': 'nodl/talker.nodl.yaml'})
    assert isinstance(exc.value, SystemExit)  # setup.py stops with these lines, no traceback
    assert str(exc.value).endswith('\npy_talker: invalid NoDL definitions: nodl/talker.nodl.yaml')
    assert capsys.readouterr().err == ''
    err = str(exc.value)
    assert err.startswith("nodl/talker.nodl.yaml:4:5: error: cannot resolve mixin "
                          "'nodl://py_talker/chatter': package 'py_talker' registers no "
                          'interface definitions')
    assert 'AMENT_PREFIX_PATH' not in os.environ  # restored


def test_the_kind_is_enforced(pkg: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(NodlBuildError) as exc:
        nodl_data_files('py_talker', interfaces={'talker': 'nodl/talker.nodl.yaml'},
                        nodes={'chatter': 'nodl/chatter.nodl.yaml'})
    err = str(exc.value)
    assert 'nodl/talker.nodl.yaml:1:1: error: expected an interface definition' in err
    assert 'nodl/chatter.nodl.yaml:1:1: error: expected a node definition' in err


def test_warnings_of_a_valid_build_are_logged_not_printed(
        pkg: Path, capsys: pytest.CaptureFixture[str], caplog: pytest.LogCaptureFixture) -> None:
    chatter = pkg / 'nodl' / 'chatter.nodl.yaml'
    chatter.write_text(chatter.read_text().replace('    description: Greetings.\n', ''))
    with caplog.at_level('WARNING', logger='nodl.packaging'):
        nodl_data_files('py_talker', nodes={'talker': 'nodl/talker.nodl.yaml'},
                        interfaces={'chatter': 'nodl/chatter.nodl.yaml'})
    assert capsys.readouterr() == ('', '')
    [record] = caplog.records
    assert record.levelname == 'WARNING' and record.name == 'nodl.packaging'
    assert record.getMessage().startswith('nodl/chatter.nodl.yaml:4:5: warning: ')


def test_validate_false_skips_validation(pkg: Path) -> None:
    (pkg / 'nodl' / 'talker.nodl.yaml').write_text('not: [valid\n')
    entries = nodl_data_files('py_talker', nodes={'talker': 'nodl/talker.nodl.yaml'},
                              validate=False)
    assert dict(entries)['share/py_talker/nodl'] == ['nodl/talker.nodl.yaml']


def test_a_removed_interface_does_not_linger_in_the_staging_index(
        pkg: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv('AMENT_PREFIX_PATH', raising=False)
    nodl_data_files('py_talker', nodes={'talker': 'nodl/talker.nodl.yaml'},
                    interfaces={'chatter': 'nodl/chatter.nodl.yaml'})
    # the next build no longer registers chatter: the node's reference must fail
    with pytest.raises(SystemExit):
        nodl_data_files('py_talker', nodes={'talker': 'nodl/talker.nodl.yaml'})


def test_package_dependencies_never_lists_a_path_outside_the_package() -> None:
    from nodl.packaging import package_dependencies

    deps = Path(__file__).parent / 'fixtures' / 'deps'
    paths, problems = package_dependencies(deps / 'escaping_pkg' / 'nodl' / 'node.nodl.yaml')
    assert paths == ['limits.yaml']
    assert [(d.code, d.severity.value) for d in problems] == [('NODL532', 'error')]
    paths, problems = package_dependencies(deps / 'invalid.nodl.yaml')
    assert paths == [] and problems and all(d.severity.value == 'error' for d in problems)
