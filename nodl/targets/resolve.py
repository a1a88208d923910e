"""The one target resolution: ``FILE``, ``PACKAGE EXECUTABLE`` or ``nodl://PACKAGE/NAME``
-> a definition, with where it came from.

Definitions folders are gathered by :func:`gather_definitions` in order of
precedence: ``--definitions DIR`` (as given), then ``NODL_PATH`` (folders
separated by ``os.pathsep``), then ``definitions = [...]`` of the ``nodl.toml`` /
``[tool.nodl]`` that applies (relative to that file); the ament index comes
last.  :func:`resolve_target` resolves a target with them in force
(:func:`nodl.registry.overlay.using`) and says where the definition came
from (:class:`Provenance`): the index, a definitions folder, or a file given by
path; and whether the file was written by ``nodl extract`` or ``nodl describe``
(read from the provenance header those verbs write).
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import NamedTuple

from nodl.composition.client_library import choose_client_library
from nodl.composition.resolved import ResolvedNode, resolve_report
from nodl.composition.resolvers import ResolutionError, ResolveContext
from nodl.config import definitions_of, find_config_file
from nodl.diagnostics import Diagnostic, Severity
from nodl.loading import check_source
from nodl.registry.nodl_resolver import AmentIndexResolver
from nodl.registry.overlay import Definitions, read_folders, using
from nodl.registry.registrations import compose_registered, find_node
from nodl.reporting import plural
from nodl.validation.kinds import Kind

__all__ = ['Provenance', 'ResolvedTarget', 'gather_definitions', 'provenance_of', 'made_by', 'no_header',
           'resolve_registered',
           'target_name',
           'resolve_target', 'resolve_reference', 'coverage_line', 'NODL_PATH']

#: The environment variable listing definitions folders.
NODL_PATH = 'NODL_PATH'
#: How many lines from the top a provenance header may start (after a marker line).
_HEADER_WINDOW = 8
_EXTRACTED = re.compile(r'#\s*Extracted from .* by nodl extract')
# ``nodl describe NODE`` / ``--all``: "Described from the running node /x by `nodl describe`";
# ``nodl describe --all --launch``: "Described by `nodl describe --all --launch` from ..."
_DESCRIBED = re.compile(r'#\s*Described (from the running node .* )?by `?nodl describe\b')


class Provenance(NamedTuple):
    """Where a definition came from."""

    #: ``index`` (the ament index), ``overlay`` (a definitions folder), ``file`` (given by
    #: path) or ``none`` (no definition).
    source: str
    #: The definitions folder (``overlay`` only).
    folder: str | None = None
    #: ``extracted`` or ``described`` when the file's header says so (else None).
    made_by: str | None = None

    def __str__(self) -> str:
        """``index``, ``overlay DIR``, ``file``, each with ``, extracted`` or ``, described``."""
        text = f'overlay {self.folder}' if self.source == 'overlay' else self.source
        return f'{text}, {self.made_by}' if self.made_by else text

    @classmethod
    def of(cls, origin: str, file: str | None) -> Provenance:
        """The provenance of a registration's ``origin`` (``index`` or ``overlay DIR``) and file."""
        if file is None:
            return cls('none')
        if origin.startswith('overlay '):
            return cls('overlay', origin[len('overlay '):], made_by(file))
        return cls(origin, None, made_by(file))


def no_header(content: str | bytes) -> bool:
    """True when a definition's ``content`` (its text or bytes, already read) cannot hold the
    header :func:`made_by` looks for: its first character that is not (ASCII) white space is
    another ASCII character than ``#``.  :func:`made_by` of such a file is None without
    reading it again (an analysis asks this of every definition it resolved)."""
    if isinstance(content, str):
        first = content.lstrip(_ASCII_SPACE)[:1]
        return bool(first) and first != '#' and first < '\x80'
    start = content.lstrip()[:1]  # (bytes.lstrip strips ASCII white space alone)
    return bool(start) and start != b'#' and start < b'\x80'


_ASCII_SPACE = ' \t\n\r\x0b\x0c'


def made_by(file: str) -> str | None:
    """``extracted`` or ``described`` if ``file`` starts with the header ``nodl extract`` or
    ``nodl describe`` writes (within its first lines), else None (also for a file that cannot
    be read, or an index entry)."""
    try:
        with open(file, encoding='utf-8', errors='replace') as stream:
            lines = [stream.readline(4096) for _ in range(_HEADER_WINDOW)]
    except OSError:
        return None
    for line in lines:
        if not line.startswith('#'):
            if line.strip():
                break
            continue
        if _EXTRACTED.match(line):
            return 'extracted'
        if _DESCRIBED.match(line):
            return 'described'
    return None


def provenance_of(origin: str, file: str | None) -> Provenance:
    """:meth:`Provenance.of`."""
    return Provenance.of(origin, file)


def gather_definitions(given: Sequence[str] = (), *, environ: Mapping[str, str] | None = None,
                       start: str | None = None, use_config: bool = True) -> Definitions:
    """The definitions folders of a run, in order of precedence: ``given`` (``--definitions``),
    ``NODL_PATH``, then the ``definitions`` of the configuration that applies to the folder
    ``start`` (default: the current folder).  Each folder is read and its layout checked
    (:attr:`Definitions.diagnostics`).  :class:`~nodl.config.ConfigError` for a
    configuration that cannot be used."""
    roots: list[tuple[str, str]] = [(folder, '--definitions') for folder in given]
    value = (environ if environ is not None else os.environ).get(NODL_PATH, '')
    roots += [(folder, NODL_PATH) for folder in value.split(os.pathsep) if folder]
    if use_config:
        config = find_config_file(start or os.getcwd())
        if config is not None:
            roots += [(folder, config) for folder in definitions_of(config)]
    return read_folders(roots)


