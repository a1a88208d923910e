"""The docs stay true (README.md and the site, ros/nodl_toolkit/doc): their quoted command output
is what the tool prints, their Python examples give the results they show."""

from __future__ import annotations

import os
import re
import subprocess
import sys

from conftest import REPO
from site_pages import docs_text, page

README = docs_text()


def test_quoted_validate_output_matches_the_tool() -> None:
    block = re.search(r'```text\n\$ nodl validate (\S+)\n(.*?)```', README, re.S)
    assert block, 'the docs lost their `nodl validate` example'
    path, quoted = block.group(1), block.group(2)
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', path], cwd=REPO,
                            text=True, capture_output=True, timeout=60)
    for line in quoted.splitlines():
        if line and line != '...':
            assert line in result.stdout.splitlines(), line


def test_readme_names_the_two_commands() -> None:
    readme = (REPO / 'README.md').read_text(encoding='utf-8')
    assert 'make demo' in readme and 'make test' in readme


def test_readme_lists_every_verb() -> None:
    """Every verb registered in pyproject.toml has a row in README.md's table of verbs."""
    import tomllib

    readme = (REPO / 'README.md').read_text(encoding='utf-8')
    project = tomllib.loads((REPO / 'pyproject.toml').read_text(encoding='utf-8'))
    verbs = project['project']['entry-points']['nodl.verbs']
    missing = [name for name in verbs if f'`nodl {name}`' not in readme and f'`nodl {name}' not in readme]
    assert not missing, f'README.md has no row for: {", ".join(missing)}'


def test_quoted_policy_example_is_what_the_tool_writes(tmp_path) -> None:  # type: ignore[no-untyped-def]
    block = re.search(r'`(nodl policy talker\.nodl\.yaml use_sim_time:=true\s+--name /robot/talker)` '
                      r'writes:\n\n```xml\n(.*?)```', README, re.S)
    assert block, 'the docs lost their `nodl policy` example'
    arguments = block.group(1).split()[2:]
    fixtures = REPO / 'tests' / 'fixtures' / 'policy'
    written = subprocess.run([sys.executable, '-m', 'nodl', 'policy', *arguments],
                             cwd=fixtures, env={**os.environ, 'PYTHONPATH': str(REPO)},
                             text=True, capture_output=True, timeout=60)
    assert written.returncode == 0, written.stderr
    assert written.stdout == block.group(2)
    # the check of a copy with one grant added by hand, as quoted
    check = re.search(r'`nodl policy --check policy.xml talker.nodl.yaml use_sim_time:=true --name\s+'
                      r'/robot/talker` exits 1 with:\n\n```text\n(.*?)```', README, re.S)
    assert check, 'the docs lost their `nodl policy --check` example'
    (tmp_path / 'talker.nodl.yaml').write_text((fixtures / 'talker.nodl.yaml').read_text())
    (tmp_path / 'policy.xml').write_text(written.stdout.replace(
        '<topic>chatter</topic>', '<topic>chatter</topic>\n            <topic>cmd_vel</topic>', 1))
    result = subprocess.run([sys.executable, '-m', 'nodl', 'policy', '--check', 'policy.xml',
                             'talker.nodl.yaml', 'use_sim_time:=true', '--name', '/robot/talker'],
                            cwd=tmp_path, env={**os.environ, 'PYTHONPATH': str(REPO)},
                            text=True, capture_output=True, timeout=60)
    assert result.returncode == 1
    assert result.stdout + result.stderr == check.group(1)


def _api_blocks() -> list[str]:
    api = page('reference/api')
    section = api[:api.index('## API reference')]
    return re.findall(r'```python\n(.*?)```', section, re.S)


def _result_comment(lines: list[str], end_line: int) -> str | None:
    """The comment after an expression (on its last line, or alone on the next line)."""
    last = lines[end_line - 1]
    if '  # ' in last:
        return last.split('  # ', 1)[1].strip()
    following = lines[end_line].strip() if end_line < len(lines) else ''
    return following[2:].strip() if following.startswith('# ') else None


