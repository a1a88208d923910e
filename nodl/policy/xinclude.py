"""XInclude in hand-written policies, expanded as SROS 2 expands it before it validates a policy.

SROS 2 loads a policy, runs XInclude on it and only then checks it against
``policy.xsd``; its own sample policies share the base node's permissions
that way (``<xi:include href="common/node.xml" xpointer="xpointer(/profile/*)"/>``).
:func:`expand_includes` does the same to a tree read by the toolkit's safe
XML reader, for what such policies use:

* ``<include>`` in the XInclude namespace (2001 or 2003, as libxml2 accepts
  both), under whatever prefix the document declares for it;
* ``href``: a local file, relative to the including file (no URLs);
  ``parse`` absent or ``xml``;
* ``xpointer``: absent (the included document's root element) or
  ``xpointer(/a/b/*)`` (the children of the elements that absolute path
  selects).

Anything else (other XPointer forms, ``<fallback>``, text inclusion, a file
that cannot be read, an include cycle, nesting deeper than
:data:`MAX_DEPTH`) is reported (NODL606) at the include and leaves nothing
in its place.  Included elements keep the positions of their own file, which
:class:`Origins` remembers, so findings name the file a grant is written in.

Hostile policies stay bounded: at most :data:`MAX_INCLUDES` includes are expanded
(NODL614 at the first one past it: an "include bomb" of files that include each other
many times over), the included text totals at most :data:`MAX_INCLUDED_BYTES`
(NODL615), and an ``href`` must lead to a file inside the including file's folder tree
once ``..`` and symbolic links are resolved (NODL616: a policy does not read
``../../etc/...``).  Each is said once, at the include, and expands to nothing.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import NamedTuple

from nodl.diagnostics import Diagnostic, Severity
from nodl.files import describe_os_error
from nodl.frontends.source import read_source
from nodl.frontends.xml_reader import XmlElement, load_xml

__all__ = ['XINCLUDE_NAMESPACES', 'MAX_DEPTH', 'MAX_INCLUDES', 'MAX_INCLUDED_BYTES', 'Origin', 'Origins',
           'expand_includes']

#: The namespaces of XInclude (the 2001 draft, which SROS 2's policies use, and 2003's).
XINCLUDE_NAMESPACES = ('http://www.w3.org/2001/XInclude', 'http://www.w3.org/2003/XInclude')
#: How deep includes may nest.
MAX_DEPTH = 16
#: How many includes one policy may expand in all (SROS 2's samples use a handful; a
#: system of hundreds of profiles each including a few common files stays well below).
MAX_INCLUDES = 1000
#: How much included text one policy may expand in all (each include counts its whole file,
#: every time it is included): the 10 MB one file may hold.
MAX_INCLUDED_BYTES = 10 * 1024 * 1024

_XPOINTER = re.compile(r'xpointer\((/[A-Za-z_][\w.-]*(?:/[A-Za-z_][\w.-]*)*)/\*\)')
_LINE_BREAK = re.compile(r'\r\n|\r|\n')


class Origin(NamedTuple):
    """A file elements were read from: its name, text and line offsets."""

    file: str
    text: str
    line_starts: list[int]


def origin_of_text(file: str, text: str) -> Origin:
    """The :class:`Origin` of ``text`` read from ``file``."""
    return Origin(file, text, [0] + [m.end() for m in _LINE_BREAK.finditer(text)])


class Origins(dict[int, Origin]):
    """``id(element)`` -> the :class:`Origin` of an included element (elements of the main file are absent)."""

    def mark(self, element: XmlElement, origin: Origin) -> None:
        """Record ``origin`` for ``element`` and everything in it not included from further away."""
        if id(element) in self:
            return
        self[id(element)] = origin
        for child in element.children:
            self.mark(child, origin)


def _problem(origin: Origin, element: XmlElement, message: str, code: str = 'NODL606') -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, (), origin.file, element.line, element.column,
                      code=code)


def _prefixes(element: XmlElement, inherited: dict[str, str]) -> dict[str, str]:
    declared = {a.name[6:] if a.name.startswith('xmlns:') else '': a.value
                for a in element.attributes if a.name == 'xmlns' or a.name.startswith('xmlns:')}
    return {**inherited, **declared} if declared else inherited


def _is_include(element: XmlElement, prefixes: dict[str, str]) -> bool:
    prefix, _, local = element.tag.rpartition(':')
    return local == 'include' and prefixes.get(prefix) in XINCLUDE_NAMESPACES


def expand_includes(root: XmlElement, origin: Origin, origins: Origins,
                    problems: list[Diagnostic]) -> None:
    """Replace every include under ``root`` by what it includes (in place)."""
    _Expander(origins, problems).walk(root, origin, {}, (os.path.realpath(origin.file),))


class _Expander:
    def __init__(self, origins: Origins, problems: list[Diagnostic]) -> None:
        self.origins = origins
        self.problems = problems
        #: Includes expanded so far, and the characters of included text read for them.
        self.count = 0
        self.size = 0
        #: The limit (NODL614, NODL615) that stopped the expansion, once reported.
        self.stopped = False

    def walk(self, element: XmlElement, origin: Origin, inherited: dict[str, str],
             chain: tuple[str, ...]) -> None:
        prefixes = _prefixes(element, inherited)
        children: list[XmlElement] = []
        for child in element.children:
            child_prefixes = _prefixes(child, prefixes)
            if _is_include(child, child_prefixes):
                children += self.include(child, origin, chain)
            else:
                self.walk(child, origin, prefixes, chain)
                children.append(child)
        element.children = children

    def include(self, include: XmlElement, origin: Origin, chain: tuple[str, ...]) -> list[XmlElement]:
        allowed = {'href', 'xpointer', 'parse'}
        for attribute in include.attributes:
            name = attribute.name
            if name not in allowed and name != 'xmlns' and not name.startswith('xmlns:'):
                self.problems.append(_problem(origin, include, f"<{include.tag}>: the attribute "
                                              f"'{name}' is not supported (href, xpointer, parse)"))
                return []
        if include.children:
            self.problems.append(_problem(origin, include, f'<{include.tag}>: <fallback> and other '
                                          'content are not supported'))
            return []
        parse = include.get('parse')
        if parse is not None and parse.value != 'xml':
            self.problems.append(_problem(origin, include, f"<{include.tag}>: parse='{parse.value}' "
                                          "is not supported (a policy includes XML)"))
            return []
        href = include.get('href')
        if href is None or not href.value or re.match(r'[A-Za-z][\w+.-]*://', href.value):
            self.problems.append(_problem(origin, include, f'<{include.tag}> needs href, the path of '
                                          'a local file (relative to this one)'))
            return []
        base = os.path.dirname(origin.file) if not origin.file.startswith('<') else os.getcwd()
        path = os.path.abspath(os.path.join(base, href.value))
        real, folder = os.path.realpath(path), os.path.realpath(base)
        if os.path.commonpath([real, folder]) != folder:
            self.problems.append(_problem(origin, include, f"<{include.tag}>: href '{href.value}' leads "
                                          f'to {real}, outside the folder of the including file '
                                          f'({folder}); an included file must be in that folder or '
                                          'below it (after resolving .. and symbolic links)', 'NODL616'))
            return []
        if real in chain:
            self.problems.append(_problem(origin, include, f'<{include.tag}>: {href.value} includes '
                                          'itself (an include cycle)'))
            return []
        if len(chain) > MAX_DEPTH:
            self.problems.append(_problem(origin, include, f'<{include.tag}>: includes nest deeper '
                                          f'than {MAX_DEPTH}'))
            return []
        if self.stopped:
            return []
        self.count += 1
        if self.count > MAX_INCLUDES:
            self.stopped = True
            self.problems.append(_problem(origin, include, f'<{include.tag}>: more than {MAX_INCLUDES:,} '
                                          'includes in one policy (files including each other many '
                                          'times over?); this and every later include are not '
                                          'expanded', 'NODL614'))
            return []
        pointer = include.get('xpointer')
        steps: list[str] = []
        if pointer is not None:
            matched = _XPOINTER.fullmatch(pointer.value.strip())
            if matched is None:
                self.problems.append(_problem(origin, include, f"<{include.tag}>: xpointer "
                                              f"'{pointer.value}' is not supported (write "
                                              "xpointer(/element/path/*) or none)"))
                return []
            steps = matched.group(1).strip('/').split('/')
        included = self.read(include, origin, path, href.value)
        if included is None:
            return []
        root, included_origin = included
        self.walk(root, included_origin, {}, chain + (real,))
        if not steps:
            selected = [root]
        else:
            level = [root] if root.tag == steps[0] else []
            for step in steps[1:]:
                level = [child for element in level for child in element.children if child.tag == step]
            selected = [child for element in level for child in element.children]
        for element in selected:
            self.origins.mark(element, included_origin)
        return selected

    def read(self, include: XmlElement, origin: Origin, path: str, href: str
             ) -> tuple[XmlElement, Origin] | None:
        shown = os.path.relpath(path) if not os.path.isabs(origin.file) else path
        try:
            read, problem = read_source(Path(path), shown)
        except OSError as exc:
            self.problems.append(_problem(origin, include, f'<{include.tag}>: cannot read {href}: '
                                          f'{describe_os_error(exc)}'))
            return None
        if read is None:
            assert problem is not None
            self.problems.append(problem)
            return None
        self.size += len(read.text)
        if self.size > MAX_INCLUDED_BYTES:
            self.stopped = True
            self.problems.append(_problem(origin, include, f'<{include.tag}>: the included files total '
                                          f'more than {MAX_INCLUDED_BYTES:,} characters (each include '
                                          'counts its whole file); this and every later '
                                          'include are not expanded', 'NODL615'))
            return None
        tree = load_xml(read.text, read.file)
        self.problems.extend(tree.diagnostics)
        if tree.root is None:
            return None
        return tree.root, origin_of_text(read.file, read.text)
