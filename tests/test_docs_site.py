"""The documentation site (ros/nodl_toolkit/doc) builds with sphinx-build -W, and what it
generates at build time (verbs, file formats, codes, API, the examples' node pages) is the
toolkit's own: every verb and option, every schema field, every code, every public name."""

from __future__ import annotations

import html
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import REPO

SITE = REPO / 'ros' / 'nodl_toolkit' / 'doc'
sys.path.insert(0, str(SITE / '_ext'))

import nodl_sphinx  # noqa: E402


def _text(page: Path) -> str:
    """The visible text of a built HTML page, whitespace folded."""
    body = re.sub(r'<script.*?</script>|<style.*?</style>', '', page.read_text(encoding='utf-8'), flags=re.S)
    return ' '.join(html.unescape(re.sub(r'<[^>]+>', ' ', body)).split())


@pytest.fixture(scope='module')
def built(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The site built as `make docs` builds it: from a copy of the folder, warnings as errors."""
    work = tmp_path_factory.mktemp('docs')
    shutil.copytree(SITE, work / 'src', ignore=shutil.ignore_patterns('__pycache__'))
    result = subprocess.run([sys.executable, '-m', 'sphinx', '-W', '--keep-going', '-q', '-b', 'html',
                             str(work / 'src'), str(work / 'html')],
                            cwd=REPO, text=True, capture_output=True, timeout=180,
                            env={**os.environ, 'NODL_REPOSITORY': str(REPO),
                                 'AMENT_PREFIX_PATH': sys.prefix})
    assert result.returncode == 0, result.stdout + result.stderr
    assert 'WARNING' not in result.stderr, result.stderr
    return work / 'html'


def test_the_guides_and_references_are_in_the_site(built: Path) -> None:
    index = _text(built / 'index.html')
    for page in ('guides/getting-started', 'guides/package-authors', 'guides/system-integrators',
                 'guides/security-engineers', 'reference/verbs', 'reference/cli', 'reference/formats',
                 'reference/codes', 'reference/api', 'reference/extending', 'reference/layout',
                 'reference/benchmarks', 'reference/tests', 'examples/index'):
        assert (built / f'{page}.html').is_file(), page
        assert f'{page}.html' in (built / 'index.html').read_text(encoding='utf-8'), page
    assert 'For package authors' in index


def test_every_verb_and_option_is_in_the_verb_reference(built: Path) -> None:
    import argparse

    from nodl.cli.main import build_parser

    page = _text(built / 'reference' / 'verbs.html')
    verbs = nodl_sphinx._subcommands(build_parser())
    assert len(verbs) >= 17
    for name, parser in verbs.items():
        assert f'nodl {name}' in page, name
        for action in parser._actions:
            if action.help == argparse.SUPPRESS:
                continue
            for option in action.option_strings:
                assert option in page, (name, option)
            if action.help and '%' not in action.help:
                assert ' '.join(action.help.split()) in page, (name, action.help)


def test_the_verb_reference_is_generated_from_the_parsers(monkeypatch: pytest.MonkeyPatch) -> None:
    """Not a copy: an option added to a parser is in the page at the next build."""
    import nodl.cli.main as cli_main

    made = cli_main.build_parser

    def with_an_extra_option(argv: list[str] | None = None):  # type: ignore[no-untyped-def]
        parser = made(argv)
        nodl_sphinx._subcommands(parser)['validate'].add_argument(
            '--brand-new-option', help='an option no page was written for')
        return parser

    monkeypatch.setattr(cli_main, 'build_parser', with_an_extra_option)
    text = nodl_sphinx.verbs_markdown()
    assert '- `--brand-new-option BRAND_NEW_OPTION`: an option no page was written for' in text


@pytest.mark.parametrize('kind', ['parameter', 'interface', 'node'])
def test_every_schema_field_is_in_its_format_page(built: Path, kind: str) -> None:
    schema = json.loads((REPO / 'nodl' / 'schemas' / f'{kind}.schema.json').read_text(encoding='utf-8'))
    page = _text(built / 'reference' / f'format-{kind}.html')
    objects = [schema, *schema.get('definitions', {}).values()]
    names = list(schema.get('definitions', {}))
    assert names or schema.get('properties')
    for name in names:
        assert name in page, name
    for shape in objects:
        for field, spec in shape.get('properties', {}).items():
            assert field in page, field
            if spec.get('description'):
                assert ' '.join(spec['description'].split()) in page, field
    # a reference between schemas is a link to the definition's section
    assert 'format-interface.html#schema-interface-' in (
        built / 'reference' / 'format-node.html').read_text(encoding='utf-8')


def test_every_code_is_in_the_codes_page(built: Path) -> None:
    from nodl.codes import CODES

    page = _text(built / 'reference' / 'codes.html')
    for code in CODES:
        assert code in page, code


def test_every_public_name_has_its_api_entry(built: Path) -> None:
    import nodl

    page = (built / 'reference' / 'api.html').read_text(encoding='utf-8')
    for name in nodl.__all__:
        assert f'id="nodl.{name}"' in page, name


def test_the_examples_node_pages_are_written_by_nodl_doc(built: Path) -> None:
    for name, summary in (('laser-driver', 'Reads a 2D laser scanner'), ('camera-lifecycle', None)):
        page = built / 'examples' / 'nodes' / f'{name}.html'
        assert page.is_file(), name
        if summary:
            assert summary in _text(page)
    assert 'nodes/index.html' in (built / 'examples' / 'index.html').read_text(encoding='utf-8')


def test_a_broken_page_fails_the_build(tmp_path: Path) -> None:
    """-W: a warning (here a link to a page that does not exist) fails the build, and the
    generator markers must name a known generator."""
    shutil.copytree(SITE, tmp_path / 'src', ignore=shutil.ignore_patterns('__pycache__'))
    with open(tmp_path / 'src' / 'reference' / 'layout.md', 'a', encoding='utf-8') as page:
        page.write('\nSee [nowhere](nowhere.md).\n\n% nodl:generate nonsense\n')
    result = subprocess.run([sys.executable, '-m', 'sphinx', '-W', '-q', '-b', 'html',
                             str(tmp_path / 'src'), str(tmp_path / 'html')],
                            cwd=REPO, text=True, capture_output=True, timeout=180,
                            env={**os.environ, 'NODL_REPOSITORY': str(REPO),
                                 'AMENT_PREFIX_PATH': sys.prefix})
    assert result.returncode != 0
    assert 'nonsense' in result.stdout + result.stderr or 'nowhere' in result.stdout + result.stderr


def test_the_makefile_builds_the_site_with_warnings_as_errors() -> None:
    makefile = (REPO / 'Makefile').read_text(encoding='utf-8')
    rule = makefile[makefile.index('\ndocs:'):]
    rule = rule[:rule.index('\n\n')]
    assert '-m sphinx -W' in rule and 'build/docs' in rule and 'ros/nodl_toolkit/doc' in rule



def test_rosdoc2_builds_the_site_for_the_package_with_no_warning(tmp_path: Path) -> None:
    """`rosdoc2 build --package-path ros/nodl_toolkit` (rosdoc2 0.2.1, offline: proxies at a
    closed loopback port) builds the same site with no warning: package.xml exports
    rosdoc2.yaml, which names the Sphinx project (doc/) and the Python source (nodl), and
    doc/conf.py leaves out the copy of doc/ that rosdoc2 adds as user_docs/ (else every page,
    label and API entry is there twice)."""
    package = REPO / 'ros' / 'nodl_toolkit'
    assert '<rosdoc2>rosdoc2.yaml</rosdoc2>' in (package / 'package.xml').read_text(encoding='utf-8')
    closed = 'http://127.0.0.1:9'
    venv_bin = str(Path(sys.prefix) / 'bin')  # rosdoc2 runs sphinx-apidoc from PATH
    env = {**os.environ, 'AMENT_PREFIX_PATH': sys.prefix, 'NODL_REPOSITORY': str(REPO),
           'PATH': venv_bin + os.pathsep + os.environ.get('PATH', ''),
           'http_proxy': closed, 'https_proxy': closed, 'HTTP_PROXY': closed,
           'HTTPS_PROXY': closed, 'no_proxy': '', 'NO_PROXY': ''}
    built = subprocess.run([str(Path(venv_bin) / 'rosdoc2'), 'build', '--package-path', str(package),
                            '--output-directory', str(tmp_path / 'site'),
                            '--doc-build-directory', str(tmp_path / 'build'),
                            '--cross-reference-directory', str(tmp_path / 'xref')],
                           cwd=tmp_path, env=env, text=True, capture_output=True, timeout=120)
    log = built.stdout + built.stderr
    assert built.returncode == 0, log
    assert 'build succeeded' in log, log
    assert 'WARNING' not in log and 'ERROR' not in log, log
    assert 'Running sphinx-apidoc' in log, log  # the Python source was found
    site = tmp_path / 'site' / 'nodl_toolkit'
    for page in ('index', 'guides/getting-started', 'guides/package-authors',
                 'guides/system-integrators', 'guides/security-engineers', 'reference/verbs',
                 'reference/codes', 'reference/api', 'examples/nodes/laser-driver'):
        assert (site / f'{page}.html').is_file(), page
    assert 'For package authors' in _text(site / 'index.html')
    assert not (site / 'user_docs').exists()  # the pages are there once
    api = (site / 'reference' / 'api.html').read_text(encoding='utf-8')
    assert 'id="nodl.validate_node"' in api


# -- every command example of the docs is what the command prints ------------------------------

#: ```text blocks whose first line is `$ nodl ...`; the comment line before one may say how to
#: run it (<!-- nodl:example cwd=tmp env=NAME=VALUE -->) or why it cannot run here
#: (<!-- nodl:not-run REASON -->).
EXAMPLE = re.compile(r'(?:^(<!-- nodl:(example|not-run)([^>]*)-->)\n)?^( *)```text\n *\$ (nodl [^\n]*)\n(.*?)\n *```',
                     re.S | re.M)


def _examples() -> list[tuple[str, str, str, str, list[str]]]:
    """(page, marker kind, marker text, command, quoted lines) of every example in the docs."""
    from site_pages import pages

    found = []
    for name, text in pages().items():
        for match in EXAMPLE.finditer(text):
            indent = len(match.group(4))
            quoted = [line[indent:] for line in match.group(6).splitlines()]
            found.append((name, match.group(2) or 'example', (match.group(3) or '').strip(),
                          match.group(5), quoted))
    return found


def _matches(printed: list[str], quoted: list[str]) -> bool:
    """Every quoted line is a printed one, in the same order (`...` and lines the docs leave
    out stand for printed lines not quoted)."""
    at = 0
    for line in quoted:
        if line == '...':
            continue
        try:
            at = printed.index(line, at) + 1
        except ValueError:
            return False
    return True


def test_the_docs_have_command_examples() -> None:
    examples = _examples()
    assert len(examples) >= 8
    for page, kind, marker, command, _quoted in examples:
        if kind == 'not-run':
            assert len(marker) > 20, f'{page}: `{command}`: say why it cannot run here'


@pytest.mark.parametrize('example', _examples(), ids=lambda e: f'{e[0]}: {e[3][:60]}')
def test_every_command_example_prints_what_the_docs_quote(example: tuple[str, str, str, str, list[str]],
                                                         tmp_path: Path) -> None:
    import shlex

    page, kind, marker, command, quoted = example
    if kind == 'not-run':
        return  # the marker says why and which test runs it instead (checked above)
    options = dict(word.split('=', 1) if '=' in word else (word, '') for word in shlex.split(marker))
    env = {**os.environ, 'PYTHONPATH': str(REPO), 'AMENT_PREFIX_PATH': sys.prefix}
    env.pop('NODL_PATH', None)
    for name, value in options.items():
        if name == 'env':
            key, _, setting = value.partition('=')
            env[key] = setting
    cwd = REPO
    if options.get('cwd') == 'tmp':  # an example that writes files runs in a folder of its own
        cwd = tmp_path
        for name in ('tests', 'examples'):
            (tmp_path / name).symlink_to(REPO / name)
    arguments = shlex.split(command)[1:]
    result = subprocess.run([sys.executable, '-m', 'nodl', *arguments], cwd=cwd, env=env, text=True,
                            capture_output=True, timeout=60)
    printed = (result.stdout + result.stderr).replace(str(tmp_path) + os.sep, '').splitlines()
    while quoted and not quoted[-1]:
        quoted = quoted[:-1]
    assert _matches(printed, quoted), f'{page}: $ {command}\n' + '\n'.join(printed)


def test_a_quoted_line_the_command_does_not_print_is_caught() -> None:
    assert _matches(['a', 'b', 'c'], ['a', '...', 'c'])
    assert not _matches(['a', 'b'], ['b', 'a'])
    assert not _matches(['a', 'b'], ['a', 'changed'])


# -- every shell example of the docs runs, or says why it cannot run here ----------------------

#: ```sh / ```console / ```bash / ```shell blocks (commands, no quoted output), with the marker
#: comment line before one: <!-- nodl:example exit=N --> (the status every command of it
#: exits with, 0 unless given) or <!-- nodl:not-run REASON -->.
SHELL_BLOCK = re.compile(r'(?:^ *(<!-- nodl:(example|not-run)([^>]*)-->)\n)?^( *)```(sh|console|bash|shell)\n'
                         r'(.*?)\n *```', re.S | re.M)

#: The commands an unmarked block may hold besides nodl: they only set up its folder.
SET_UP = {'mkdir', 'cd', 'cp', 'ls', 'cat', 'diff'}


def _commands(language: str, body: str, indent: int) -> list[str]:
    """The command lines of a shell block (a console block's `$ ` lines; `\\` joins lines)."""
    lines = [line[indent:] for line in body.splitlines()]
    if language == 'console':
        lines = [line[2:] for line in lines if line.startswith('$ ')]
    commands: list[str] = []
    for line in lines:
        if commands and commands[-1].endswith('\\'):
            commands[-1] = commands[-1][:-1] + line
        elif line.strip() and not line.lstrip().startswith('#'):
            commands.append(line)
    return commands


def _programs(command: str) -> list[str]:
    """The programs one command line runs (first words, and after `&&`, `||`, `;`, `|`, `(`)."""
    import shlex

    lexer = shlex.shlex(command, posix=True, punctuation_chars=True)
    lexer.commenters = '#'
    programs, first = [], True
    for token in lexer:
        if token in ('&&', '||', ';', '|', '(', ')', '&'):
            first = True
        elif first:
            programs.append(token)
            first = False
    return programs


def _shell_blocks() -> list[tuple[str, int, str, str, list[str]]]:
    """(page, line, marker kind, marker text, command lines) of every shell block of the docs."""
    from site_pages import pages

    found = []
    for name, text in pages().items():
        for match in SHELL_BLOCK.finditer(text):
            line = text.count('\n', 0, match.start(4)) + 1
            found.append((name, line, match.group(2) or 'example', (match.group(3) or '').strip(),
                          _commands(match.group(5), match.group(6), len(match.group(4)))))
    return found


def _run_block(block: tuple[str, int, str, str, list[str]], work: Path) -> tuple[str, list[tuple[str, int]]]:
    """Run one block's commands in order in one bash, in a folder of its own holding a copy of
    examples/ (tests/ linked, read only) with HOME there too: its output, and each command's
    exit status."""
    work.mkdir(parents=True)
    shutil.copytree(REPO / 'examples', work / 'examples', symlinks=True,
                    ignore=shutil.ignore_patterns('__pycache__'))
    (work / 'tests').symlink_to(REPO / 'tests')
    shim = work / '.bin'
    shim.mkdir()
    (shim / 'nodl').write_text(f'#!/bin/sh\nexec "{sys.executable}" -m nodl "$@"\n', encoding='utf-8')
    (shim / 'nodl').chmod(0o755)
    script = ''.join(f'{command}\nprintf "\\n@@status %s\\n" "$?"\n' for command in block[4])
    env = {**os.environ, 'PYTHONPATH': str(REPO), 'AMENT_PREFIX_PATH': sys.prefix, 'HOME': str(work),
           'PATH': str(shim) + os.pathsep + os.environ.get('PATH', '')}
    env.pop('NODL_PATH', None)
    result = subprocess.run(['bash', '--noprofile', '--norc', '-c', script], cwd=work, env=env,
                            text=True, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
    statuses = [int(status) for status in re.findall(r'^@@status (\d+)$', result.stdout, re.M)]
    return result.stdout, list(zip(block[4], statuses, strict=False))


@pytest.fixture(scope='module')
def shell_runs(tmp_path_factory: pytest.TempPathFactory) -> dict[tuple[str, int], tuple[str, list[tuple[str, int]]]]:
    """Every block that is not marked not-run, run at once (each in its own folder)."""
    from concurrent.futures import ThreadPoolExecutor

    root = tmp_path_factory.mktemp('shell-examples')
    blocks = [block for block in _shell_blocks() if block[2] != 'not-run']
    with ThreadPoolExecutor(max_workers=4) as pool:
        runs = pool.map(lambda numbered: _run_block(numbered[1], root / str(numbered[0])), enumerate(blocks))
        return {(block[0], block[1]): run for block, run in zip(blocks, runs, strict=True)}


def test_the_docs_have_shell_examples_that_run() -> None:
    blocks = _shell_blocks()
    assert len(blocks) >= 10
    run = [block for block in blocks if block[2] != 'not-run']
    assert len(run) >= 3 and sum(len(block[4]) for block in run) >= 5
    for page, line, kind, marker, commands in blocks:
        assert commands, f'{page}:{line}: a shell block with no command'
        if kind == 'not-run':
            assert len(marker) > 20, f'{page}:{line}: say why it cannot run here'


@pytest.mark.parametrize('block', _shell_blocks(), ids=lambda b: f'{b[0]}:{b[1]}')
def test_every_shell_example_runs_or_says_why_not(
        block: tuple[str, int, str, str, list[str]],
        shell_runs: dict[tuple[str, int], tuple[str, list[tuple[str, int]]]]) -> None:
    import shlex

    page, line, kind, marker, commands = block
    if kind == 'not-run':
        return  # the marker says why (checked above)
    for command in commands:
        programs = _programs(command)
        assert 'nodl' in programs or set(programs) <= SET_UP, (
            f'{page}:{line}: `{command}` cannot run in the test: run only nodl and folder set-up '
            f'({", ".join(sorted(SET_UP))}) or mark the block <!-- nodl:not-run REASON -->')
        assert set(programs) <= SET_UP | {'nodl'}, (
            f'{page}:{line}: `{command}`: {set(programs) - SET_UP - {"nodl"}} cannot run in the test; '
            'mark the block <!-- nodl:not-run REASON -->')
    options = dict(word.split('=', 1) if '=' in word else (word, '') for word in shlex.split(marker))
    expected = int(options.get('exit', '0'))
    output, statuses = shell_runs[(page, line)]
    assert len(statuses) == len(commands), f'{page}:{line}: the block stopped early\n{output}'
    for command, status in statuses:
        assert status == expected, f'{page}:{line}: `{command}` exited {status}, not {expected}\n{output}'


def test_a_shell_example_that_fails_or_is_not_nodl_is_caught(tmp_path: Path) -> None:
    assert _programs('mkdir -p .vscode && nodl schema node -o x.json  # a comment; rm') == ['mkdir', 'nodl']
    assert _programs('(cd /tmp/ws && colcon build)') == ['cd', 'colcon']
    assert _commands('sh', '  nodl validate a \\\n  b  # why\n  # a comment\n', 2) == ['nodl validate a b  # why']
    assert _commands('console', '$ nodl show x\nprinted\n', 0) == ['nodl show x']
    output, statuses = _run_block(('page', 1, 'example', '', ['nodl validate examples/',
                                                              'nodl show no/such/file.nodl.yaml']),
                                  tmp_path / 'run')
    assert statuses[0][1] == 0 and statuses[1][1] != 0, output


def test_the_security_engineers_guide_holds_what_a_security_engineer_needs(built: Path) -> None:
    """Policies, what runs when a launch file is read, the hostile-input limits, text safety
    and the writing rules: in the guide, or linked from it to where the details live."""
    page = built / 'guides' / 'security-engineers.html'
    text = _text(page)
    for words in ('nodl policy', '--check', '--live', '--enclave-map', 'XInclude', '1,000 includes',
                  '--no-exec', '$(command)', '$(eval)', '--launch-timeout', '--launch-memory',
                  'sandboxed child', '16 MiB', '10 MB', '100 levels', 'NODL219', 'NODL220', 'NODL221',
                  'NODL222', 'NODL223', 'NODL224', 'Every writer escapes', 'Atomic', 'Modes kept',
                  'Links replaced, never followed', 'An output is never an input', 'Content markers',
                  '--force'):
        assert words in text, words
    markup = page.read_text(encoding='utf-8')
    assert 'system-integrators.html#reading-launch-files' in markup
    assert '../reference/cli.html#how-files-are-written-and-force' in markup


def test_no_shared_file_points_at_a_readme_section_that_moved() -> None:
    """The README is a short first page: code, tests, docs and examples point at the site's
    pages, not at README sections that are no longer there."""
    stale = re.compile(r"(in|see) the README\b(?! of)(?!$)|README's|README lost|README\.md#")
    found = []
    for folder in ('nodl', 'ros', 'tests', 'docs', 'examples'):
        for path in sorted((REPO / folder).rglob('*')):
            if path.suffix not in ('.py', '.md', '.txt', '.toml', '.cmake', '.xml', '.yaml') or not path.is_file():
                continue
            if path == Path(__file__) or 'fixtures' in path.parts:
                continue
            for number, line in enumerate(path.read_text(encoding='utf-8', errors='replace').splitlines(), 1):
                if stale.search(line):
                    found.append(f'{path.relative_to(REPO)}:{number}: {line.strip()}')
    assert not found, '\n'.join(found)