class ResolvedTarget(NamedTuple):
    """A resolved target: the node (None on errors), the diagnostics, the file it was read
    from, and where that file came from."""

    node: ResolvedNode | None
    diagnostics: list[Diagnostic]
    source: str
    provenance: Provenance


def resolve_target(target: Sequence[str] | str, *, client_library: str | None = None,
                   prefixes: list[str] | None = None,
                   definitions: Definitions | None = None) -> ResolvedTarget:
    """Resolve ``FILE`` or ``PACKAGE EXECUTABLE`` to a node.

    ``PACKAGE EXECUTABLE`` is looked up in ``definitions`` (and whatever folders are in
    force) before the ament index ``prefixes`` (default: ``AMENT_PREFIX_PATH``); a file's
    and a registration's ``nodl://`` mixins too.  The client library defaults to the one
    of the package's build type (a registered node), else rclpy.  Never raises for a
    missing or invalid definition (diagnostics); OSError for a file that cannot be read,
    ValueError for an unknown client library or a malformed target.
    """
    parts = [target] if isinstance(target, str) else list(target)
    with using(definitions):
        if len(parts) == 2:
            registration = find_node(parts[0], parts[1], prefixes)
            node, diagnostics, source = resolve_registered(
                parts[0], parts[1], client_library=client_library, prefixes=prefixes)
            provenance = Provenance.of(registration.origin if registration else 'index',
                                       registration.file if registration else None)
            return ResolvedTarget(node, diagnostics, source, provenance)
        if len(parts) != 1:
            raise ValueError('give a definition FILE or PACKAGE EXECUTABLE')
        path = parts[0]
        if not os.path.isfile(path):
            raise OSError(f"{path}: {'is a directory' if os.path.isdir(path) else 'no such file'}")
        report = check_source(Path(path), kind=Kind.NODE, file=path)
        node, diagnostics = resolve_report(report, client_library=client_library,
                                           prefixes=prefixes)
        return ResolvedTarget(node, diagnostics, path, Provenance('file', None, made_by(path)))


def target_name(target: Sequence[str] | str) -> str:
    """The executable (``PACKAGE EXECUTABLE``) or the file a target names: what a generated
    node's default names are derived from."""
    parts = [target] if isinstance(target, str) else list(target)
    return parts[-1]


def resolve_reference(reference: str, *, prefixes: list[str] | None = None,
                      definitions: Definitions | None = None
                      ) -> tuple[str | bytes | None, str, list[Diagnostic]]:
    """The interface definition ``nodl://PACKAGE/NAME``: ``(text or None, file, diagnostics)``,
    looked up in the definitions folders, then the ament index ``prefixes``."""
    with using(definitions):
        try:
            resolved = AmentIndexResolver().resolve(
                reference, ResolveContext(None, None,
                                          tuple(prefixes) if prefixes is not None else None))
        except ResolutionError as exc:
            searched = f' (searched: {", ".join(exc.searched)})' if exc.searched else ''
            return None, reference, [Diagnostic(
                Severity.ERROR, f"cannot resolve '{reference}': {exc.message}{searched}", (),
                reference, code='NODL306')]
    return resolved.text, resolved.file, []


#: The words of the coverage line, per source, in order.
_COVERAGE = (('index', 'registered'), ('overlay', 'overlay'), ('file', 'from files'),
             ('none', 'without definition'))


def coverage_line(sources: Iterable[Provenance | str]) -> str:
    """``16 nodes: 9 registered, 6 overlay (2 extracted, 1 described), 1 without definition``:
    how many nodes each source served (``from files`` only when some node came from a file
    given by path; the others whenever some node was looked up by package), and of those,
    how many files ``nodl extract`` or ``nodl describe`` wrote (drafts to review; known from
    a :class:`Provenance`, not from a bare source name)."""
    counts = {key: 0 for key, _ in _COVERAGE}
    drafts: dict[str, dict[str, int]] = {key: {} for key, _ in _COVERAGE}
    total = 0
    for source in sources:
        key = source.source if isinstance(source, Provenance) else source
        key = key if key in counts else 'none'
        counts[key] += 1
        if isinstance(source, Provenance) and source.made_by and key != 'none':
            drafts[key][source.made_by] = drafts[key].get(source.made_by, 0) + 1
        total += 1
    looked_up = counts['index'] or counts['overlay'] or counts['none']
    parts = []
    for key, words in _COVERAGE:
        if counts[key] or (key != 'file' and looked_up):
            made = ', '.join(f'{drafts[key][how]} {how}' for how in ('extracted', 'described')
                             if drafts[key].get(how))
            parts.append(f'{counts[key]} {words}' + (f' ({made})' if made else ''))
    return plural(total, 'node') + (': ' + ', '.join(parts) if parts else '')


def resolve_registered(package: str, executable: str, *, client_library: str | None = None,
                       prefixes: list[str] | None = None
                       ) -> tuple[ResolvedNode | None, list[Diagnostic], str]:
    """Resolve the node definition registered for ``package``'s ``executable``.

    The client library defaults to the one of the package's build type
    (``ament_python`` -> rclpy, ``ament_cmake`` -> rclcpp; else rclpy).  The
    definition, its package and its ``nodl://`` mixins are all looked up in ``prefixes``
    (default ``AMENT_PREFIX_PATH``).  Returns ``(resolved or None, diagnostics, source
    file)``; never raises for a missing or broken registration (ValueError for an unknown
    client library).
    """
    choice = choose_client_library(client_library, package, prefixes)
    composed, diagnostics, source = compose_registered(package, executable, prefixes,
                                                       client_library=choice.name)
    if composed is None:
        return None, diagnostics, source
    return ResolvedNode(composed, choice.reason), diagnostics, source
