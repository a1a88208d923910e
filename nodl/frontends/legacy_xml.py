"""The legacy XML frontend: NoDL before v2 (specs 000, 001 and 002).

A legacy file is ``<interface version="1">`` holding ``<node name executable>``
elements, each with ``<parameter>``, ``<topic>``, ``<service>`` and ``<action>``
children.  Endpoint roles are written either as boolean attributes
(``publisher="true"``, ``subscription``, ``server``, ``client``; specs 000 and
001) or as one ``role`` attribute (``publisher|subscription|both``,
``server|client|both``; spec 002).  Endpoints may carry an old ``<qos>`` child.
Spec 000 exported such files from ``package.xml``
(``<export><interface path="..."/></export>``).

This module reads that format into plain records that remember the 1-based
line and column of every element (and of every attribute).  It never raises
for bad content: malformed XML, a wrong root, unknown elements or attributes,
missing names or types, invalid booleans, conflicting or missing roles are
:class:`~nodl.diagnostics.Diagnostic` objects, all collected.
The XML itself is read by :func:`nodl.frontends.xml_reader.load_xml`
(positions, no DTDs or entities, the size and encoding limits of
:mod:`nodl.frontends.source`).

Dataclasses and pathlib are not imported at module level, to keep the command
line fast.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any, NamedTuple

from nodl.diagnostics import Diagnosed, Diagnostic, Severity
from nodl.frontends.xml_reader import XmlAttribute, XmlElement, XmlTree, load_xml
from nodl.vocabulary import QOS_DURATIONS, QOS_ENUMS, legacy_roles

if TYPE_CHECKING:  # pragma: no cover - for type checkers only
    from pathlib import Path

    from nodl.frontends.source import Source

__all__ = [
    'LEGACY_VERSION', 'TOPIC_ROLES', 'SERVICE_ROLES', 'ACTION_ROLES', 'QOS_VALUES',
    'LEGACY_ONLY_QOS_VALUES',
    'LegacyQoS', 'LegacyParameter', 'LegacyEndpoint', 'LegacyNode', 'LegacyDocument',
    'legacy_document_from_tree', 'parse_legacy_xml',
    'ExportedInterface', 'package_exports_from_tree', 'package_exports',
    'interface_files_from_package_xml',
]

#: The only ``<interface version>`` the legacy format defines.
LEGACY_VERSION = '1'

TOPIC_ROLES = legacy_roles('topic')
SERVICE_ROLES = legacy_roles('service')
ACTION_ROLES = legacy_roles('action')
_ROLES = {'topic': TOPIC_ROLES, 'service': SERVICE_ROLES, 'action': ACTION_ROLES}
_ROLES_OF_OTHER_KINDS = {'topic': SERVICE_ROLES, 'service': TOPIC_ROLES, 'action': TOPIC_ROLES}

#: Accepted (lower-case) values of the enumerated ``<qos>`` attributes: the
#: rclpy short keys of the time.  Some have no NoDL v2 equivalent; the
#: converter says so.
#: The v2 values in lower case, plus the values only the legacy format knows.
LEGACY_ONLY_QOS_VALUES: dict[str, tuple[str, ...]] = {'liveliness': ('manual_by_node',)}
QOS_VALUES: dict[str, tuple[str, ...]] = {
    policy: tuple(v.lower() for v in values) + LEGACY_ONLY_QOS_VALUES.get(policy, ())
    for policy, values in QOS_ENUMS.items()}
_QOS_DURATIONS = tuple(QOS_DURATIONS.values())
_QOS_ATTRIBUTES = ('history', 'reliability', 'durability', 'depth', 'deadline', 'lifespan',
                   'liveliness', 'liveliness_lease_duration', 'avoid_ros_namespace_conventions')

_SECONDS = re.compile(r'[0-9]+(\.[0-9]*)?|\.[0-9]+')
_DEPTH = re.compile(r'[0-9]+')
_TRUE = ('true', '1')
_FALSE = ('false', '0')


# --------------------------------------------------------------------------
# Records


class _Record:
    """Plain value records (not dataclasses: importing dataclasses costs start-up time)."""

    __slots__: tuple[str, ...] = ()

    def __init__(self, **values: Any) -> None:
        for name in self.__slots__:
            setattr(self, name, values.pop(name, None))
        if values:
            raise TypeError(f'unknown fields for {type(self).__name__}: {sorted(values)}')

    def _key(self) -> tuple[Any, ...]:
        return tuple(getattr(self, name) for name in self.__slots__)

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return False
        assert isinstance(other, _Record)
        return self._key() == other._key()

    __hash__ = None  # type: ignore[assignment]  # mutable records

    def __repr__(self) -> str:
        fields = ', '.join(f'{name}={getattr(self, name)!r}' for name in self.__slots__)
        return f'{type(self).__name__}({fields})'


class LegacyQoS(_Record):
    """An old ``<qos>`` element.  Unset (absent or empty) attributes are ``None``.

    Policies are lower-case rclpy short keys (``keep_last``, ``best_effort``,
    ...); ``depth`` is an int; durations stay as written (seconds, ``".5"``).
    """

    __slots__ = ('history', 'reliability', 'durability', 'depth', 'deadline', 'lifespan',
                 'liveliness', 'liveliness_lease_duration', 'avoid_ros_namespace_conventions',
                 'line', 'column', 'positions')

    history: str | None
    reliability: str | None
    durability: str | None
    depth: int | None
    deadline: str | None
    lifespan: str | None
    liveliness: str | None
    liveliness_lease_duration: str | None
    avoid_ros_namespace_conventions: bool | None
    line: int
    column: int
    #: Attribute name -> (line, column) of the attribute in the file.
    positions: dict[str, tuple[int, int]]


class LegacyParameter(_Record):
    """A ``<parameter name type>`` element (the type as written)."""

    __slots__ = ('name', 'type', 'line', 'column', 'positions')

    name: str
    type: str
    line: int
    column: int
    positions: dict[str, tuple[int, int]]


class LegacyEndpoint(_Record):
    """A ``<topic>``, ``<service>`` or ``<action>`` element.

    ``kind`` is ``topic``, ``service`` or ``action``; ``roles`` the roles it
    plays, in canonical order (``('publisher', 'subscription')`` for a topic
    with role ``both``).
    """

    __slots__ = ('kind', 'name', 'type', 'roles', 'qos', 'line', 'column', 'positions')

    kind: str
    name: str
    type: str
    roles: tuple[str, ...]
    qos: LegacyQoS | None
    line: int
    column: int
    positions: dict[str, tuple[int, int]]


class LegacyNode(_Record):
    """A ``<node>`` element: its identity attributes and its interface, in file order."""

    __slots__ = ('name', 'executable', 'parameters', 'topics', 'services', 'actions',
                 'line', 'column', 'positions')

    name: str | None
    executable: str | None
    parameters: list[LegacyParameter]
    topics: list[LegacyEndpoint]
    services: list[LegacyEndpoint]
    actions: list[LegacyEndpoint]
    line: int
    column: int
    positions: dict[str, tuple[int, int]]


class LegacyDocument(_Record, Diagnosed):
    """A parsed legacy file: its nodes and every diagnostic found reading it.

    Elements with a structural error are left out of ``nodes``; a document
    with errors must not be converted as if it were complete.
    """

    __slots__ = ('file', 'version', 'nodes', 'diagnostics', 'line', 'column')

    file: str
    version: str | None
    nodes: list[LegacyNode]
    diagnostics: list[Diagnostic]
    line: int
    column: int


# --------------------------------------------------------------------------
# Interpreting a legacy interface file


def _error(file: str, message: str, line: int = 0, column: int = 0, *, code: str) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, (), file, line, column, code=code)


def _warning(file: str, message: str, line: int = 0, column: int = 0, *, code: str) -> Diagnostic:
    return Diagnostic(Severity.WARNING, message, (), file, line, column, code=code)


def _did_you_mean(word: str, choices: Iterable[str]) -> str:
    # Imported here: the validation package is not otherwise needed to read XML.
    from nodl.wording import did_you_mean

    return did_you_mean(word, choices)


def _is_ignored_attribute(name: str) -> bool:
    """Namespace declarations and XML Schema instance hints (``xsi:...``) are allowed anywhere."""
    return name == 'xmlns' or name.startswith(('xmlns:', 'xsi:', 'xml:'))


def _positions(element: XmlElement) -> dict[str, tuple[int, int]]:
    return {a.name: (a.line, a.column) for a in element.attributes}


class _LegacyReader:
    """Turns an :class:`XmlTree` into a :class:`LegacyDocument`, collecting diagnostics."""

    def __init__(self, tree: XmlTree) -> None:
        self.file = tree.file
        self.tree = tree
        self.diagnostics: list[Diagnostic] = list(tree.diagnostics)
        self.errors = sum(1 for d in self.diagnostics if d.severity is Severity.ERROR)

    # -- helpers ----------------------------------------------------------

    def error(self, message: str, at: XmlElement | XmlAttribute | tuple[int, int], *,
              code: str) -> None:
        line, column = (at.line, at.column) if isinstance(at, (XmlElement, XmlAttribute)) else at
        self.diagnostics.append(_error(self.file, message, line, column, code=code))
        self.errors += 1

    def warning(self, message: str, at: XmlElement | XmlAttribute, *, code: str) -> None:
        self.diagnostics.append(_warning(self.file, message, at.line, at.column, code=code))

    def error_count(self) -> int:
        # A running count: summing the diagnostics for every element was quadratic.
        return self.errors

    def attributes(self, element: XmlElement, allowed: Sequence[str],
                   hints: dict[str, str] | None = None) -> dict[str, XmlAttribute]:
        """The element's attributes by name; unknown ones are errors."""
        out: dict[str, XmlAttribute] = {}
        for attribute in element.attributes:
            if attribute.name in allowed:
                out[attribute.name] = attribute
            elif not _is_ignored_attribute(attribute.name):
                hint = (hints or {}).get(attribute.name)
                if hint is None:
                    hint = (f"; expected {', '.join(allowed)}"
                            + _did_you_mean(attribute.name, allowed)) if allowed else \
                        '; it takes no attributes'
                else:
                    hint = f'; {hint}'
                self.error(f"unknown attribute '{attribute.name}' on <{element.tag}>{hint}",
                           attribute, code='NODL801')
        return out

    def no_text(self, element: XmlElement) -> None:
        if element.text_at is not None:
            self.error(f'unexpected text inside <{element.tag}>; legacy NoDL elements hold '
                       'only elements and attributes', element.text_at, code='NODL801')

    def unknown_element(self, element: XmlElement, parent: XmlElement,
                        allowed: Sequence[str]) -> None:
        expected = (f"; <{parent.tag}> holds {', '.join(f'<{t}>' for t in allowed)}"
                    + _did_you_mean(element.tag, allowed)) if allowed else \
            f'; <{parent.tag}> holds no elements'
        self.error(f'unknown element <{element.tag}> inside <{parent.tag}>{expected}', element, code='NODL801')

    def required(self, element: XmlElement, attributes: dict[str, XmlAttribute],
                 name: str) -> str | None:
        attribute = attributes.get(name)
        if attribute is None:
            self.error(f"<{element.tag}> has no '{name}' attribute", element, code='NODL802')
            return None
        if not attribute.value.strip():
            self.error(f"'{name}' of <{element.tag}> is empty", attribute, code='NODL802')
            return None
        return attribute.value

    def boolean(self, attribute: XmlAttribute) -> bool | None:
        value = attribute.value.strip().lower()
        if value in _TRUE:
            return True
        if value in _FALSE:
            return False
        self.error(f"invalid value '{attribute.value}' for '{attribute.name}'; "
                   'expected true or false', attribute, code='NODL803')
        return None

    # -- elements ---------------------------------------------------------

    def document(self) -> LegacyDocument:
        root = self.tree.root
        doc = LegacyDocument(file=self.file, version=None, nodes=[], diagnostics=self.diagnostics,
                             line=root.line if root else 0, column=root.column if root else 0)
        if root is None:
            if not self.tree.diagnostics:
                self.error('the document has no root element', (1, 1), code='NODL806')
            return doc
        if root.tag != 'interface':
            hint = (' (this is a package manifest: convert it as a package.xml, which exports '
                    'interface files)' if root.tag == 'package' else '')
            self.error(f'the root element is <{root.tag}>; a legacy NoDL file has root '
                       f'<interface version="1">{hint}', root, code='NODL806')
            return doc
        attributes = self.attributes(root, ('version',))
        version = attributes.get('version')
        if version is None:
            self.warning(f"<interface> has no 'version' attribute; read as version "
                         f'{LEGACY_VERSION}', root, code='NODL805')
        elif version.value.strip() != LEGACY_VERSION:
            self.error(f"unsupported legacy NoDL version '{version.value}'; this reader knows "
                       f'version {LEGACY_VERSION}', version, code='NODL804')
        doc.version = version.value if version is not None else None
        self.no_text(root)
        for child in root.children:
            if child.tag == 'node':
                node = self.node(child)
                if node is not None:
                    doc.nodes.append(node)
            else:
                self.unknown_element(child, root, ('node',))
        if not root.children:
            self.warning('<interface> declares no nodes; there is nothing to convert', root, code='NODL809')
        self.diagnostics.sort(key=lambda d: (d.line, d.column))
        return doc

    def node(self, element: XmlElement) -> LegacyNode | None:
        attributes = self.attributes(element, ('name', 'executable'))
        values: dict[str, str | None] = {}
        for key in ('name', 'executable'):
            attribute = attributes.get(key)
            if attribute is not None and not attribute.value.strip():
                self.error(f"'{key}' of <node> is empty", attribute, code='NODL802')
            values[key] = attribute.value if attribute is not None and attribute.value.strip() \
                else None
        if 'name' not in attributes and 'executable' not in attributes:
            self.error("<node> has neither an 'executable' nor a 'name' attribute; one of them "
                       'says which node this is', element, code='NODL802')
        node = LegacyNode(name=values['name'], executable=values['executable'], parameters=[],
                          topics=[], services=[], actions=[], line=element.line,
                          column=element.column, positions=_positions(element))
        self.no_text(element)
        seen_parameters: dict[str, LegacyParameter] = {}
        for child in element.children:
            if child.tag == 'parameter':
                parameter = self.parameter(child)
                if parameter is None:
                    continue
                first = seen_parameters.get(parameter.name)
                if first is not None:
                    self.error(f"parameter '{parameter.name}' is declared twice in this node "
                               f'(first at line {first.line})', child, code='NODL807')
                    continue
                seen_parameters[parameter.name] = parameter
                node.parameters.append(parameter)
            elif child.tag in _ROLES:
                endpoint = self.endpoint(child)
                if endpoint is not None:
                    getattr(node, f'{child.tag}s').append(endpoint)
            else:
                self.unknown_element(child, element, ('parameter', 'topic', 'service', 'action'))
        return node

    def parameter(self, element: XmlElement) -> LegacyParameter | None:
        before = self.error_count()
        attributes = self.attributes(element, ('name', 'type'))
        name = self.required(element, attributes, 'name')
        type_ = self.required(element, attributes, 'type')
        self.no_text(element)
        for child in element.children:
            self.unknown_element(child, element, ())
        if self.error_count() != before or name is None or type_ is None:
            return None
        return LegacyParameter(name=name, type=type_, line=element.line, column=element.column,
                               positions=_positions(element))

    def endpoint(self, element: XmlElement) -> LegacyEndpoint | None:
        kind = element.tag
        roles = _ROLES[kind]
        before = self.error_count()
        other = _ROLES_OF_OTHER_KINDS[kind]
        hints = {word: (f"'{word}' is not a role of a {kind}; a {kind}'s roles are "
                        f'{" and ".join(roles)}') for word in other}
        attributes = self.attributes(element, ('name', 'type', *roles, 'role'), hints)
        name = self.required(element, attributes, 'name')
        type_ = self.required(element, attributes, 'type')
        played = self.roles(element, attributes, roles, name)
        self.no_text(element)
        qos: LegacyQoS | None = None
        first: XmlElement | None = None
        for child in element.children:
            if child.tag != 'qos':
                self.unknown_element(child, element, ('qos',))
            elif first is not None:
                self.error(f'<{kind}> has more than one <qos> (the first is at line '
                           f'{first.line})', child, code='NODL807')
            else:
                first = child
                qos = self.qos(child)
        if self.error_count() != before or name is None or type_ is None or not played:
            return None
        return LegacyEndpoint(kind=kind, name=name, type=type_, roles=played, qos=qos,
                              line=element.line, column=element.column,
                              positions=_positions(element))

    def roles(self, element: XmlElement, attributes: dict[str, XmlAttribute],
              roles: tuple[str, ...], name: str | None) -> tuple[str, ...]:
        """The roles an endpoint plays, from boolean attributes or a ``role`` attribute."""
        kind = element.tag
        flags: dict[str, bool] = {}
        for word in roles:
            attribute = attributes.get(word)
            if attribute is not None:
                value = self.boolean(attribute)
                if value is not None:
                    flags[word] = value
        from_flags = tuple(word for word in roles if flags.get(word))
        role = attributes.get('role')
        from_role: tuple[str, ...] | None = None
        if role is not None:
            role_value = role.value.strip()
            if role_value == 'both':
                from_role = roles
            elif role_value in roles:
                from_role = (role_value,)
            else:
                choices = (*roles, 'both')
                self.error(f"invalid role '{role.value}' for <{kind}>; expected "
                           f"{', '.join(choices[:-1])} or {choices[-1]}"
                           + _did_you_mean(role_value, choices), role, code='NODL803')
                return ()
        written = [attributes[w] for w in roles if w in attributes]
        if role is not None and from_role is not None and written:
            flag_text = ' '.join(f'{a.name}="{a.value}"' for a in written)
            if set(from_role) == set(from_flags):
                self.warning(f'<{kind}> gives its role twice, as role="{role.value}" and as '
                             f'{flag_text}; keep only role="{role.value}"', role, code='NODL815')
            else:
                self.error(f'role="{role.value}" conflicts with {flag_text} on <{kind}>; '
                           'use only the role attribute', role, code='NODL808')
                return ()
        played = from_role if from_role is not None else from_flags
        misplaced = any(a.name in _ROLES_OF_OTHER_KINDS[kind] for a in element.attributes)
        if not played and len(flags) == len(written) and not misplaced:
            label = f" '{name}'" if name else ''
            self.error(f'<{kind}>{label} has no role: give role="{roles[0]}", "{roles[1]}" or '
                       f'"both" (or {roles[0]}="true" / {roles[1]}="true")', element, code='NODL808')
        return played

    def qos(self, element: XmlElement) -> LegacyQoS | None:
        before = self.error_count()
        attributes = self.attributes(element, _QOS_ATTRIBUTES)
        self.no_text(element)
        for child in element.children:
            self.unknown_element(child, element, ())
        qos = LegacyQoS(line=element.line, column=element.column, positions=_positions(element))
        for key, attribute in attributes.items():
            value = attribute.value.strip()
            if not value:
                continue  # an empty string means unset
            if key in QOS_VALUES:
                lowered = value.lower()
                if lowered in QOS_VALUES[key]:
                    setattr(qos, key, lowered)
                else:
                    self.error(f"invalid {key} '{attribute.value}' in <qos>; expected one of: "
                               f"{', '.join(QOS_VALUES[key])}"
                               + _did_you_mean(lowered, QOS_VALUES[key]), attribute, code='NODL803')
            elif key == 'depth':
                if _DEPTH.fullmatch(value):
                    qos.depth = int(value)
                else:
                    self.error(f"invalid depth '{attribute.value}' in <qos>; expected a "
                               'non-negative integer', attribute, code='NODL803')
            elif key in _QOS_DURATIONS:
                if _SECONDS.fullmatch(value):
                    setattr(qos, key, value)
                else:
                    self.error(f"invalid {key} '{attribute.value}' in <qos>; expected a "
                               'non-negative number of seconds such as 0.5', attribute, code='NODL803')
            else:  # avoid_ros_namespace_conventions
                qos.avoid_ros_namespace_conventions = self.boolean(attribute)
        return qos if self.error_count() == before else None


