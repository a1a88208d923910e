"""The import contracts between nodl's layers (issue 16), held by the real tool.

``pyproject.toml``'s ``[tool.importlinter]`` states them: the shared layers import no
feature, a feature imports shared layers only (never another feature), and no two
packages (or modules) import each other, however indirectly.  import-linter reads every
import, those inside functions too, as grimp finds them; so does the package-cycle check
here, with grimp itself.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import grimp
import pytest

REPO = Path(__file__).resolve().parent.parent
LINT_IMPORTS = Path(sys.executable).with_name('lint-imports')

#: Packages whose own modules still import each other in a circle, and why that is not a
#: cycle between packages.  Each entry goes when its cycle does (a test says so).
KNOWN_MODULE_CYCLES = {
    # New this stop (nodl system): the composition and its operations.
    'nodl.composer': 'the composer\'s model and its operations',
}


def _lint_imports(root: Path) -> subprocess.CompletedProcess[str]:
    """``lint-imports`` with ``root``'s configuration, on the packages under ``root``."""
    return subprocess.run([str(LINT_IMPORTS), '--no-cache', str(root / 'pyproject.toml')],
                          cwd=root, capture_output=True, text=True, timeout=120)


def test_the_import_contracts_hold() -> None:
    result = _lint_imports(REPO)
    assert result.returncode == 0, result.stdout + result.stderr
    assert ' broken' not in result.stdout.replace('0 broken', '')


def _copy_of_the_packages(destination: Path) -> Path:
    for package in ('nodl', 'nodl_schema'):
        shutil.copytree(REPO / package, destination / package,
                        ignore=shutil.ignore_patterns('__pycache__', 'node_modules', 'static'))
    shutil.copy(REPO / 'pyproject.toml', destination / 'pyproject.toml')
    return destination


def _add_import(root: Path, module: str, imported: str) -> None:
    """An import of ``imported`` inside a function of ``module`` (a place imports hide in)."""
    path = root / (module.replace('.', '/') + '.py')
    if not path.exists():
        path = root / module.replace('.', '/') / '__init__.py'
    with path.open('a', encoding='utf-8') as f:
        f.write(f'\n\ndef _added_by_the_test() -> None:\n    import {imported}  # noqa\n')


def test_a_feature_importing_a_feature_or_a_layer_importing_a_feature_breaks_a_contract(
        tmp_path: Path) -> None:
    root = _copy_of_the_packages(tmp_path)
    _add_import(root, 'nodl.policy.names', 'nodl.doc.html')
    _add_import(root, 'nodl.vocabulary', 'nodl.analysis')
    result = _lint_imports(root)
    assert result.returncode == 1, result.stdout
    assert 'nodl.policy is not allowed to import nodl.doc' in result.stdout
    assert 'nodl.policy.names -> nodl.doc.html' in result.stdout
    assert 'nodl.vocabulary is not allowed to import nodl.analysis' in result.stdout


def test_a_cycle_between_shared_layers_breaks_a_contract(tmp_path: Path) -> None:
    root = _copy_of_the_packages(tmp_path)
    _add_import(root, 'nodl.vocabulary', 'nodl.registry')  # the registry uses the vocabulary
    result = _lint_imports(root)
    assert result.returncode == 1, result.stdout
    assert 'No cycles are allowed in nodl.' in result.stdout
    assert 'vocabulary' in result.stdout.split('No cycles are allowed in nodl.')[1]


def _children(graph: grimp.ImportGraph, package: str) -> dict[str, str]:
    """Every module below ``package`` -> the child of ``package`` it belongs to."""
    owner = {}
    for module in graph.find_descendants(package):
        owner[module] = f'{package}.{module[len(package) + 1:].split(".")[0]}'
    return owner


def _cycles(graph: grimp.ImportGraph, package: str) -> list[set[str]]:
    """The strongly connected sets (of two or more) of ``package``'s children."""
    owner = _children(graph, package)
    edges: dict[str, set[str]] = {child: set() for child in owner.values()}
    for module, child in owner.items():
        for imported in graph.find_modules_directly_imported_by(module):
            other = owner.get(imported)
            if other is not None and other != child:
                edges[child].add(other)
    # Tarjan's algorithm, iteratively
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[set[str]] = []
    for start in sorted(edges):
        if start in index:
            continue
        work = [(start, iter(sorted(edges[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, successors = work[-1]
            for successor in successors:
                if successor not in index:
                    index[successor] = low[successor] = len(index)
                    stack.append(successor)
                    on_stack.add(successor)
                    work.append((successor, iter(sorted(edges[successor]))))
                    break
                if successor in on_stack:
                    low[node] = min(low[node], index[successor])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = set()
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.add(member)
                        if member == node:
                            break
                    if len(component) > 1:
                        found.append(component)
    return found


@pytest.fixture(scope='module')
def graph() -> grimp.ImportGraph:
    spec_origin = Path(__import__('nodl').__file__ or '').resolve()
    assert spec_origin.parent == REPO / 'nodl', f'nodl imported from {spec_origin}, not the tree'
    return grimp.build_graph('nodl', cache_dir=None)


def test_no_package_cycle_in_nodl(graph: grimp.ImportGraph) -> None:
    """No two packages of nodl import each other, directly or through others, at any depth
    (imports inside functions count): every cycle found is listed with its members."""
    packages = sorted(m for m in graph.modules if graph.find_children(m))
    problems = []
    for package in packages:
        for cycle in _cycles(graph, package):
            subpackages = {member for member in cycle if graph.find_children(member)}
            if package in KNOWN_MODULE_CYCLES and not subpackages:
                continue  # modules of one package (listed above, with the reason)
            problems.append(f'{package}: {", ".join(sorted(cycle))}')
    assert not problems, 'package cycles:\n' + '\n'.join(problems)


def test_the_known_module_cycles_are_still_there(graph: grimp.ImportGraph) -> None:
    """An entry of KNOWN_MODULE_CYCLES goes when its cycle does."""
    gone = [package for package in KNOWN_MODULE_CYCLES if not _cycles(graph, package)]
    assert not gone, f'no cycle left in {gone}: remove them from KNOWN_MODULE_CYCLES'


def test_the_cycle_finder_finds_a_cycle() -> None:
    graph = grimp.ImportGraph()
    for module in ('p', 'p.a', 'p.a.x', 'p.b', 'p.c'):
        graph.add_module(module)
    graph.add_import(importer='p.a.x', imported='p.b')
    graph.add_import(importer='p.b', imported='p.a')
    graph.add_import(importer='p.c', imported='p.b')
    assert _cycles(graph, 'p') == [{'p.a', 'p.b'}]
