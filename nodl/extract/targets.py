"""What ``nodl extract PATH...`` reads: packages, their executables, and loose source files.

A PATH is a package (a folder with ``package.xml``, ``setup.py`` or ``setup.cfg``), a folder
holding packages, or source files.  For a Python package, ``setup.py`` (read with ``ast``, never
run) and ``setup.cfg`` give the package name, the console-script entry points (which function
of which module each executable runs) and the generate_parameter_library modules
(``generate_parameter_module(NAME, YAML)``).  For an ament_cmake package, ``CMakeLists.txt``
(:mod:`nodl.extract.cmake`, read, never run) says which executables are built from which
C++ sources, which classes are components, and which scripts ``install(PROGRAMS)`` puts where
``ros2 run`` finds them (the Python nodes of an ament_cmake_python package).  Every reader of
:data:`BUILD_READERS` is asked, so a mixed package is read by both.  :data:`LANGUAGES` maps a
source suffix to its extractor; the files of one extractor are given to it together (C++
headers and sources are read as one).
"""

from __future__ import annotations

import ast
import copy
import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.extract.model import ExtractedNode, Extraction

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable
    from typing import Any

    from nodl.extract.cmake import CMakeTargets

__all__ = ['Package', 'BUILD_READERS', 'LANGUAGES', 'find_packages', 'read_python_build',
           'read_cmake_build', 'extract_paths', 'output_paths', 'registrations', 'nodes_file_text']

_SKIPPED_FOLDERS = {'build', 'install', 'log', '.git', '__pycache__', 'node_modules', '.venv', 'venv',
                    '.tox', '.mypy_cache', '.pytest_cache'}


