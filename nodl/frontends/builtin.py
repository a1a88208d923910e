"""The built-in frontends, registered under ``nodl.frontends`` like any plug-in.

In the order the loader asks them (``PRIORITY``, highest first):

* ``legacy-xml`` (300): an XML text (legacy NoDL, specs 000-002, a
  ``package.xml`` or any other XML) is not a NoDL v2 document: the reading
  says what it is (NODL817) with the legacy reader's own findings
  (:mod:`nodl.frontends.xml_recognise`);
* ``include`` (200): the reference implementation's include dialect, read
  as a node definition (:mod:`nodl.frontends.include`);
* ``genparamlib`` (190): a generate_parameter_library file, recognised and
  said to be one (NODL861; :mod:`nodl.frontends.genparamlib`);
* ``yaml-json`` (0): everything else, read as YAML or strict JSON
  (:mod:`nodl.frontends.yaml_json`).

Each recognises its texts cheaply first: the XML and generate_parameter_library
readers are imported by their frontend only for a text that is theirs, so that
``nodl validate`` of a YAML file does not pay for them at start-up.
"""

from __future__ import annotations

from typing import Any

from nodl.frontends.frontend import FrontendExtension, FrontendInput, Reading
from nodl.frontends.include import (
    CODEGEN_KEY,
    is_include_document,
    read_include,
    remapped,
)
from nodl.frontends.yaml_json import ParsedDocument
from nodl.vocabulary import NODE_KEYS

__all__ = [
    'DIALECTS',
    'GENPARAMLIB',
    'INCLUDE',
    'GenParamLibFrontend',
    'IncludeFrontend',
    'LegacyXmlFrontend',
    'YamlJsonFrontend',
    'recognise',
]

#: The dialect names, as ``nodl convert --from`` spells them.
INCLUDE = 'include'
GENPARAMLIB = 'genparamlib'
#: Every dialect read besides NoDL v2 itself: name -> what it is, for messages and help.
DIALECTS = {
    INCLUDE: "the reference implementation's include dialect (flat interface + include: [{ref: ...}])",
    GENPARAMLIB: 'a generate_parameter_library parameter file',
}


def recognise(data: Any) -> str | None:
    """The dialect ``data`` (a parsed document) is written in, or None for NoDL v2 (or anything else)."""
    if not isinstance(data, dict):
        return None
    if is_include_document(data):
        return INCLUDE
    if 'nodl_version' in data or 'type' in data:
        return None
    from nodl.frontends.genparamlib import is_genparamlib_document

    return GENPARAMLIB if is_genparamlib_document(data) else None


def _mapping(source: FrontendInput) -> ParsedDocument | None:
    """The text as YAML/JSON if it parsed into a mapping without problems, else None."""
    parsed = source.parsed()
    return parsed if parsed.ok else None


class YamlJsonFrontend(FrontendExtension):
    """NoDL v2 as YAML or strict JSON: reads every text the others leave."""

    PRIORITY = 0
    DESCRIPTION = 'NoDL v2 documents in YAML or JSON'
    SUFFIXES = ('.nodl.yaml', '.nodl.yml', '.nodl.json')

    def read(self, source: FrontendInput) -> Reading:
        """The parsed text; a text that does not parse into a mapping is not a document."""
        parsed = source.parsed()
        if parsed.diagnostics:
            return Reading(None, parsed, parsed.diagnostics, raw=parsed.data)
        return Reading(parsed.data, parsed)


class LegacyXmlFrontend(FrontendExtension):
    """XML where NoDL v2 is read: legacy NoDL files and other XML, said to be what they are."""

    PRIORITY = 300
    DESCRIPTION = 'XML: legacy NoDL (specs 000-002), package.xml, other XML (to be converted)'

    def read(self, source: FrontendInput) -> Reading | None:
        """What an XML text is (an error that says how to convert it); None for other text."""
        if source.text.lstrip('\ufeff \t\r\n')[:1] != '<':
            return None
        from nodl.frontends.xml_recognise import xml_diagnostics

        found = xml_diagnostics(source.text, source.file)
        return None if found is None else Reading(None, None, found)


class IncludeFrontend(FrontendExtension):
    """The reference implementation's include dialect, read as a node definition."""

    PRIORITY = 200
    DESCRIPTION = DIALECTS[INCLUDE]

    def read(self, source: FrontendInput) -> Reading | None:
        """The node definition the document means; diagnostics land at the keys written.

        A document an ament package registered (``source.installed``) is the reference's
        flat interface, read so with or without ``include`` and without the suggestion to
        convert it (a NoDL v2 node definition, with ``base``, ``main`` or ``mixins``, is not).
        """
        parsed = _mapping(source)
        if parsed is None:
            return None
        data = parsed.data
        installed = source.installed and 'nodl_version' in data and not any(k in data for k in NODE_KEYS)
        if not installed and not is_include_document(data):
            return None
        reading = read_include(data, announce=not installed)
        placed = [parsed.place(d) for d in reading.diagnostics]
        extra = {CODEGEN_KEY: reading.codegen} if reading.codegen is not None else None
        return Reading(reading.data, remapped(parsed, reading), placed, raw=data, dialect=INCLUDE,
                       extra=extra)


class GenParamLibFrontend(FrontendExtension):
    """generate_parameter_library files: recognised, and said not to be NoDL documents."""

    PRIORITY = 190
    DESCRIPTION = DIALECTS[GENPARAMLIB]

    def read(self, source: FrontendInput) -> Reading | None:
        """An error that says what the file is and how to convert it; None for other text."""
        parsed = _mapping(source)
        if parsed is None or 'nodl_version' in parsed.data or 'type' in parsed.data:
            return None
        from nodl.frontends.genparamlib import (
            is_genparamlib_document,
            not_nodl,
            read_genparamlib,
        )

        if not is_genparamlib_document(parsed.data):
            return None
        problem = not_nodl(read_genparamlib(parsed.data))
        return Reading(None, parsed, [parsed.place(problem)], raw=parsed.data, dialect=GENPARAMLIB)
