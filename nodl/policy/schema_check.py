"""The structure SROS 2 requires of a policy document, checked without an XML Schema library.

SROS 2 validates every policy against its ``policy.xsd`` (format 0.2.0)
before it uses it.  What that schema requires, in words:

* the root is ``<policy>`` with ``version="0.2.0"`` and exactly one child,
  ``<enclaves>``;
* ``<enclaves>`` holds one or more ``<enclave>``, each with a ``path``
  attribute and one or more ``<profiles>``;
* ``<profiles>`` (optional ``type`` attribute) holds one or more
  ``<profile>``, then at most one ``<metadata>`` of any content;
* ``<profile>`` has ``ns`` and ``node`` attributes and holds any number of
  ``<topics>``, ``<services>`` and ``<actions>`` in any order;
* each of those holds one or more ``<topic>`` / ``<service>`` / ``<action>``
  (a name each) and may carry its two access attributes (``publish`` and
  ``subscribe``; ``reply`` and ``request``; ``execute`` and ``call``), each
  ``ALLOW`` or ``DENY``;
* ``xml:base`` may appear on profiles and permission lists (XInclude), and
  no element holds text other than the names.

The document is read with the toolkit's safe XML reader (no DTD, no entity
expansion, size limits), keeping positions for every diagnostic (NODL606).
Like SROS 2, it expands XInclude first (:mod:`nodl.policy.xinclude`),
so hand-written policies that share permissions through included files are
checked as SROS 2 sees them, and findings name the file a grant is in.
"""

from __future__ import annotations

import html
import os
import re
from collections.abc import Iterator
from typing import TYPE_CHECKING, NamedTuple

from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.source import read_source
from nodl.frontends.xml_reader import XmlElement, XmlTree, load_xml
from nodl.policy.model import PERMISSIONS, POLICY_VERSION, QUALIFIERS
from nodl.policy.xinclude import Origin, Origins, expand_includes

if TYPE_CHECKING:
    from nodl.policy.xinclude import Origin, Origins

__all__ = ['ParsedPolicy', 'read_policy', 'check_policy_structure', 'check_policy_text']

_LISTS = {p.element: p for p in PERMISSIONS}
_LINE_BREAK = re.compile(r'\r\n|\r|\n')


class ParsedPolicy(NamedTuple):
    """A policy file read with positions: its text, its element tree and reading problems."""

    file: str
    text: str
    tree: XmlTree
    #: Offsets of the start of each line (to take text out of the file by position).
    line_starts: list[int]
    #: Where included elements come from (None: nothing was included).
    origins: Origins | None = None

    def _origin(self, element: XmlElement) -> tuple[str, str, list[int]]:
        found: Origin | None = self.origins.get(id(element)) if self.origins else None
        if found is None:
            return self.file, self.text, self.line_starts
        return found.file, found.text, found.line_starts

    def file_of(self, element: XmlElement) -> str:
        """The file ``element`` is written in (an included file, or this one)."""
        return self._origin(element)[0]

    @property
    def root(self) -> XmlElement | None:
        """The root element (None if the file could not be read)."""
        return self.tree.root

    def text_of(self, element: XmlElement, strip: bool = True) -> str:
        """The text directly inside ``element`` up to its first child or end ('' if none).

        ``strip=False`` keeps the white space around it, as SROS 2 reads a name.
        """
        if element.text_at is None:
            return ''
        line, column = element.text_at
        _, source, line_starts = self._origin(element)
        if line > len(line_starts):
            return ''
        # The reader places text where the parser reported it (its start or its end): the
        # text is what lies between the tags around that place.
        at = line_starts[line - 1] + column - 1
        start = source.rfind('>', 0, at) + 1
        end = source.find('<', start)
        raw = source[start:end if end >= 0 else len(source)]
        text = html.unescape(raw)
        return text.strip() if strip else text


def read_policy(source: str | os.PathLike[str], file: str | None = None) -> ParsedPolicy:
    """Read a policy document: a path, or (``str``) its text.  OSError if the file cannot be read."""
    if isinstance(source, os.PathLike):
        read, problem = read_source(source, file)
    else:
        read, problem = read_source(source, file or '<policy>')
    if read is None:
        assert problem is not None
        return ParsedPolicy(problem.file, '', XmlTree(problem.file, None, [problem]), [0])
    tree = load_xml(read.text, read.file)
    starts = [0] + [m.end() for m in _LINE_BREAK.finditer(read.text)]
    origins = None
    if tree.root is not None and 'XInclude' in read.text:
        origins = Origins()
        expand_includes(tree.root, Origin(read.file, read.text, starts), origins, tree.diagnostics)
    return ParsedPolicy(read.file, read.text, tree, starts, origins)