def _check_result(value: object, comment: str, namespace: dict[str, object]) -> str | None:
    """Why ``value`` is not what ``comment`` says (None: it is, or the comment is prose)."""
    try:
        expected = eval(comment, dict(namespace))  # noqa: S307 - the docs' own text
    except Exception:  # noqa: BLE001 - not an expression: a repr, an abridged repr or prose
        if '...' in comment and re.match(r'\[?[\w.]+\(', comment):
            prefix = comment.split('...', 1)[0].rstrip(', ')
            return None if repr(value).startswith(prefix) else f'{value!r} does not start with {prefix}'
        if re.match(r'\[?[\w.]+\(', comment):
            return None if repr(value) == comment else f'{value!r} != {comment}'
        return None  # prose
    return None if value == expected else f'{value!r} != {comment}'


def test_python_api_examples_run_and_give_the_results_they_show(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """Every example of the Python API page (reference/api.md) runs, in order, in a folder holding
    the examples and the talker/listener it names; each `expression  # result` is checked."""
    import ast
    import contextlib
    import io
    import shutil

    for name in ('talker.nodl.yaml', 'listener.nodl.yaml'):
        shutil.copy(REPO / 'tests' / 'fixtures' / 'readme' / name, tmp_path / name)
    (tmp_path / 'examples').symlink_to(REPO / 'examples')
    blocks = _api_blocks()
    assert len(blocks) >= 5, 'the API section lost its examples (model, names, system, QoS, diagnostics)'
    namespace: dict[str, object] = {}
    problems: list[str] = []
    checked = 0
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        for number, block in enumerate(blocks):
            lines = block.splitlines()
            for statement in ast.parse(block).body:
                where = f'block {number}, line {statement.lineno}'
                with contextlib.redirect_stdout(io.StringIO()):
                    if isinstance(statement, ast.Expr):
                        value = eval(compile(ast.Expression(statement.value), where, 'eval'), namespace)
                    else:
                        exec(compile(ast.Module([statement], []), where, 'exec'), namespace)
                        continue
                comment = _result_comment(lines, statement.end_lineno or statement.lineno)
                if comment is not None:
                    checked += 1
                    problem = _check_result(value, comment, namespace)
                    if problem:
                        problems.append(f'{where}: {problem}')
    finally:
        os.chdir(cwd)
    assert not problems, '\n'.join(problems)
    assert checked >= 20


def test_quoted_extract_example_is_what_the_tool_prints() -> None:
    block = re.search(r'```text\n\$ nodl extract (\S+)\n(.*?)```', README, re.S)
    assert block, 'the docs lost their `nodl extract` example'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'extract', block.group(1)], cwd=REPO,
                            text=True, capture_output=True, timeout=60)
    assert result.returncode == 0, result.stderr
    printed = result.stdout.splitlines()
    for line in block.group(2).splitlines():
        if line and line != '...':
            assert line in printed, line


def test_quoted_overlay_analysis_matches_the_tool() -> None:
    block = re.search(r'```text\n\$ (nodl analyse \S+ --definitions \S+ -v)\n(.*?)```', README, re.S)
    assert block, 'the docs lost their definitions folder example'
    arguments = block.group(1).split()[1:]
    env = {**os.environ, 'PYTHONPATH': str(REPO), 'AMENT_PREFIX_PATH': 'tests/fixtures/analysis/prefix'}
    env.pop('NODL_PATH', None)
    result = subprocess.run([sys.executable, '-m', 'nodl', *arguments], cwd=REPO, env=env,
                            text=True, capture_output=True, timeout=60)
    assert result.returncode == 0, result.stderr
    quoted = [line for line in block.group(2).splitlines() if line and line != '...']
    assert result.stdout.splitlines()[-len(quoted):] == quoted


def test_quoted_monitor_aggregator_config_is_what_the_tool_writes(tmp_path) -> None:  # type: ignore[no-untyped-def]
    block = re.search(r'`(nodl monitor sensor\.nodl\.yaml [^`]*--aggregator-config agg\.yaml)` '
                      r'writes:\n\n```yaml\n(.*?)```', README, re.S)
    assert block, 'the docs lost their `nodl monitor --aggregator-config` example'
    arguments = block.group(1).split()[2:]
    (tmp_path / 'sensor.nodl.yaml').write_text(
        (REPO / 'tests' / 'fixtures' / 'monitor' / 'sensor.nodl.yaml').read_text())
    result = subprocess.run([sys.executable, '-m', 'nodl', 'monitor', *arguments],
                            cwd=tmp_path, env={**os.environ, 'PYTHONPATH': str(REPO)},
                            text=True, capture_output=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / 'agg.yaml').read_text() == block.group(2)


