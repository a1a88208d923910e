"""What ``nodl extract PATH...`` reads: packages, their executables, and loose source files.

A PATH is a package (a folder with ``package.xml``, ``setup.py`` or ``setup.cfg``), a folder
holding packages, or source files.  For a Python package, ``setup.py`` (read with ``ast``, never
run) and ``setup.cfg`` give the package name, the console-script entry points (which function
of which module each executable runs) and the generate_parameter_library modules
(``generate_parameter_module(NAME, YAML)``).  Other build systems plug in through
:data:`BUILD_READERS` (a reader of ``CMakeLists.txt`` for C++ packages) and other languages
through :data:`LANGUAGES`.
"""

from __future__ import annotations

import ast
import copy
import os
from dataclasses import dataclass, field

from nodl_schema.diagnostics import Diagnostic, Severity
from nodl_schema.extract.model import ExtractedNode, Extraction

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any, Callable, Iterable

__all__ = ['Package', 'BUILD_READERS', 'LANGUAGES', 'find_packages', 'read_python_build',
           'extract_paths', 'output_paths']

_SKIPPED_FOLDERS = {'build', 'install', 'log', '.git', '__pycache__', 'node_modules', '.venv', 'venv',
                    '.tox', '.mypy_cache', '.pytest_cache'}


@dataclass(slots=True)
class Package:
    """A package (or a set of loose files, ``name`` None) and what its build files say.

    ``executables``: executable -> ``(source file, function)`` (for Python, the module file and
    the function an entry point runs; for C++, the file and ``''``).  ``genparam``: a
    generate_parameter_library module (dotted) -> its YAML file.
    """

    name: str | None
    root: str
    files: list[str] = field(default_factory=list)
    executables: dict[str, tuple[str, str]] = field(default_factory=dict)
    genparam: dict[str, str] = field(default_factory=dict)
    diagnostics: list[Diagnostic] = field(default_factory=list)


def _package_xml_name(root: str) -> str | None:
    path = os.path.join(root, 'package.xml')
    try:
        import xml.etree.ElementTree as ET

        with open(path, 'rb') as handle:
            raw = handle.read(1024 * 1024)
        if b'<!DOCTYPE' in raw or b'<!ENTITY' in raw:
            return None
        name = ET.fromstring(raw).findtext('name')
    except (OSError, ET.ParseError):
        return None
    return name.strip() if name else None


def _literal(expr: ast.expr, constants: dict[str, Any]) -> Any:
    """A setup.py value: literals, names of module constants, ``+`` and f-strings of them."""
    if isinstance(expr, ast.Constant):
        return expr.value
    if isinstance(expr, ast.Name):
        return constants.get(expr.id)
    if isinstance(expr, (ast.List, ast.Tuple)):
        return [_literal(e, constants) for e in expr.elts]
    if isinstance(expr, ast.Dict):
        return {_literal(k, constants): _literal(v, constants) for k, v in zip(expr.keys, expr.values)
                if k is not None}
    if isinstance(expr, ast.BinOp) and isinstance(expr.op, ast.Add):
        left, right = _literal(expr.left, constants), _literal(expr.right, constants)
        if isinstance(left, str) and isinstance(right, str):
            return left + right
        if isinstance(left, list) and isinstance(right, list):
            return left + right
        return None
    if isinstance(expr, ast.JoinedStr):
        parts = []
        for part in expr.values:
            value = _literal(part.value, constants) if isinstance(part, ast.FormattedValue) else \
                _literal(part, constants)
            if not isinstance(value, str):
                return None
            parts.append(value)
        return ''.join(parts)
    return None


def _entry_points(value: Any) -> list[str]:
    if isinstance(value, dict):
        scripts = value.get('console_scripts')
        if isinstance(scripts, str):
            return [line for line in scripts.splitlines() if line.strip()]
        if isinstance(scripts, list):
            return [s for s in scripts if isinstance(s, str)]
    return []


def _add_entry(package: Package, spec: str, where: str) -> None:
    name, _, target = spec.partition('=')
    module, _, function = target.strip().partition(':')
    name, module = name.strip(), module.strip()
    if not name or not module:
        return
    path = os.path.join(package.root, *module.split('.')) + '.py'
    if not os.path.isfile(path):
        init = os.path.join(package.root, *module.split('.'), '__init__.py')
        path = init if os.path.isfile(init) else path
    package.executables[name] = (path, function.strip().split('.')[0] or 'main')


