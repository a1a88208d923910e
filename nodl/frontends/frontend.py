"""The ``nodl.frontends`` extension point (version 1.0): readers of a text as a NoDL document.

A frontend turns one text (a file's, already decoded and size-checked by
:mod:`nodl.frontends.source`) into NoDL v2 data and a way to place a
diagnostic about that data back in the text.  Every frontend, the built-in
ones included (:mod:`nodl.frontends.builtin`), is a class registered in the
``nodl.frontends`` entry point group, exactly as a third-party package
registers its own::

    [project.entry-points."nodl.frontends"]
    toml = "nodl_toml:TomlFrontend"

A frontend subclasses :class:`FrontendExtension` and implements
:meth:`~FrontendExtension.read`: given a :class:`FrontendInput` it returns
a :class:`Reading`, or None for a text that is not its own.  The loader
(:func:`read_document`, which :func:`nodl.loading.check_source` calls) asks
the frontends in order of ``PRIORITY`` (highest first) and the first that
returns a reading reads the text.  A frontend recognises its texts as it
likes: by the file name (:attr:`FrontendInput.suffix`), by the first
characters, or by the text read as YAML (:meth:`FrontendInput.parsed`,
parsed once for every frontend that asks).  ``SUFFIXES`` names the files a
directory scan (``nodl validate DIR``) picks up for it.

A frontend that cannot be loaded (an import error, an incompatible
``EXTENSION_POINT_VERSION``) or that raises while reading is skipped: the
next document read carries one warning (NODL017) that says so, and the
other frontends read it.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable
from typing import Any, Protocol

from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.source import SourceText
from nodl.frontends.yaml_json import ParsedDocument, parse_document
from nodl.plugins import (
    BLOCKLIST_VARIABLE,
    EXTENSION_POINTS,
    EntryPointSpec,
    ExtensionPoint,
    PluginError,
    instantiate_extensions,
    iter_entry_points,
)

__all__ = [
    'BROKEN_FRONTEND',
    'FRONTEND_GROUP',
    'NO_FRONTEND',
    'FrontendExtension',
    'FrontendInput',
    'Placer',
    'Reading',
    'frontend_suffixes',
    'load_frontends',
    'read_document',
]

#: The entry point group of frontends.
FRONTEND_GROUP = 'nodl.frontends'
#: A frontend plug-in that could not be loaded, or raised while reading, was skipped.
BROKEN_FRONTEND = 'NODL017'
#: No frontend reads the text (every one of them is blocked or broken).
NO_FRONTEND = 'NODL018'
#: The built-in frontends as pyproject.toml registers them, used only where no distribution
#: declares the group at all (a source tree run without its metadata); a test keeps the two equal.
BUILTIN_FRONTENDS: dict[str, str] = {
    'yaml-json': 'nodl.frontends.builtin:YamlJsonFrontend',
    'legacy-xml': 'nodl.frontends.builtin:LegacyXmlFrontend',
    'include': 'nodl.frontends.builtin:IncludeFrontend',
    'genparamlib': 'nodl.frontends.builtin:GenParamLibFrontend',
}


class Placer(Protocol):
    """What places a diagnostic about a reading's data (a document path) in the text."""

    def place(self, diagnostic: Diagnostic) -> Diagnostic:
        """``diagnostic`` at its file, line and column."""


class FrontendInput:
    """One text to read, as every frontend sees it."""

    def __init__(self, source: SourceText, *, installed: bool = False) -> None:
        #: The text and the name diagnostics give it.
        self.source = source
        self.text: str = source.text
        self.file: str = source.file
        #: The text is a document an ament package registered (the reference's resource type
        #: ``nodl``): the include frontend reads it as a node definition.
        self.installed = installed
        self._parsed: ParsedDocument | None = None

    @property
    def suffix(self) -> str:
        """The file name's last extension, lower case (``.yaml``), or ``''``."""
        return os.path.splitext(self.file)[1].lower()

    def parsed(self) -> ParsedDocument:
        """The text read as YAML or JSON (:func:`~nodl.frontends.yaml_json.parse_document`), once."""
        if self._parsed is None:
            self._parsed = parse_document(self.source)
        return self._parsed


class Reading:
    """What a frontend made of a text.

    ``data`` is the NoDL v2 document to validate, or None when the text is not
    a NoDL document (its ``diagnostics`` then say what it is, or why it could not
    be read).  ``document`` places diagnostics about ``data`` in the text (a
    :class:`~nodl.frontends.yaml_json.ParsedDocument`); without one they are
    placed at the start of the file.  ``raw`` is the text's own data as read (by
    default ``data``), ``dialect`` the name of the format when it is not NoDL v2
    itself, and ``extra`` what the text carries that NoDL does not use.
    """

    def __init__(self, data: Any, document: Placer | None = None,
                 diagnostics: Iterable[Diagnostic] = (), *, raw: Any = None,
                 dialect: str | None = None, extra: dict[str, Any] | None = None) -> None:
        self.data = data
        self.document = document
        self.diagnostics: list[Diagnostic] = list(diagnostics)
        self.raw = data if raw is None else raw
        self.dialect = dialect
        self.extra: dict[str, Any] = extra or {}
        #: The entry point name of the frontend that read the text (set by :func:`read_document`).
        self.frontend: str | None = None