def test_quoted_doc_example_is_what_the_tool_writes(tmp_path) -> None:  # type: ignore[no-untyped-def]
    block = re.search(r'```text\n\$ nodl doc (\S+) -o site\n(.*?)```', README, re.S)
    assert block, 'the docs lost their `nodl doc` example'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'doc', block.group(1), '-o',
                             str(tmp_path / 'site')], cwd=REPO, text=True, capture_output=True,
                            timeout=60, env={**os.environ, 'AMENT_PREFIX_PATH': sys.prefix})
    assert result.returncode == 0, result.stderr
    assert result.stdout.replace(str(tmp_path) + os.sep, '') == block.group(2)
    checked = subprocess.run([sys.executable, '-m', 'nodl', 'doc', block.group(1), '-o',
                              str(tmp_path / 'site'), '--check'], cwd=REPO, text=True,
                             capture_output=True, timeout=60,
                             env={**os.environ, 'AMENT_PREFIX_PATH': sys.prefix})
    assert checked.returncode == 0, checked.stderr


def test_the_integrators_flow_names_what_the_tools_write(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """'From a launch file to a fully covered system': step 2's extract writes the drafts it
    names (with the gap it mentions), the hand-written files of step 4 are the fixture's, and
    its commands are the verbs' (the outputs quoted are checked by
    tests/test_integration_definitions.py, which builds and runs the system)."""
    section = README[README.index('## From a launch file to a fully covered system'):]
    section = section[:section.index('\n## ', 1)]
    fixture = REPO / 'tests' / 'fixtures' / 'integration_definitions'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'extract',
                             str(fixture / 'src' / 'cart_autonomy'), '-o', str(tmp_path / 'extracted')],
                            cwd=REPO, text=True, capture_output=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert '`nodl extract ~/src/cart_autonomy -o extracted`' in section
    for name in ('planner.nodl.yaml', 'mission.nodl.yaml'):
        assert name in section and (tmp_path / 'extracted' / 'cart_autonomy' / name).is_file()
    assert '[NODL901]' in result.stdout + result.stderr and 'NODL901' in section
    for name in re.findall(r'`hand/([\w/]+\.yaml)`', section):
        assert (fixture / 'hand' / name).is_file(), name
    assert '--missing --definitions extracted -o described' in ' '.join(section.split())


def test_the_output_format_example_is_a_working_reporter(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """'An output format': the quoted plug-in, installed under the quoted entry point in a
    site directory, is offered by nodl validate and prints one annotation per diagnostic."""
    section = README[README.index('### An output format'):]
    toml = re.search(r'```toml\n(.*?)```', section, re.S)
    code = re.search(r'```python\n(.*?)```', section, re.S)
    assert toml and code, 'the output format example lost its entry point or its code'
    name, target = re.search(r'(\w+) = "([\w.]+):(\w+)"', toml.group(1)).group(1, 2)  # type: ignore[union-attr]
    module = tmp_path / (target.replace('.', os.sep) + '.py')
    module.parent.mkdir(parents=True)
    for folder in (module.parent, module.parent.parent):
        (folder / '__init__.py').touch()
    module.write_text(code.group(1))
    dist = tmp_path / 'my_package-1.0.dist-info'
    dist.mkdir()
    (dist / 'METADATA').write_text('Metadata-Version: 2.1\nName: my-package\nVersion: 1.0\n')
    (dist / 'entry_points.txt').write_text(f'[nodl.reporters]\n{name} = {target}:'
                                           f'{toml.group(1).rsplit(":", 1)[1].strip().strip(chr(34))}\n')
    invalid = REPO / 'tests' / 'fixtures' / 'invalid' / 'duplicate_endpoints.nodl.yaml'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', '--format', name, str(invalid)],
                            cwd=REPO, text=True, capture_output=True, timeout=60,
                            env={**os.environ, 'PYTHONPATH': str(tmp_path)})
    assert result.returncode == 1, result.stderr
    assert result.stdout.startswith(f'::error file={invalid},line='), result.stdout + result.stderr
