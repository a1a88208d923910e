"""The code catalogue (nodl.codes) and the code that reports diagnostics stay in step."""

from __future__ import annotations

import re
from pathlib import Path

from nodl.codes import CODES, RANGES, catalogue_markdown, close_codes, default_severity, explain

REPO = Path(__file__).resolve().parent.parent
LIBRARY = REPO / 'nodl'
CODE = re.compile(r'NODL[0-9]{3}')


def _used() -> dict[str, list[str]]:
    used: dict[str, list[str]] = {}
    for path in sorted(LIBRARY.rglob('*.py')):
        if path.name == 'codes.py' and path.parent == LIBRARY:
            continue
        for code in CODE.findall(path.read_text(encoding='utf-8')):
            used.setdefault(code, []).append(str(path.relative_to(REPO)))
    return used


def test_every_code_used_in_the_library_is_catalogued() -> None:
    unknown = {code: files for code, files in _used().items() if code not in CODES}
    assert not unknown, f'add these codes to nodl/codes.py: {unknown}'


def test_every_catalogued_code_is_used_somewhere() -> None:
    unused = sorted(set(CODES) - set(_used()))
    assert not unused, f'catalogued but never reported (remove them, or report them): {unused}'


def test_no_code_is_catalogued_twice() -> None:
    """A dict literal keeps the last of two equal keys silently: read the source itself."""
    import ast

    tree = ast.parse((LIBRARY / 'codes.py').read_text(encoding='utf-8'))
    keys = [node.value for table in ast.walk(tree) if isinstance(table, ast.Dict)
            for node in table.keys if isinstance(node, ast.Constant) and isinstance(node.value, str)
            and CODE.fullmatch(node.value)]
    duplicates = sorted({key for key in keys if keys.count(key) > 1})
    assert not duplicates, f'catalogued twice in nodl/codes.py: {duplicates}'


def test_entries_are_well_formed_and_in_order() -> None:
    assert list(CODES) == sorted(CODES)
    for code, (severity, explanation) in CODES.items():
        assert CODE.fullmatch(code), code
        assert code[4] in RANGES, code
        assert severity in ('error', 'warning', 'info'), code
        assert explanation and '\n' not in explanation and not explanation.endswith('.'), code
    assert len({e for _, e in CODES.values()}) == len(CODES), 'two codes share an explanation'


def test_lookups() -> None:
    assert default_severity('NODL216') == 'warning'
    assert explain('NODL101') == 'unknown key'
    assert close_codes('nodl21') and close_codes('nodl21')[0].startswith('NODL21')
    assert close_codes('completely different') == []


def test_docs_catalogue_is_the_generated_one() -> None:
    docs = REPO / 'docs' / 'diagnostics.md'
    assert docs.read_text(encoding='utf-8') == catalogue_markdown(), (
        'docs/diagnostics.md is out of date: regenerate it with '
        "python -c 'from nodl.codes import catalogue_markdown as m; "
        "open(\"docs/diagnostics.md\", \"w\").write(m())'")
    listed = re.findall(r'^\| (NODL[0-9]{3}) \|', docs.read_text(encoding='utf-8'), re.M)
    assert listed == list(CODES)


def test_readme_links_the_catalogue() -> None:
    assert '(docs/diagnostics.md)' in (REPO / 'README.md').read_text(encoding='utf-8')


def _output_or_exit(tree: object) -> list[tuple[int, str]]:
    """Every place in a module's code (not its docstrings) that prints, writes a standard
    stream or exits: print(...), sys.exit(...), sys.stdout/stderr/__stdout__... .write(...),
    raising or making a SystemExit, and a class derived from it.  Catching one (the user's
    code run by the launch reader may call sys.exit()) is not exiting."""
    import ast

    def is_exit(node: object) -> bool:
        target = node.func if isinstance(node, ast.Call) else node
        return isinstance(target, ast.Name) and target.id == 'SystemExit'

    found = []
    for node in ast.walk(tree):  # type: ignore[arg-type]
        if isinstance(node, ast.Call):
            text = ast.unparse(node.func)
            if text in ('print', 'sys.exit', 'exit', 'quit', 'os._exit', 'SystemExit') or re.fullmatch(
                    r'sys\.(__)?std(out|err)(__)?\.(write|writelines)', text):
                found.append((node.lineno, text))
        elif isinstance(node, ast.Raise) and node.exc is not None and is_exit(node.exc):
            found.append((node.lineno, 'raise SystemExit'))
        elif isinstance(node, ast.ClassDef) and any(is_exit(base) for base in node.bases):
            found.append((node.lineno, 'a SystemExit class'))
    return sorted(set(found))


def test_library_never_prints_or_exits() -> None:
    """Outside the command line, the library returns diagnostics or raises documented errors."""
    import ast

    # The one exception, and why: the setup.py helper's documented error is a SystemExit so
    # that a build stops with its diagnostics and no traceback (see NodlBuildError).
    # The launch sandbox's forked child ends with os._exit: it must never return into (or run
    # the exit handlers of) the process it is a copy of.
    allowed = {('packaging.py', 'class NodlBuildError(SystemExit):'),
               ('launch/sandbox.py', "os._exit(status)  # the forked child ends here: it never returns "
                                     "into the caller's code")}
    offenders = []
    for path in sorted(LIBRARY.rglob('*.py')):
        relative = path.relative_to(LIBRARY)
        if relative.parts[0] == 'cli' or relative.as_posix() == '__main__.py':
            continue
        text = path.read_text(encoding='utf-8')
        lines = text.splitlines()
        for number, what in _output_or_exit(ast.parse(text)):
            line = lines[number - 1].strip()
            if (relative.as_posix(), line) not in allowed:
                offenders.append(f'{relative}:{number}: {what}: {line}')
    assert not offenders, '\n'.join(offenders)


def test_the_output_check_finds_what_it_looks_for() -> None:
    import ast

    code = ('print(1)\nsys.exit(2)\nsys.stderr.write("x")\nsys.__stdout__.write("y")\n'
            'raise SystemExit(3)\n"""print(4) in a docstring"""\n# print(5)\nfile.write("z")\n'
            'class Stop(SystemExit): pass\nraise SystemExit\n'
            'try:\n    run()\nexcept SystemExit:\n    pass\nisinstance(e, SystemExit)\n')
    assert sorted({n for n, _ in _output_or_exit(ast.parse(code))}) == [1, 2, 3, 4, 5, 9, 10]