class FrontendExtension(ExtensionPoint):
    """Base class of frontends (the ``nodl.frontends`` extension point, version 1.0)."""

    EXTENSION_POINT_VERSION = EXTENSION_POINTS[FRONTEND_GROUP].version
    #: What the frontend reads, in a few words (for messages and help).
    DESCRIPTION: str = ''
    #: File name endings a directory scan picks up for this frontend (``.nodl.toml``).
    SUFFIXES: tuple[str, ...] = ()

    def read(self, source: FrontendInput) -> Reading | None:
        """Read ``source``, or return None if it is not a text of this frontend."""
        raise NotImplementedError


class _Loaded:
    def __init__(self, key: tuple[tuple[str, ...], str], frontends: dict[str, FrontendExtension],
                 broken: list[PluginError]) -> None:
        self.key = key
        self.frontends = frontends
        self.broken = broken
        #: Broken plug-ins not yet reported on a document.
        self.unreported = list(broken)


#: The frontends loaded last, for the ``sys.path`` and blocklist they were found with.
_loaded: _Loaded | None = None


def load_frontends() -> tuple[dict[str, FrontendExtension], list[PluginError]]:
    """The frontends (by entry point name, highest priority first) and the broken plug-ins.

    Loaded once per process, again when ``sys.path`` or the blocklist changes (what
    :func:`nodl.plugins.iter_entry_points` finds depends on nothing else).
    """
    frontends, loaded = _frontends()
    return dict(frontends), list(loaded.broken)


def _frontends() -> tuple[dict[str, FrontendExtension], _Loaded]:
    global _loaded
    # Asked once per document read: the key is cheap to build (not the entry points themselves).
    key = (tuple(sys.path), os.environ.get(BLOCKLIST_VARIABLE, ''))
    if _loaded is None or _loaded.key != key:
        broken: list[PluginError] = []
        if iter_entry_points(FRONTEND_GROUP, include_blocked=True):
            found = instantiate_extensions(FRONTEND_GROUP, on_error=broken.append)
        else:  # no distribution declares the group: a source tree without its metadata
            found = _builtins()
        _loaded = _Loaded(key, found, broken)
    return _loaded.frontends, _loaded


def _builtins() -> dict[str, FrontendExtension]:
    """The built-in frontends, by priority, without the entry point metadata."""
    found: dict[str, FrontendExtension] = {}
    for name, value in BUILTIN_FRONTENDS.items():
        frontend = EntryPointSpec(name, value, FRONTEND_GROUP).load()()
        frontend.EXTENSION_GROUP, frontend.EXTENSION_NAME = FRONTEND_GROUP, name
        found[name] = frontend
    return dict(sorted(found.items(), key=lambda item: (-item[1].PRIORITY, item[0])))


def frontend_suffixes() -> tuple[str, ...]:
    """The file name endings of every frontend's ``SUFFIXES``, in order of priority."""
    found: list[str] = []
    for frontend in _frontends()[0].values():
        suffixes = getattr(frontend, 'SUFFIXES', ())
        if isinstance(suffixes, tuple):
            found.extend(s for s in suffixes if isinstance(s, str) and s and s not in found)
    return tuple(found)


def _broken(file: str, name: str, value: str, why: str) -> Diagnostic:
    return Diagnostic(Severity.WARNING, f"frontend plug-in '{name}' ({value}) was skipped: {why}; "
                      'the other frontends read this file', (), file, code=BROKEN_FRONTEND)


def read_document(source: SourceText, *, installed: bool = False) -> Reading:
    """Read a text with the first frontend (by priority) that takes it.

    Never raises for bad content or a broken plug-in: a broken one is skipped with a
    warning on the reading (NODL017), once per plug-in and process when it cannot be loaded,
    each time it raises on a text.
    """
    frontends, loaded = _frontends()
    notes: list[Diagnostic] = []
    if loaded.unreported:
        notes = [_broken(source.file, e.name, e.value, e.error) for e in loaded.unreported]
        loaded.unreported = []
    given = FrontendInput(source, installed=installed)
    for name, frontend in frontends.items():
        try:
            reading = frontend.read(given)
            if reading is not None and not isinstance(reading, Reading):
                raise TypeError(f'read() returned {type(reading).__name__}, not a Reading or None')
        except Exception as exc:  # noqa: BLE001 - a broken plug-in must not stop the loader
            value = f'{type(frontend).__module__}:{type(frontend).__qualname__}'
            notes.append(_broken(source.file, name, value, f'it raised {type(exc).__name__}: {exc}'))
            continue
        if reading is None:
            continue
        reading.frontend = name
        reading.diagnostics[:0] = notes
        return reading
    notes.append(Diagnostic(
        Severity.ERROR, f'no frontend reads this file (frontends: {", ".join(frontends) or "none"}); '
        f'is {FRONTEND_GROUP} left out by NODL_EXTENSION_BLOCKLIST?', (), source.file,
        code=NO_FRONTEND))
    return Reading(None, None, notes)