@dataclass(slots=True)
class Package:
    """A package (or a set of loose files, ``name`` None) and what its build files say.

    ``executables``: executable -> ``(source file, function)`` (for Python, the module file and
    the function an entry point runs; for a script ``install(PROGRAMS)`` installs, the file and
    ``''``: its module-level code).  ``genparam``: a generate_parameter_library module (dotted)
    -> its YAML file.  ``cmake``: what ``CMakeLists.txt`` builds (C++ executables and
    components), None without one.
    """

    name: str | None
    root: str
    files: list[str] = field(default_factory=list)
    executables: dict[str, tuple[str, str]] = field(default_factory=dict)
    genparam: dict[str, str] = field(default_factory=dict)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    cmake: CMakeTargets | None = None
    #: os.path.realpath of the paths looked up while the package is extracted (asked once each).
    _real: dict[str, str] = field(default_factory=dict, init=False, repr=False, compare=False)

    def real(self, path: str) -> str:
        """``os.path.realpath(path)``, found once per path (and its folder's once per folder)."""
        found = self._real.get(path)
        if found is None:
            folder, name = os.path.split(path)
            if name in ('', '.', '..') or os.path.islink(path):
                found = os.path.realpath(path)
            else:
                key = folder + os.sep  # a folder's entry: no file path ends with a separator
                base = self._real.get(key)
                if base is None:
                    base = self._real[key] = os.path.realpath(folder)
                found = os.path.join(base, name)
            self._real[path] = found
        return found


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
        return {_literal(k, constants): _literal(v, constants) for k, v in zip(expr.keys, expr.values, strict=True)
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
        from nodl.extract.python import read_source

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
        from nodl.extract.python import _walk

        for call in _walk(tree):  # ast.walk's order, gathered faster
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


def read_cmake_build(root: str) -> Package | None:
    """A CMake package's name, C++ targets and installed scripts, from ``CMakeLists.txt`` (None
    when the folder has none); what it cannot read is one located diagnostic each."""
    path = os.path.join(root, 'CMakeLists.txt')
    if not os.path.isfile(path):
        return None
    from nodl.extract.cmake import read_cmake

    targets = read_cmake(path)
    package = Package(_package_xml_name(root) or targets.package, root, cmake=targets)
    package.diagnostics += targets.diagnostics
    for name, source in sorted(targets.programs.items()):
        if source.endswith('.py') or not os.path.splitext(source)[1]:
            package.executables[name] = (source, '')
    return package


#: Readers of build files, each asked on every package folder: each returns a :class:`Package`
#: (its executables, generated-parameter modules, CMake targets) or None; what several readers
#: find is merged (an ament_cmake_python package has a CMakeLists.txt and Python sources).
BUILD_READERS: list[Callable[[str], Package | None]] = [read_python_build, read_cmake_build]

#: Source extensions -> the extractor of that language: ``(files, package) -> Extraction``.
#: The files of one extractor are given to it in one call (all the C++ sources and headers
#: of a package together).
LANGUAGES: dict[str, Callable[[list[str], Package], Extraction]] = {}


def _extract_python(files: list[str], package: Package) -> Extraction:
    from nodl.extract.python import PackageSources, extract_file
    from nodl.extract.writer import check_entities

    out = Extraction()
    runs: dict[str, set[str]] = {}  # file -> the functions its entry points run ('': a script)
    for target, function in package.executables.values():
        runs.setdefault(package.real(target), set()).add(function)
    read: list[str] = []
    sources = PackageSources(package.root, files)  # where the bases of node classes are found
    root = os.path.join(package.root, '')
    for path in files:
        folder = os.path.dirname(path)
        rel = folder[len(root):] if folder.startswith(root) and '..' not in folder else \
            os.path.relpath(folder, package.root)
        module_package = '.'.join(p for p in rel.split(os.sep) if p not in ('', '.')) or None
        found = extract_file(path, package=module_package, genparam=package.genparam,
                             starts=runs.get(package.real(path), ()), check=False, sources=sources)
        out.nodes += found.nodes  # what Extraction.extend does, the files made unique once
        out.diagnostics += found.diagnostics
        read += found.files
        out.starts.update(found.starts)
    out.files = list(dict.fromkeys(read))
    for node in out.nodes:  # the validator's checks together, once every file is read
        check_entities(node)
    return out


LANGUAGES['.py'] = _extract_python


def _extract_cpp(files: list[str], package: Package) -> Extraction:
    from nodl.extract.cpp import extract_cpp

    extraction = extract_cpp(files, package=package.name, targets=package.cmake, relative_to=os.getcwd())
    if package.cmake is not None:
        extraction.files.insert(0, package.cmake.file)
    return extraction


for _suffix in ('.cpp', '.cc', '.cxx', '.c++', '.hpp', '.hh', '.hxx', '.h', '.ipp'):
    LANGUAGES[_suffix] = _extract_cpp


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
    package: Package | None = None
    for reader in BUILD_READERS:
        found = reader(root)
        if found is None:
            continue
        if package is None:
            package = found
            continue
        package.name = package.name or found.name
        for name, target in found.executables.items():
            package.executables.setdefault(name, target)
        package.genparam.update(found.genparam)
        package.diagnostics += found.diagnostics
        package.cmake = package.cmake or found.cmake
    if package is None:
        package = Package(_package_xml_name(root), root)
    package.files = _source_files(root, stop_at_packages=True)
    for path, _function in package.executables.values():  # a script without a suffix (#!/usr/bin/env python3)
        if not os.path.splitext(path)[1] and os.path.isfile(path) and path not in package.files:
            package.files.append(path)
    return package


def find_packages(paths: Iterable[str]) -> tuple[list[Package], list[Diagnostic]]:
    """The packages (and loose files) named by ``paths``, and a NODL020 diagnostic for each path
    that cannot be read."""
    from nodl.files import describe_os_error

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
    real = package.real

    python: list[ExtractedNode] = []
    for node in extraction.nodes:
        if node.language != 'python':  # C++: CMakeLists.txt named the executable (or said why not)
            node.package = package.name or node.package
            if node.executable is None and not any(d.code == 'NODL944' for d in node.notes):
                where = 'its package has no CMakeLists.txt that builds it' if package.name else \
                    'it is not in a package (no CMakeLists.txt maps executables)'
                node.notes.append(Diagnostic(Severity.INFO, f"node '{node.name}': {where}; its draft is named "
                                             f"'{node.output_name}'", file=node.location.file,
                                             line=node.location.line, column=node.location.column,
                                             code='NODL911'))
            out.append(node)
            continue
        node.package = package.name
        python.append(node)
        by_file.setdefault(real(node.location.file), []).append(node)
    starts = {real(f): calls for f, calls in extraction.starts.items()}
    classes: dict[str, ExtractedNode] = {}  # the first node class of each name in the package
    for node in python:
        if node.made_by == 'class':
            classes.setdefault(node.name, node)
    used: set[int] = set()
    for executable, (path, function) in sorted(package.executables.items()):
        here = by_file.get(real(path), [])
        calls = starts.get(real(path), {})
        called = list(calls.get(function, []))
        if function == '':  # a script: its module-level code and the module functions it calls
            called += [name for top in calls.get('', []) for name in calls.get(top, []) if name not in called]
        started = [n for n in here if n.made_by == 'call' and (n.made_in in (function, '') or (
            function == '' and n.made_in in calls.get('', [])))]
        for name in called:  # node classes of the same module first, then of the package
            same = [n for n in here if n.made_by == 'class' and n.name == name]
            other = same or ([classes[name]] if name in classes else [])
            started += [n for n in other if n not in started]
        for node in started:
            copy_ = node if id(node) not in used else copy.deepcopy(node)
            used.add(id(node))
            copy_.executable = executable
            out.append(copy_)
    for node in python:
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
        by_extractor: dict[Callable[[list[str], Package], Extraction], list[str]] = {}
        for path in package.files:
            suffix = os.path.splitext(path)[1]
            by_extractor.setdefault(LANGUAGES[suffix] if suffix else _extract_python, []).append(path)
        found = Extraction()
        for extractor, files in by_extractor.items():
            found.extend(extractor(files, package))
        result.diagnostics += found.diagnostics
        result.files += found.files
        result.nodes += _assign_executables(package, found)
    if not result.nodes and not any(d.severity is Severity.ERROR for d in result.diagnostics):
        shown = ', '.join(paths) if not isinstance(paths, str) else paths
        result.diagnostics.append(Diagnostic(
            Severity.ERROR, f'no node found in {shown}: no class derived from an rclpy or rclcpp Node or '
            'LifecycleNode, and no node made with Node(...), rclpy.create_node(...) or '
            'rclcpp::Node::make_shared(...)', file=str(shown), code='NODL912'))
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



def registrations(extraction: Extraction) -> tuple[dict[str, dict[str, dict[str, str]]], list[Diagnostic]]:
    """What each package's ``nodes.yaml`` of the overlay layout records (see
    :mod:`nodl.registry.overlay`): package -> ``{key: {plugin: pkg::Class, node_name: name}}``,
    the key being the draft's file stem.  A component is recorded with its plugin class, every
    node whose name the source fixes with its ``node_name``.  A plugin class outside its package's
    namespace cannot be recorded there (the layout refuses it): one NODL961 note each."""
    import re

    from nodl.registry.overlay import NODES_FILE

    paths = output_paths(extraction)
    tables: dict[str, dict[str, dict[str, str]]] = {}
    problems: list[Diagnostic] = []
    for node in extraction.nodes:
        if not node.package:
            continue
        key = os.path.basename(paths[id(node)])[:-len('.nodl.yaml')]
        if not re.fullmatch(r'[A-Za-z0-9_][A-Za-z0-9_.-]*', key):
            continue
        record: dict[str, str] = {}
        if node.plugin:
            if re.fullmatch(r'[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)+', node.plugin) and \
                    node.plugin.split('::', 1)[0] == node.package:
                record['plugin'] = node.plugin
            else:
                problems.append(Diagnostic(
                    Severity.INFO, f"component {node.plugin} is not recorded in {node.package}/{NODES_FILE}: a "
                    f"definitions folder records plugins as {node.package}::<Class> (its package's namespace); "
                    'record it where the node is registered (ament_nodl_register_node PLUGIN)',
                    file=node.location.file, line=node.location.line, column=node.location.column,
                    code='NODL961'))
        if node.node_name and re.fullmatch(r'[A-Za-z_][A-Za-z0-9_]*', node.node_name):
            record['node_name'] = node.node_name
        if record:
            tables.setdefault(node.package, {})[key] = record
    return tables, problems


def nodes_file_text(package: str, table: dict[str, dict[str, str]]) -> str:
    """The text of ``<package>/nodes.yaml`` for :func:`registrations`' table of one package."""
    import yaml

    from nodl.text_safety import one_line

    header = (f'# What registrations record for {one_line(package)} (plugin, node name), as extracted '
              'from its source by nodl extract.\n# Provenance: extracted.\n')
    return header + yaml.safe_dump(table, sort_keys=True, default_flow_style=False)
