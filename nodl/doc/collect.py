"""The targets of ``nodl doc`` -> the pages of one run.

Each target is one of:

* a definition file (``*.nodl.yaml``...): its node's page;
* ``PACKAGE``: the package's page and a page per registered node;
* ``PACKAGE/EXECUTABLE``: that node's page;
* a definitions folder: a package page per package in it, a page per node;
* a launch file (``*.launch.xml|py|yaml``): the system's page (through the
  analysis, as ``nodl analyse`` makes it) and a page per node that has a
  definition.

Every file path a page shows is relative to ``root`` (or, for an installed
file, to its ament prefix), so the pages are the same wherever they are
built and ``--check`` compares like with like.  A target that cannot be
documented is an error diagnostic (NODL273), never an exception.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.doc.blocks import Contents, Link, Page, Picture, Table, label
from nodl.doc.model import PageSource, node_page, package_page
from nodl.doc.system import graph_picture, system_page
from nodl.interface_types.resolve import interface_index
from nodl.loading import check_source
from nodl.registry.overlay import read_folders, using
from nodl.registry.registrations import list_registrations, search_path
from nodl.system.run import analyse_launch
from nodl.system.settings import load_settings
from nodl.targets.placement import is_launch_file
from nodl.targets.resolve import resolve_target
from nodl.validation.kinds import Kind

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from nodl.doc.blocks import Picture
    from nodl.interface_types.resolve import InterfaceIndex
    from nodl.launch.sandbox import LaunchLimits
    from nodl.registry.overlay import Definitions
    from nodl.targets.resolve import ResolvedTarget

__all__ = ['DocSet', 'collect', 'Displayer']


class Displayer:
    """File paths as pages show them: relative to the ament prefix they are installed in
    (``share/<package>/nodl/...``: the same wherever the workspace is and whichever folder
    the pages are built from), else to ``root`` when inside it, else as given."""

    def __init__(self, root: str, prefixes: Sequence[str]) -> None:
        self.root = os.path.abspath(root)
        self.prefixes = [os.path.abspath(p) for p in prefixes]

    def __call__(self, path: str) -> str:
        if not path:
            return ''
        absolute = os.path.abspath(path)
        for base in (*self.prefixes, self.root):
            if absolute.startswith(base.rstrip(os.sep) + os.sep):
                return os.path.relpath(absolute, base).replace(os.sep, '/')
        return path


class DocSet:
    """The pages of one run, what they say about problems, and what was read."""

    def __init__(self) -> None:
        self.pages: dict[str, Page] = {}
        #: Problems: targets that cannot be documented (errors), unavailable tables (warnings).
        self.diagnostics: list[Diagnostic] = []
        #: Every file read (an output must be none of them).
        self.inputs: list[str] = []

    @property
    def failed(self) -> bool:
        """True when some target could not be documented."""
        return any(d.severity is Severity.ERROR for d in self.diagnostics)

    def add(self, page: Page) -> None:
        """Add a page (the first of a path wins: a node documented twice is one page)."""
        self.pages.setdefault(page.path, page)

    def pictures(self) -> list[Picture]:
        """Every picture of the pages (written next to them)."""
        return [b for page in self.pages.values() for b in page.blocks if isinstance(b, Picture)]


def _error(target: str, message: str) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, file=target, code='NODL273')


class _Run:
    def __init__(self, docs: DocSet, display: Displayer, index: InterfaceIndex,
                 client_library: str | None, prefixes: list[str] | None) -> None:
        self.docs, self.display, self.index = docs, display, index
        self.client_library, self.prefixes = client_library, prefixes

    def node(self, found: ResolvedTarget, package: str | None, executable: str | None) -> Page | None:
        problems = [d for d in found.diagnostics if d.severity is not Severity.INFO]
        if found.node is None:
            self.docs.diagnostics += problems or [_error(found.source, 'the definition cannot be '
                                                                       'resolved')]
            return None
        self.docs.inputs += [found.source, *(layer.file for layer in found.node.layers if layer.file)]
        source = PageSource(package, executable, self.display(found.source), str(found.provenance))
        page, made = node_page(found.node, source, self.index, self.display, problems)
        self.docs.diagnostics += made
        self.docs.add(page)
        return page

    def package(self, package: str, description_of: Mapping[str, str] | None = None) -> None:
        registrations = list_registrations(package, self.prefixes)
        if not registrations:
            self.docs.diagnostics.append(_error(package, f"the package '{package}' has no registered "
                                                'definitions (is it built and its install '
                                                'sourced? give --definitions DIR for a folder)'))
            return
        nodes: list[tuple[str, str, str]] = []
        interfaces: list[tuple[str, str]] = []
        missing: list[tuple[str, str]] = []
        for registration in registrations:
            if registration.kind == 'interface':
                interfaces.append((f'nodl://{package}/{registration.name}',
                                   _interface_description(registration.file)))
                continue
            found = resolve_target([package, registration.name], client_library=self.client_library,
                                   prefixes=self.prefixes)
            page = self.node(found, package, registration.name)
            if page is None:
                missing.append((registration.name, 'its definition does not resolve (see the '
                                                   'findings)'))
                continue
            nodes.append((registration.name, page.path,
                          found.node.interface.description or '' if found.node else ''))
        owned = self.index.package(package)
        types = owned.names() if owned is not None else []
        self.docs.add(package_page(package, nodes, interfaces, types, missing))


def _interface_description(file: str) -> str:
    try:
        report = check_source(file, kind=Kind.INTERFACE, file=file)
    except OSError:
        return ''
    if report.has_errors():
        return ''
    return str(getattr(report.model(), 'description', '') or '')


def collect(targets: Sequence[str], *, root: str | None = None, client_library: str | None = None,
            prefixes: list[str] | None = None, launch_arguments: Mapping[str, str] | None = None,
            limits: LaunchLimits | None = None, definitions: Definitions | None = None) -> DocSet:
    """The pages of ``targets`` (see the module docstring), with the definitions folders
    ``definitions`` in force; paths shown relative to ``root`` (default: the current folder)."""
    docs = DocSet()
    chosen = search_path(prefixes)
    run = _Run(docs, Displayer(root or os.getcwd(), chosen), interface_index(prefixes=chosen),
               client_library, prefixes)
    with using(definitions):
        for target in targets:
            if os.path.isdir(target):
                _folder(run, target)
            elif is_launch_file(target):
                _launch(run, target, launch_arguments, limits, definitions)
            elif os.path.isfile(target):
                run.node(resolve_target(target, client_library=client_library, prefixes=prefixes),
                         None, None)
            elif any(c in target for c in '.\\') or target.count('/') > 1 or target.startswith('/'):
                docs.diagnostics.append(_error(target, 'no such file or folder; give a definition '
                                               'file, PACKAGE, PACKAGE/EXECUTABLE, a definitions '
                                               'folder or a launch file'))
            elif '/' in target:
                package, _, executable = target.partition('/')
                run.node(resolve_target([package, executable], client_library=client_library,
                                        prefixes=prefixes), package, executable)
            else:
                run.package(target)
    if docs.pages:
        docs.add(_index(docs))
    return docs


def _folder(run: _Run, folder: str) -> None:
    found = read_folders([(folder, 'TARGET')])
    run.docs.diagnostics += found.diagnostics
    packages = sorted(found.packages())
    if not packages:
        run.docs.diagnostics.append(_error(folder, 'the definitions folder holds no definitions '
                                           '(DIR/<package>/<executable>.nodl.yaml)'))
    with using(found):
        for package in packages:
            run.package(package)


def _launch(run: _Run, launch_file: str, arguments: Mapping[str, str] | None,
            limits: LaunchLimits | None, definitions: Definitions | None) -> None:
    if not os.path.isfile(launch_file):
        run.docs.diagnostics.append(_error(launch_file, 'no such launch file'))
        return
    analysis = analyse_launch(launch_file, arguments, client_library=run.client_library,
                              prefixes=run.prefixes, settings=load_settings(launch_file),
                              limits=limits, definitions=definitions)
    run.docs.inputs += analysis.files()
    if analysis.unreadable:
        run.docs.diagnostics += [f.diagnostic for f in analysis.findings
                                 if f.severity is Severity.ERROR][:1] or [
            _error(launch_file, 'the launch file cannot be read')]
        return
    pages: dict[int, tuple[str, str]] = {}
    for node in analysis.nodes:
        match = node.match
        if match.resolved is None or id(match) in pages:
            continue
        executable = node.entry.executable or match.key
        source = PageSource(match.package, executable, run.display(match.file or ''), match.origin)
        page, made = node_page(match.resolved, source, run.index, run.display,
                               [d for d in match.resolved.diagnostics
                                if d.severity is not Severity.INFO])
        run.docs.diagnostics += made
        run.docs.add(page)
        pages[id(match)] = (page.path, page.title)
    stem = os.path.basename(launch_file)
    for ending in ('.launch.xml', '.launch.py', '.launch.yaml', '.launch.yml', '.launch'):
        if stem.endswith(ending):
            stem = stem[:-len(ending)]
            break
    path = f'systems/{label(stem)}'
    picture, problem = graph_picture(analysis, f'{label(stem)}.graph.svg')
    extra = [problem] if problem is not None else []
    run.docs.diagnostics += extra
    run.docs.add(system_page(analysis, path, pages, run.display, picture, extra))


def _index(docs: DocSet) -> Page:
    page = Page('index', 'Reference', 'nodl-doc-index')
    page.heading(1, 'Reference', 'nodl-doc-index')
    page.paragraph('The nodes, packages and systems documented here, from their NoDL definitions.')
    rows = []
    for path, found in sorted(docs.pages.items()):
        what = ('system' if path.startswith('systems/') else 'package'
                if path.endswith('/index') else 'node')
        rows.append(((Link(found.title, found.label, path),), (what,)))
    page.blocks.append(Table(('Page', 'Kind'), tuple(rows)))
    page.blocks.append(Contents(tuple(sorted(docs.pages))))
    return page