def read_python_build(root: str) -> Package | None:
    """A Python package's name, entry points and generate_parameter_library modules, from
    ``setup.py`` and ``setup.cfg`` (None when the folder has neither)."""
    setup_py = os.path.join(root, 'setup.py')
    setup_cfg = os.path.join(root, 'setup.cfg')
    if not os.path.isfile(setup_py) and not os.path.isfile(setup_cfg):
        return None
    package = Package(_package_xml_name(root), root)
    if os.path.isfile(setup_cfg):
        import configparser

        parser = configparser.ConfigParser(interpolation=None)
        try:
            parser.read(setup_cfg, encoding='utf-8')
            if package.name is None and parser.has_option('metadata', 'name'):
                package.name = parser.get('metadata', 'name').strip()
            if parser.has_option('options.entry_points', 'console_scripts'):
                for line in parser.get('options.entry_points', 'console_scripts').splitlines():
                    if line.strip():
                        _add_entry(package, line, setup_cfg)
        except (configparser.Error, UnicodeDecodeError, OSError) as exc:
            package.diagnostics.append(Diagnostic(
                Severity.WARNING, f'setup.cfg cannot be read ({type(exc).__name__}): its entry points are '
                'not used', file=setup_cfg, code='NODL911'))
    if os.path.isfile(setup_py):
        from nodl_schema.extract.python import read_source

        text, problem = read_source(setup_py)
        try:
            tree = ast.parse(text or '', filename=setup_py)
        except (SyntaxError, ValueError, RecursionError):
            tree = None
        if problem is not None or tree is None:
            package.diagnostics.append(Diagnostic(
                Severity.WARNING, 'setup.py cannot be read: its entry points are not used, so nodes are named '
                'after their classes', file=setup_py, line=1, column=1, code='NODL911'))
            return package
        constants: dict[str, Any] = {}
        for stmt in tree.body:
            if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name):
                constants[stmt.targets[0].id] = _literal(stmt.value, constants)
        for call in ast.walk(tree):
            if not isinstance(call, ast.Call):
                continue
            callee = call.func.attr if isinstance(call.func, ast.Attribute) else \
                call.func.id if isinstance(call.func, ast.Name) else ''
            if callee == 'setup':
                for keyword in call.keywords:
                    if keyword.arg == 'name' and package.name is None:
                        name = _literal(keyword.value, constants)
                        package.name = name if isinstance(name, str) else None
                    elif keyword.arg == 'entry_points':
                        for spec in _entry_points(_literal(keyword.value, constants)):
                            _add_entry(package, spec, setup_py)
            elif callee == 'generate_parameter_module' and len(call.args) >= 2:
                module, yaml_file = (_literal(a, constants) for a in call.args[:2])
                if isinstance(module, str) and isinstance(yaml_file, str):
                    owner = package.name or os.path.basename(root)
                    package.genparam[f'{owner}.{module}'] = os.path.join(root, yaml_file)
    return package


#: Readers of build files, tried in order on each package folder: each returns a
#: :class:`Package` (its executables and generated-parameter modules) or None.  A reader for
#: another build system (CMakeLists.txt) is added here.
BUILD_READERS: list[Callable[[str], Package | None]] = [read_python_build]

#: Source extensions -> the extractor of that language: ``(files, package) -> Extraction``.
#: The Python extractor is built in; another language is added here.
LANGUAGES: dict[str, Callable[[list[str], Package], Extraction]] = {}


def _extract_python(files: list[str], package: Package) -> Extraction:
    from nodl_schema.extract.python import extract_file

    out = Extraction()
    for path in files:
        rel = os.path.relpath(os.path.dirname(path), package.root)
        module_package = '.'.join(p for p in rel.split(os.sep) if p not in ('', '.')) or None
        out.extend(extract_file(path, package=module_package, genparam=package.genparam))
    return out


LANGUAGES['.py'] = _extract_python


def _is_package(folder: str) -> bool:
    return any(os.path.isfile(os.path.join(folder, marker))
               for marker in ('package.xml', 'setup.py', 'setup.cfg', 'CMakeLists.txt'))


def _source_files(root: str, stop_at_packages: bool) -> list[str]:
    found: list[str] = []
    for folder, folders, files in os.walk(root):
        folders[:] = sorted(f for f in folders if f not in _SKIPPED_FOLDERS and not f.startswith('.')
                            and not (stop_at_packages and _is_package(os.path.join(folder, f)))
                            and not os.path.isfile(os.path.join(folder, f, 'COLCON_IGNORE')))
        for name in sorted(files):
            if os.path.splitext(name)[1] in LANGUAGES and name != 'setup.py':
                found.append(os.path.join(folder, name))
    return found


def _read_package(root: str) -> Package:
    for reader in BUILD_READERS:
        package = reader(root)
        if package is not None:
            break
    else:
        package = Package(_package_xml_name(root), root)
    package.files = _source_files(root, stop_at_packages=True)
    return package