def legacy_document_from_tree(tree: XmlTree) -> LegacyDocument:
    """Interpret a parsed XML tree as a legacy NoDL interface file."""
    return _LegacyReader(tree).document()


def parse_legacy_xml(source: Source, file: str | None = None) -> LegacyDocument:
    """Read a legacy ``.nodl.xml`` file (text, bytes, a file object or a path).

    Never raises for bad content: every problem is in the returned
    document's ``diagnostics``.  I/O errors propagate as :class:`OSError`.
    """
    return legacy_document_from_tree(load_xml(source, file))


# --------------------------------------------------------------------------
# package.xml exports (spec 000)


class ExportedInterface(NamedTuple):
    """An ``<interface path>`` exported by a package.xml, resolved against its directory."""

    path: str
    line: int
    column: int


def package_exports_from_tree(tree: XmlTree) -> tuple[list[ExportedInterface], list[Diagnostic]]:
    """The interface files a parsed package.xml exports, and what is wrong with the export."""
    file = tree.file
    diagnostics = list(tree.diagnostics)
    root = tree.root
    if root is None:
        if not diagnostics:
            diagnostics.append(_error(file, 'the document has no root element', 1, 1, code='NODL806'))
        return [], diagnostics
    if root.tag != 'package':
        diagnostics.append(_error(file, f'the root element is <{root.tag}>; a package manifest '
                                  'has root <package>', root.line, root.column, code='NODL806'))
        return [], diagnostics
    base = os.path.dirname(file)
    exports = [child for child in root.children if child.tag == 'export']
    found: list[ExportedInterface] = []
    seen: set[str] = set()
    for export in exports:
        for child in export.children:
            if child.tag != 'interface':
                continue  # other tools' exports (build_type, ...)
            path = child.get('path')
            for attribute in child.attributes:
                if attribute.name != 'path' and not _is_ignored_attribute(attribute.name):
                    diagnostics.append(_error(
                        file, f"unknown attribute '{attribute.name}' on <interface>; "
                        'expected path', attribute.line, attribute.column, code='NODL801'))
            if path is None:
                diagnostics.append(_error(file, "<interface> has no 'path' attribute",
                                          child.line, child.column, code='NODL802'))
                continue
            value = path.value.strip()
            if not value:
                diagnostics.append(_error(file, "'path' of <interface> is empty",
                                          path.line, path.column, code='NODL802'))
                continue
            normal = os.path.normpath(value)
            if os.path.isabs(value) or normal == '..' or normal.startswith('..' + os.sep):
                diagnostics.append(_error(
                    file, f"interface path '{value}' leaves the package; it must be relative to "
                    'the directory of package.xml', path.line, path.column, code='NODL810'))
                continue
            if normal in seen:
                diagnostics.append(_warning(file, f"interface path '{value}' is exported twice",
                                            path.line, path.column, code='NODL815'))
                continue
            seen.add(normal)
            found.append(ExportedInterface(os.path.join(base, normal), path.line, path.column))
    if not found and not any(d.severity is Severity.ERROR for d in diagnostics):
        where = exports[0] if exports else root
        diagnostics.append(_error(
            file, 'package.xml exports no interface file; add '
            '<export><interface path="FILE.nodl.xml"/></export>', where.line, where.column, code='NODL810'))
    return found, diagnostics


def package_exports(source: Source,
                    file: str | None = None) -> tuple[list[ExportedInterface], list[Diagnostic]]:
    """Read a package.xml and return the interface files it exports, with positions.

    Paths are resolved against the directory of ``file`` (or of the path).
    I/O errors propagate as :class:`OSError`.
    """
    return package_exports_from_tree(load_xml(source, file))


def interface_files_from_package_xml(
        path: str | os.PathLike[str]) -> tuple[list[Path], list[Diagnostic]]:
    """The paths a package.xml exports with ``<export><interface path="..."/></export>``.

    Paths are relative to the package.xml directory in the file and are
    returned joined to it.  A missing or invalid export is a diagnostic.
    I/O errors propagate as :class:`OSError`.
    """
    from pathlib import Path

    exports, diagnostics = package_exports(Path(path))
    return [Path(e.path) for e in exports], diagnostics
