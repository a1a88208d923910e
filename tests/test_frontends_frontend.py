"""The nodl.frontends extension point (nodl.frontends.frontend): discovery, order, plug-ins.

The third-party frontend is a fixture plug-in (tests/fixtures/plugins/frontends): NoDL in
TOML, registered through its entry_points.txt like the built-ins, with broken neighbours
(one that raises, one for a future version, one whose module does not exist).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import tomllib

from conftest import FIXTURES, REPO
from nodl import check_source, plugins
from nodl.files import find_nodl_files
from nodl.frontends import frontend
from nodl.frontends.builtin import (
    GenParamLibFrontend,
    IncludeFrontend,
    LegacyXmlFrontend,
    YamlJsonFrontend,
)
from nodl.frontends.frontend import (
    FrontendExtension,
    Reading,
    load_frontends,
    read_document,
)
from nodl.frontends.source import SourceText

SITE = FIXTURES / 'plugins' / 'frontends'
NODE_TOML = '''nodl_version = 2

[main]
nodl_version = 2

[[main.publishers]]
name = "chatter"
type = "std_msgs/msg/String"
description = "What is said."

[main.publishers.qos]
history = "KEEP_LAST"
depth = 10
reliability = "RELIABLE"
durability = "VOLATILE"
'''


@pytest.fixture
def fresh(monkeypatch: pytest.MonkeyPatch) -> None:
    """The frontends loaded again for this test (and after it)."""
    monkeypatch.setattr(plugins, '_cache', None)
    monkeypatch.setattr(frontend, '_loaded', None)
    monkeypatch.delenv(plugins.BLOCKLIST_VARIABLE, raising=False)


@pytest.fixture
def third_party(fresh: None, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.syspath_prepend(str(SITE))


def test_pyproject_registers_the_builtins_the_fallback_names() -> None:
    project = tomllib.loads((REPO / 'pyproject.toml').read_text(encoding='utf-8'))
    registered = project['project']['entry-points']['nodl.frontends']
    assert registered == frontend.BUILTIN_FRONTENDS


def test_builtins_are_frontends_asked_by_priority(fresh: None) -> None:
    found, broken = load_frontends()
    assert broken == []
    assert list(found) == ['legacy-xml', 'include', 'genparamlib', 'yaml-json']
    assert [type(f) for f in found.values()] == [
        LegacyXmlFrontend, IncludeFrontend, GenParamLibFrontend, YamlJsonFrontend]
    assert all(isinstance(f, FrontendExtension) and f.EXTENSION_GROUP == 'nodl.frontends'
               for f in found.values())
    assert plugins.EXTENSION_POINTS['nodl.frontends'].version == FrontendExtension.EXTENSION_POINT_VERSION


def test_without_metadata_the_builtins_still_read(fresh: None, monkeypatch: pytest.MonkeyPatch) -> None:
    """A source tree run without its entry point metadata still reads documents."""
    monkeypatch.setattr(frontend, 'iter_entry_points', lambda group, include_blocked=False: [])
    found, _ = load_frontends()
    assert list(found) == ['legacy-xml', 'include', 'genparamlib', 'yaml-json']


@pytest.mark.parametrize(('text', 'name', 'dialect', 'code'), [
    ('nodl_version: 2\nmain: {nodl_version: 2}\n', 'yaml-json', None, None),
    ('{"nodl_version": 2}', 'yaml-json', None, None),
    ('a: [1\n', 'yaml-json', None, 'NODL003'),
    ('<interface version="1"/>\n', 'legacy-xml', None, 'NODL817'),
    ('nodl_version: 2\ninclude: [{ref: "nodl://rclcpp/node"}]\n', 'include', 'include', 'NODL851'),
    ('ns:\n  speed: {type: double}\n', 'genparamlib', 'genparamlib', 'NODL861'),
])
def test_each_text_is_read_by_its_frontend(fresh: None, text: str, name: str, dialect: str | None,
                                           code: str | None) -> None:
    reading = read_document(SourceText(text, 'x.nodl.yaml'))
    assert (reading.frontend, reading.dialect) == (name, dialect)
    assert [d.code for d in reading.diagnostics][:1] == ([code] if code else [])


def test_a_third_party_frontend_reads_its_files_and_broken_ones_are_said_once(
        third_party: None, tmp_path: Path) -> None:
    found, broken = load_frontends()
    assert list(found) == ['legacy-xml', 'exploding', 'toml', 'include', 'genparamlib', 'yaml-json']
    assert sorted(e.name for e in broken) == ['future', 'gone']
    node = tmp_path / 'talker.nodl.toml'
    node.write_text(NODE_TOML, encoding='utf-8')
    first = check_source(node)
    assert first.kind is not None and first.kind.value == 'node' and not first.errors
    assert first.dialect == 'toml'
    warned = {d.message.split("'")[1]: d for d in first.warnings}
    assert sorted(warned) == ['future', 'gone'] and {d.code for d in warned.values()} == {'NODL017'}
    assert 'ModuleNotFoundError' in warned['gone'].message
    assert 'version 2.0 of the nodl.frontends extension point' in warned['future'].message
    again = check_source(node)  # each broken plug-in is said once per process
    assert again.diagnostics == []
    assert check_source(node).model().main.publishers[0].name == 'chatter'  # type: ignore[union-attr]


def test_a_frontend_that_raises_is_skipped_on_that_file(third_party: None, tmp_path: Path) -> None:
    load_frontends()
    frontend._loaded.unreported = []  # type: ignore[union-attr]
    exploding = tmp_path / 'x.explode.yaml'
    exploding.write_text('nodl_version: 2\nmain: {nodl_version: 2}\n', encoding='utf-8')
    report = check_source(exploding)
    assert report.kind is not None and not report.errors
    [warning] = report.warnings
    assert warning.code == 'NODL017'
    assert "frontend plug-in 'exploding'" in warning.message
    assert 'it raised RuntimeError: boom' in warning.message


def test_a_directory_scan_takes_every_frontends_files(third_party: None, tmp_path: Path) -> None:
    (tmp_path / 'a.nodl.toml').write_text(NODE_TOML, encoding='utf-8')
    (tmp_path / 'b.nodl.yaml').write_text('nodl_version: 2\n', encoding='utf-8')
    (tmp_path / 'c.toml').write_text(NODE_TOML, encoding='utf-8')
    assert sorted(Path(t.path).name for t in find_nodl_files([str(tmp_path)])) == [
        'a.nodl.toml', 'b.nodl.yaml']


def test_blocking_every_frontend_is_an_error_not_a_crash(
        fresh: None, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(plugins.BLOCKLIST_VARIABLE, 'nodl.frontends')
    reading = read_document(SourceText('nodl_version: 2\n', 'x.nodl.yaml'))
    assert reading.data is None and [d.code for d in reading.diagnostics] == ['NODL018']
    monkeypatch.setenv(plugins.BLOCKLIST_VARIABLE, 'nodl.frontends.include')
    included = read_document(SourceText('nodl_version: 2\ninclude: []\n', 'x.nodl.yaml'))
    assert included.frontend == 'yaml-json'


def test_a_reading_that_is_not_a_reading_is_a_broken_frontend(
        fresh: None, monkeypatch: pytest.MonkeyPatch) -> None:
    class Wrong(FrontendExtension):
        def read(self, source: frontend.FrontendInput) -> Reading | None:
            return {'nodl_version': 2}  # type: ignore[return-value]

    found, _ = load_frontends()
    monkeypatch.setattr(frontend._loaded, 'frontends', {'wrong': Wrong(), **found})
    reading = read_document(SourceText('nodl_version: 2\n', 'x.nodl.yaml'))
    assert reading.frontend == 'yaml-json'
    assert 'read() returned dict, not a Reading or None' in reading.diagnostics[0].message


def test_cli_validates_with_a_third_party_frontend() -> None:
    env = {k: v for k, v in os.environ.items() if k != plugins.BLOCKLIST_VARIABLE}
    env['PYTHONPATH'] = str(SITE)
    result = subprocess.run(
        [sys.executable, '-m', 'nodl', 'validate', str(SITE.parent / 'frontends_example')],
        cwd=REPO, env=env, text=True, capture_output=True, timeout=60, check=False)
    assert 'Traceback' not in result.stderr
    out = result.stdout + result.stderr
    assert 'talker.nodl.toml: valid node definition' in out, out
    assert out.count('[NODL017]') == 2, out  # 'future' and 'gone', once each
    assert result.returncode == 0, out


def test_reading_yaml_loads_no_other_frontends_reader() -> None:
    """The XML and generate_parameter_library readers are loaded for their own texts only."""
    program = ('import json, sys\nfrom nodl.cli.main import main\n'
               "code = main(['validate', '-q', sys.argv[1]])\n"
               'print(json.dumps([code, sorted(sys.modules)]))\n')
    node = FIXTURES / 'valid' / 'node_laser_driver.nodl.yaml'
    done = subprocess.run([sys.executable, '-c', program, str(node)], capture_output=True, text=True,
                          timeout=60, cwd=REPO, check=False)
    assert done.returncode == 0, done.stderr
    code, modules = json.loads(done.stdout.splitlines()[-1])
    assert code == 0 and 'nodl.frontends.builtin' in modules
    assert not {'nodl.frontends.xml_reader', 'nodl.frontends.legacy_xml', 'nodl.frontends.xml_recognise',
                'nodl.frontends.genparamlib', 'pyexpat', 'importlib.metadata'} & set(modules)