def find_packages(paths: Iterable[str]) -> tuple[list[Package], list[Diagnostic]]:
    """The packages (and loose files) named by ``paths``, and a NODL020 diagnostic for each path
    that cannot be read."""
    from nodl_schema.files import describe_os_error

    packages: list[Package] = []
    problems: list[Diagnostic] = []
    loose = Package(None, os.getcwd())
    for path in paths:
        try:
            os.stat(path)
        except OSError as exc:
            problems.append(Diagnostic(Severity.ERROR, f'cannot read {path}: {describe_os_error(exc)}',
                                       file=path, code='NODL020'))
            continue
        if os.path.isfile(path):
            loose.files.append(path)
            continue
        if _is_package(path):
            packages.append(_read_package(path))
            continue
        inner = []
        for folder, folders, _files in os.walk(path):
            folders[:] = sorted(f for f in folders if f not in _SKIPPED_FOLDERS and not f.startswith('.'))
            if folder != path and _is_package(folder):
                if not os.path.isfile(os.path.join(folder, 'COLCON_IGNORE')):
                    inner.append(_read_package(folder))
                folders[:] = []
        if inner:
            packages += inner
        else:
            loose.files += _source_files(path, stop_at_packages=False)
    if loose.files:
        packages.append(loose)
    return packages, problems


def _assign_executables(package: Package, extraction: Extraction) -> list[ExtractedNode]:
    """Give each node its package and executable; a node no entry point runs keeps its name, with
    a NODL911 note.  A node class several executables run is one node per executable."""
    out: list[ExtractedNode] = []
    by_file: dict[str, list[ExtractedNode]] = {}
    for node in extraction.nodes:
        node.package = package.name
        by_file.setdefault(os.path.realpath(node.location.file), []).append(node)
    starts = {os.path.realpath(f): calls for f, calls in extraction.starts.items()}
    used: set[int] = set()
    for executable, (path, function) in sorted(package.executables.items()):
        real = os.path.realpath(path)
        called = starts.get(real, {}).get(function, [])
        here = by_file.get(real, [])
        started = [n for n in here if n.made_by == 'call' and n.made_in in (function, '')]
        for name in called:  # node classes of the same module first, then of the package
            same = [n for n in here if n.made_by == 'class' and n.name == name]
            other = same or [n for n in extraction.nodes if n.made_by == 'class' and n.name == name][:1]
            started += [n for n in other if n not in started]
        for node in started:
            copy_ = node if id(node) not in used else copy.deepcopy(node)
            used.add(id(node))
            copy_.executable = executable
            out.append(copy_)
    for node in extraction.nodes:
        if id(node) in used:
            continue
        where = 'its package has no entry point that runs it' if package.name else \
            'it is not in a package (no setup.py or setup.cfg maps executables)'
        node.notes.append(Diagnostic(Severity.INFO, f"node '{node.name}': {where}; its draft is named "
                                     f"'{node.name}'", file=node.location.file, line=node.location.line,
                                     column=node.location.column, code='NODL911'))
        out.append(node)
    return out


def extract_paths(paths: Iterable[str]) -> Extraction:
    """Extract every node of the packages, folders and files in ``paths``."""
    packages, problems = find_packages(paths)
    result = Extraction(diagnostics=problems)
    for package in packages:
        result.diagnostics += package.diagnostics
        by_language: dict[str, list[str]] = {}
        for path in package.files:
            by_language.setdefault(os.path.splitext(path)[1], []).append(path)
        found = Extraction()
        for suffix, files in by_language.items():
            found.extend(LANGUAGES[suffix](files, package))
        result.diagnostics += found.diagnostics
        result.files += found.files
        result.nodes += _assign_executables(package, found)
    if not result.nodes and not any(d.severity is Severity.ERROR for d in result.diagnostics):
        shown = ', '.join(paths) if not isinstance(paths, str) else paths
        result.diagnostics.append(Diagnostic(
            Severity.ERROR, f'no node found in {shown}: no class derived from an rclpy Node or LifecycleNode, '
            'and no node made with Node(...) or rclpy.create_node(...)', file=str(shown), code='NODL912'))
    return result


def output_paths(extraction: Extraction) -> dict[int, str]:
    """The relative path of each node's draft in the overlay layout
    (``<package>/<executable>.nodl.yaml``; ``<name>.nodl.yaml`` outside packages), by ``id(node)``;
    nodes of one executable are told apart by their names."""
    counts: dict[tuple[str | None, str], int] = {}
    for node in extraction.nodes:
        key = (node.package, node.output_name)
        counts[key] = counts.get(key, 0) + 1
    out: dict[int, str] = {}
    for node in extraction.nodes:
        stem = node.output_name
        if counts[(node.package, stem)] > 1:
            stem = f'{stem}__{node.node_name or node.name}'
        stem = stem.replace(os.sep, '_')
        out[id(node)] = os.path.join(node.package, f'{stem}.nodl.yaml') if node.package else f'{stem}.nodl.yaml'
    return out