def _error(file: str, element: XmlElement, message: str, line: int = 0, column: int = 0) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, (), file, line or element.line,
                      column or element.column, code='NODL606')


def _namespace_declaration(name: str) -> bool:
    return name == 'xmlns' or name.startswith('xmlns:')


class _Checker:
    def __init__(self, parsed: ParsedPolicy) -> None:
        self.parsed = parsed
        self.file = parsed.file
        self.out: list[Diagnostic] = []

    def error(self, element: XmlElement, message: str, line: int = 0, column: int = 0) -> None:
        self.out.append(_error(self.parsed.file_of(element), element, message, line, column))

    def attributes(self, element: XmlElement, required: tuple[str, ...],
                   optional: tuple[str, ...] = ()) -> None:
        for attribute in element.attributes:
            if attribute.name in required or attribute.name in optional \
                    or _namespace_declaration(attribute.name):
                continue
            allowed = ', '.join(required + optional) or 'none'
            self.error(element, f"<{element.tag}> has no attribute '{attribute.name}' "
                       f'(allowed: {allowed})', attribute.line, attribute.column)
        for name in required:
            if element.get(name) is None:
                self.error(element, f"<{element.tag}> needs the attribute '{name}'")

    def no_text(self, element: XmlElement) -> None:
        if element.text_at is not None:
            line, column = element.text_at
            self.error(element, f'<{element.tag}> holds text; only elements belong there', line, column)

    def children(self, element: XmlElement, allowed: tuple[str, ...], at_least: str | None
                 ) -> Iterator[XmlElement]:
        self.no_text(element)
        found = False
        for child in element.children:
            if child.tag not in allowed:
                expected = ', '.join(f'<{a}>' for a in allowed)
                self.error(child, f'<{child.tag}> is not allowed in <{element.tag}> '
                           f'(expected {expected})')
                continue
            found = found or child.tag == at_least
            yield child
        if at_least is not None and not found:
            self.error(element, f'<{element.tag}> needs at least one <{at_least}>')

    def check(self) -> list[Diagnostic]:
        root = self.parsed.root
        if root is None:
            return self.out
        if root.tag != 'policy':
            self.error(root, f'the root element is <{root.tag}>; an SROS 2 policy starts with <policy>')
            return self.out
        self.attributes(root, ('version',))
        version = root.get('version')
        if version is not None and version.value != POLICY_VERSION:
            self.error(root, f"policy version '{version.value}' is not supported; SROS 2 reads "
                       f"version '{POLICY_VERSION}'", version.line, version.column)
        enclaves = list(self.children(root, ('enclaves',), 'enclaves'))
        if len(enclaves) > 1:
            self.error(enclaves[1], '<policy> holds one <enclaves>, not several')
        for element in enclaves:
            self.attributes(element, ())
            for enclave in self.children(element, ('enclave',), 'enclave'):
                self.enclave(enclave)
        return self.out

    def enclave(self, enclave: XmlElement) -> None:
        self.attributes(enclave, ('path',))
        for profiles in self.children(enclave, ('profiles',), 'profiles'):
            self.attributes(profiles, (), ('type',))
            metadata_seen = False
            for child in self.children(profiles, ('profile', 'metadata'), 'profile'):
                if child.tag == 'metadata':
                    if metadata_seen:
                        self.error(child, '<profiles> holds at most one <metadata>')
                    metadata_seen = True
                    continue
                if metadata_seen:
                    self.error(child, '<profile> after <metadata>: <metadata> comes last')
                self.profile(child)

    def profile(self, profile: XmlElement) -> None:
        self.attributes(profile, ('ns', 'node'), ('xml:base',))
        for permissions in self.children(profile, tuple(_LISTS), None):
            kind = _LISTS[permissions.tag]
            self.attributes(permissions, (), kind.accesses + ('xml:base',))
            for access in kind.accesses:
                value = permissions.get(access)
                if value is not None and value.value not in QUALIFIERS:
                    self.error(permissions, f"{access}='{value.value}' is not a rule qualifier "
                               f'(expected {" or ".join(QUALIFIERS)})', value.line, value.column)
            for item in self.children(permissions, (kind.item,), kind.item):
                self.attributes(item, ())
                for child in item.children:
                    self.error(child, f'<{child.tag}> is not allowed in <{item.tag}>, which holds a name')


def check_policy_structure(parsed: ParsedPolicy) -> list[Diagnostic]:
    """Reading problems, then every way the document breaks the structure SROS 2 requires."""
    return list(parsed.tree.diagnostics) + _Checker(parsed).check()


def check_policy_text(text: str, file: str = '<policy>') -> list[Diagnostic]:
    """:func:`check_policy_structure` of a document given as text."""
    return check_policy_structure(read_policy(text, file))
