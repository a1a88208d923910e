"""Converting legacy NoDL XML to NoDL v2 node definitions.

Every ``<node>`` of a legacy file becomes one node definition
(``base: node``, its interface in ``main``), named after its executable
(``<executable>.nodl.yaml``, or ``<name>.nodl.yaml`` without one).

* A ``both`` role (or both boolean roles) lands in both sections.
* ``<qos>`` is carried over: rclpy short keys become v2 policy names
  (``keep_last`` -> ``KEEP_LAST``), durations in seconds become ``*_ns``
  integers.  A ``<qos>`` with a depth and no history means ``KEEP_LAST`` (as
  rclpy read it).  v2 requires a history and a reliability for a profile: what
  is missing is written ``SYSTEM_DEFAULT``, with a warning.  A topic without
  ``<qos>`` gets ``{history: SYSTEM_DEFAULT, reliability: SYSTEM_DEFAULT}``,
  with a warning.
* Parameter types are mapped to v2 (``integer_array`` -> ``int_array``, ...).
* What has no v2 meaning is left out with a warning naming it: the node
  ``name`` (v2 files carry no node identity), ``avoid_ros_namespace_conventions``,
  ``<qos>`` on an action, QoS values v2 lacks, unknown parameter types (written
  ``none``).

Each converted document is validated as a v2 node definition; what fails is
an error placed at the legacy element it came from.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from nodl.diagnostics import Diagnostic, DocPath, Severity, has_errors
from nodl.frontends.legacy_xml import (
    LEGACY_ONLY_QOS_VALUES,
    LegacyDocument,
    LegacyEndpoint,
    LegacyNode,
    LegacyQoS,
    legacy_document_from_tree,
    package_exports_from_tree,
)
from nodl.frontends.xml_reader import XmlTree, load_xml
from nodl.legacy.converted import Converted, Origins, origin_of
from nodl.vocabulary import ENDPOINT_KINDS, KIND_NAMESPACES, QOS_DURATIONS, SECTION_KEYS
from nodl.vocabulary import SECTIONS as _VOCABULARY_SECTIONS

if TYPE_CHECKING:  # pragma: no cover
    from pathlib import Path

    from nodl.writing import WriteError

__all__ = ['Converted', 'FileConversion', 'convert_legacy', 'render_converted', 'convert_file',
           'convert_files', 'seconds_to_ns']

#: Legacy parameter type (lower case) -> v2 type.  ROS 2 parameter type names
#: (rcl_interfaces ParameterType, as rclpy spells them) and v2's own names.
PARAMETER_TYPES = {
    'bool': 'bool',
    'int': 'int',
    'integer': 'int',
    'double': 'double',
    'string': 'string',
    'byte_array': 'byte_array',
    'bool_array': 'bool_array',
    'int_array': 'int_array',
    'integer_array': 'int_array',
    'double_array': 'double_array',
    'string_array': 'string_array',
    'not_set': 'none',
    'none': 'none',
}

#: Endpoint kind -> legacy role -> v2 section.
SECTIONS: dict[str, dict[str, str]] = {
    kind: {s.legacy_role: s.key for s in _VOCABULARY_SECTIONS if s.kind == kind}
    for kind in ENDPOINT_KINDS}
_SECTION_ORDER = SECTION_KEYS
_INTERFACE_NAMESPACE = KIND_NAMESPACES

#: Legacy QoS values v2 has no name for.
_QOS_WITHOUT_V2 = {(policy, value) for policy, values in LEGACY_ONLY_QOS_VALUES.items()
                   for value in values}
_DURATIONS = tuple((legacy, v2) for v2, legacy in QOS_DURATIONS.items())
_INT64_MAX = 2 ** 63 - 1
_SHORT_TYPE = re.compile(r'([A-Za-z][A-Za-z0-9_]*)/([A-Za-z][A-Za-z0-9_]*)')
_FILE_STEM = re.compile(r'[A-Za-z0-9_][A-Za-z0-9_.+-]*')
_SUFFIX = '.nodl.yaml'


def seconds_to_ns(seconds: str) -> int:
    """``'.5'`` -> ``500000000``: a legacy duration (seconds) in whole nanoseconds.

    Digits beyond nanoseconds are dropped.  Raises :class:`ValueError` for
    text that is not a non-negative decimal number.
    """
    text = seconds.strip()
    whole, _, fraction = text.partition('.')
    if not (whole or fraction) or not (whole or '0').isdigit() or \
            (fraction and not fraction.isdigit()) or not text.isascii():
        raise ValueError(f'not a number of seconds: {seconds!r}')
    return int(whole or '0') * 1_000_000_000 + int((fraction + '0' * 9)[:9])


class _NodeConverter:
    """Converts one legacy node, collecting diagnostics and where each v2 path came from."""

    def __init__(self, node: LegacyNode, file: str) -> None:
        self.node = node
        self.file = file
        self.diagnostics: list[Diagnostic] = []
        #: The source map the converted document carries (see Converted.origins).
        self.origins: Origins = {(): (node.line, node.column)}
        #: True while converting an endpoint a second time (its second role):
        #: what there is to say about it was said the first time.
        self.quiet = False
        #: Paths of the v2 document where the converter found an error.
        self.failed: list[DocPath] = []

    def warn(self, message: str, at: tuple[int, int], path: DocPath = (), *, code: str) -> None:
        if not self.quiet:
            self.diagnostics.append(Diagnostic(Severity.WARNING, message, path, self.file, *at,
                                               code=code))

    def fail(self, message: str, at: tuple[int, int], path: DocPath = (), *, code: str) -> None:
        if path:
            self.failed.append(path)
        if not self.quiet:
            self.diagnostics.append(Diagnostic(Severity.ERROR, message, path, self.file, *at,
                                               code=code))

    def remember(self, path: DocPath, element: Any) -> None:
        """Record that ``path`` (and its ``name``/``type`` keys) came from ``element``."""
        self.origins[path] = (element.line, element.column)
        for key in ('name', 'type'):
            if key in element.positions:
                self.origins[path + (key,)] = element.positions[key]

    def convert(self) -> dict[str, Any]:
        node = self.node
        if node.name is not None:
            used = '' if node.executable else ' (it only names the converted file)'
            self.warn(f"node name '{node.name}' is not carried over{used}: a NoDL v2 file does "
                      "not declare its node's name (it comes from the package and the launch "
                      'configuration)', node.positions.get('name', (node.line, node.column)),
                      code='NODL811')
        main: dict[str, Any] = {'nodl_version': 2}
        if node.parameters:
            main['parameters'] = self.parameters()
        sections: dict[str, list[dict[str, Any]]] = {}
        for endpoint in (*node.topics, *node.services, *node.actions):
            for index, role in enumerate(endpoint.roles):
                section = SECTIONS[endpoint.kind][role]
                entries = sections.setdefault(section, [])
                path: DocPath = ('main', section, len(entries))
                self.quiet = index > 0
                entries.append(self.endpoint(endpoint, path))
            self.quiet = False
        for section in _SECTION_ORDER:
            if section in sections:
                main[section] = sections[section]
        return {'nodl_version': 2, 'base': 'node', 'main': main}

    def parameters(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for parameter in self.node.parameters:
            path: DocPath = ('main', 'parameters', parameter.name)
            self.remember(path, parameter)
            at = parameter.positions.get('type', (parameter.line, parameter.column))
            written = parameter.type.strip()
            v2_type = PARAMETER_TYPES.get(written.lower())
            if v2_type is None and _is_v2_parameter_type(written):
                v2_type = written
            if v2_type is None:
                v2_type = 'none'
                self.warn(f"parameter '{parameter.name}' has type '{parameter.type}', which is "
                          "not a ROS 2 parameter type; written as 'none' (a parameter of any "
                          'type): set the right type', at, path + ('type',), code='NODL812')
            out[parameter.name] = {'type': v2_type}
        return out

    def endpoint(self, endpoint: LegacyEndpoint, path: DocPath) -> dict[str, Any]:
        self.remember(path, endpoint)
        out: dict[str, Any] = {'name': endpoint.name,
                               'type': self.interface_type(endpoint, path)}
        qos = endpoint.qos
        if qos is not None:
            self.origins[path + ('qos',)] = (qos.line, qos.column)
            for key, at in qos.positions.items():
                self.origins[path + ('qos', key)] = at
        if endpoint.kind == 'action':
            if qos is not None:
                self.warn(f"<qos> of action '{endpoint.name}' is dropped: NoDL v2 actions have "
                          'no QoS profile', (qos.line, qos.column), path, code='NODL811')
        elif qos is not None:
            out['qos'] = self.qos(qos, endpoint, path + ('qos',))
        elif endpoint.kind == 'topic':
            out['qos'] = {'history': 'SYSTEM_DEFAULT', 'reliability': 'SYSTEM_DEFAULT'}
            self.warn(f"topic '{endpoint.name}' has no <qos>; NoDL v2 requires one: written as "
                      'history SYSTEM_DEFAULT, reliability SYSTEM_DEFAULT (set the real profile)',
                      (endpoint.line, endpoint.column), path + ('qos',), code='NODL812')
        return out

    def interface_type(self, endpoint: LegacyEndpoint, path: DocPath) -> str:
        """The type, with the interface namespace added to a short ``pkg/Type``."""
        short = _SHORT_TYPE.fullmatch(endpoint.type)
        if short is None:
            return endpoint.type
        full = f'{short.group(1)}/{_INTERFACE_NAMESPACE[endpoint.kind]}/{short.group(2)}'
        self.warn(f"type '{endpoint.type}' omits the interface namespace; written as '{full}'",
                  endpoint.positions.get('type', (endpoint.line, endpoint.column)),
                  path + ('type',), code='NODL812')
        return full

    def qos(self, qos: LegacyQoS, endpoint: LegacyEndpoint, path: DocPath) -> dict[str, Any]:
        where = (qos.line, qos.column)

        def attr(key: str) -> tuple[int, int]:
            return qos.positions.get(key, where)

        def warn(message: str, at: tuple[int, int], key: str | None = None, *, code: str) -> None:
            self.warn(message, at, path + ((key,) if key else ()), code=code)

        def fail(message: str, at: tuple[int, int], key: str | None = None) -> None:
            self.fail(message, at, path + ((key,) if key else ()), code='NODL813')

        label = f"{endpoint.kind} '{endpoint.name}'"
        out: dict[str, Any] = {}
        if qos.history is not None:
            out['history'] = qos.history.upper()
        elif qos.depth is not None:
            out['history'] = 'KEEP_LAST'
        else:
            out['history'] = 'SYSTEM_DEFAULT'
            warn(f'<qos> of {label} sets neither history nor depth; NoDL v2 requires a history: '
                 'written as SYSTEM_DEFAULT', where, 'history', code='NODL812')
        if qos.reliability is not None:
            out['reliability'] = qos.reliability.upper()
        else:
            out['reliability'] = 'SYSTEM_DEFAULT'
            warn(f'<qos> of {label} does not set reliability; NoDL v2 requires it: written as '
                 'SYSTEM_DEFAULT (the legacy toolkit, through rclpy, read it as RELIABLE; set '
                 'the real policy)',
                 attr('reliability'), 'reliability', code='NODL812')
        if qos.depth is not None:
            if qos.depth > 0:
                out['depth'] = qos.depth
            elif out['history'] == 'KEEP_LAST':
                fail(f'<qos> of {label} has depth 0 with history keep_last; NoDL v2 requires '
                     'a depth of at least 1', attr('depth'), 'depth')
            else:
                warn(f'depth 0 in <qos> of {label} is dropped: it has no meaning with history '
                     f"{qos.history or 'unset'}", attr('depth'), 'depth', code='NODL811')
        elif out['history'] == 'KEEP_LAST':
            fail(f'<qos> of {label} has history keep_last but no depth; NoDL v2 requires a '
                 'depth with KEEP_LAST', attr('history'), 'depth')
        if qos.durability is not None:
            out['durability'] = qos.durability.upper()
        for legacy, v2 in _DURATIONS[:2]:
            self.duration(qos, legacy, v2, out, label, warn, fail)
        if qos.liveliness is not None:
            if ('liveliness', qos.liveliness) in _QOS_WITHOUT_V2:
                warn(f"liveliness '{qos.liveliness}' in <qos> of {label} is dropped: NoDL v2 "
                     'has no such policy (use automatic or manual_by_topic)',
                     attr('liveliness'), 'liveliness', code='NODL811')
            else:
                out['liveliness'] = qos.liveliness.upper()
        self.duration(qos, *_DURATIONS[2], out, label, warn, fail)
        if qos.avoid_ros_namespace_conventions:
            warn(f'avoid_ros_namespace_conventions in <qos> of {label} is dropped: NoDL v2 '
                 'has no equivalent (names always follow the ROS conventions)',
                 attr('avoid_ros_namespace_conventions'), code='NODL811')
        return out

    def duration(self, qos: LegacyQoS, legacy: str, v2: str, out: dict[str, Any], label: str,
                 warn: Any, fail: Any) -> None:
        text = getattr(qos, legacy)
        if text is None:
            return
        at = qos.positions.get(legacy, (qos.line, qos.column))
        try:
            value = seconds_to_ns(text)
        except ValueError:
            fail(f"{legacy} '{text}' in <qos> of {label} is not a number of seconds", at, v2)
            return
        if value > _INT64_MAX:
            fail(f"{legacy} '{text}' s in <qos> of {label} is too large: at most "
                 f'{_INT64_MAX} ns', at, v2)
            return
        fraction = text.strip().partition('.')[2]
        if fraction[9:].strip('0'):
            warn(f"{legacy} '{text}' s in <qos> of {label} is finer than a nanosecond; "
                 f'written as {value} ns', at, v2, code='NODL811')
        out[v2] = value


def _is_v2_parameter_type(name: str) -> bool:
    from nodl.model.parameter_types import parse_type

    return parse_type(name) is not None


def _file_stems(nodes: list[LegacyNode]) -> list[str | None]:
    """``executable`` (or ``name``) per node; ``executable.name`` when an executable has several."""
    stems = [n.executable or n.name for n in nodes]
    counts: dict[str | None, int] = {}
    for stem in stems:
        counts[stem] = counts.get(stem, 0) + 1
    return [f'{n.executable}.{n.name}'
            if counts[stem] > 1 and n.executable is not None and n.name is not None else stem
            for stem, n in zip(stems, nodes, strict=True)]


def _validate(data: dict[str, Any], converter: _NodeConverter) -> None:
    """Validate the v2 document; place what it finds at the legacy element it came from."""
    from nodl.diagnostics import ValidationError
    from nodl.loading import validate_node

    try:
        found = validate_node(data)
    except ValidationError as exc:
        found = exc.diagnostics
    said: set[tuple[Any, ...]] = set()
    for d in found:
        if any(p[:len(d.path)] == d.path or d.path[:len(p)] == p for p in converter.failed):
            continue  # the converter already said what is wrong there
        if d.code == 'NODL216':
            continue  # the legacy format has no descriptions: nothing the converter can do
        line, column = origin_of(converter.origins, d.path)
        key = (d.severity, d.message, line, column)
        if key in said:
            continue  # an endpoint with both roles is in two sections: say it once
        said.add(key)
        prefix = 'not valid in NoDL v2: ' if d.severity is Severity.ERROR else ''
        converter.diagnostics.append(d.replace(message=prefix + d.message, file=converter.file,
                                               line=line, column=column))


def convert_legacy(doc: LegacyDocument) -> list[Converted]:
    """Convert every node of a legacy document into a v2 node definition.

    Nodes are converted even when the document has errors (elements with a
    structural error are not in it); check ``doc.ok`` before using the result
    as a complete conversion.
    """
    out: list[Converted] = []
    taken: dict[str, LegacyNode] = {}
    for node, stem in zip(doc.nodes, _file_stems(doc.nodes), strict=True):
        converter = _NodeConverter(node, doc.file)
        data = converter.convert()
        _validate(data, converter)
        at = (node.line, node.column)
        if stem is None:
            file_name = f'node-{node.line}{_SUFFIX}'  # only for a node with a structural error
        elif not _FILE_STEM.fullmatch(stem):
            key = 'executable' if node.executable else 'name'
            converter.fail(f"{key} '{stem}' cannot be used as a file name (letters, digits, "
                           "'_', '-', '+' and '.' only, not starting with '.'); rename it",
                           node.positions.get(key, at), code='NODL814')
            file_name = f'node-{node.line}{_SUFFIX}'
        else:
            file_name = stem + _SUFFIX
            if stem != (node.executable or node.name):
                converter.warn(f"executable '{node.executable}' holds several nodes; this one "
                               f'is written to {file_name}', at, code='NODL816')
        first = taken.get(file_name)
        if first is not None:
            converter.fail(f'another node (line {first.line}) is already converted to '
                           f'{file_name}; give the nodes different executables or names', at,
                           code='NODL814')
        else:
            taken[file_name] = node
        converter.diagnostics.sort(key=lambda d: (d.line, d.column))
        out.append(Converted(file_name, data, converter.diagnostics, doc.file, node,
                             converter.origins))
    return out


def render_converted(converted: Converted) -> str:
    """The YAML text of a converted node, with a header saying where it came from."""
    from nodl.loading import dump_nodl
    from nodl.text_safety import one_line

    node = converted.node
    identity = ', '.join(f"{key} '{one_line(value)}'" for key, value in
                         (('node', node.name), ('executable', node.executable)) if value)
    # The last line marks what the legacy format cannot say (see nodl.overrides): no
    # 'has no description' warning, even with --strict, until someone writes the descriptions.
    header = (f'# Converted from {one_line(converted.source)} by `nodl convert`\n'
              f'# (legacy NoDL XML: {identity}, line {node.line}).\n'
              '# nodl: ignore=NODL216 (legacy NoDL has no descriptions: write them, then remove '
              'this line)\n')
    document = converted.document
    return header + dump_nodl(document if document is not None else converted.data)


class FileConversion:
    """The outcome of converting one input file: what was written, diagnostics, or why not read."""

    __slots__ = ('path', 'written', 'diagnostics', 'problem')

    def __init__(self, path: str, written: list[str] | None = None,
                 diagnostics: list[Diagnostic] | None = None, problem: str | None = None) -> None:
        self.path = path
        self.written: list[str] = written or []
        self.diagnostics: list[Diagnostic] = diagnostics or []
        #: Why the input could not be read or the output not written (exit status 2).
        self.problem = problem

    @property
    def readable(self) -> bool:
        """False if the input could not be read or the output not written."""
        return self.problem is None

    @property
    def errors(self) -> list[Diagnostic]:
        """Diagnostics of severity error."""
        return [d for d in self.diagnostics if d.severity is Severity.ERROR]

    def __repr__(self) -> str:
        return (f'FileConversion(path={self.path!r}, written={self.written!r}, '
                f'diagnostics={len(self.diagnostics)}, problem={self.problem!r})')


def _reason(exc: OSError) -> str:
    from nodl.files import describe_os_error

    text = describe_os_error(exc)
    return text[:1].lower() + text[1:]


def _sorted(diagnostics: list[Diagnostic]) -> list[Diagnostic]:
    """Per file (in the order files first appear), by position."""
    rank: dict[str, int] = {}
    for d in diagnostics:
        rank.setdefault(d.file, len(rank))
    return sorted(diagnostics, key=lambda d: (rank[d.file], d.line, d.column))


def _gather(path: str) -> tuple[list[Converted], list[Diagnostic]]:
    """Read one input (a legacy file or a package.xml exporting some) and convert it."""
    from pathlib import Path

    tree = load_xml(Path(path), path)
    trees: list[XmlTree] = []
    diagnostics: list[Diagnostic] = []
    if tree.root is not None and tree.root.tag == 'package':
        exports, found = package_exports_from_tree(tree)
        diagnostics.extend(found)
        for export in exports:
            try:
                trees.append(load_xml(Path(export.path), export.path))
            except OSError as exc:
                diagnostics.append(Diagnostic(
                    Severity.ERROR, f"cannot read exported interface file '{export.path}': "
                    f'{_reason(exc)}', (), tree.file, export.line, export.column, code='NODL015'))
    else:
        trees.append(tree)
    converted: list[Converted] = []
    for each in trees:
        doc = legacy_document_from_tree(each)
        diagnostics.extend(doc.diagnostics)
        if has_errors(each.diagnostics):
            continue  # unreadable XML: converting what was read before the error is noise
        for item in convert_legacy(doc):
            converted.append(item)
            diagnostics.extend(item.diagnostics)
    return converted, diagnostics  # sorted once, by the caller


def _convert(path: str, out_dir: str, taken: dict[str, str], force: bool = False,
             inputs: Sequence[str] = ()) -> tuple[list[str], list[Diagnostic]]:
    """Convert one input; write nothing if anything in it is an error.  OSError reading
    propagates; an output that cannot be written or replaced is a :class:`_WriteFailed`
    (checked for every output before any is written)."""
    converted, diagnostics = _gather(path)
    planned: dict[str, Converted] = {}
    for item in converted:
        target = os.path.join(out_dir, item.file_name)
        key = os.path.normcase(os.path.abspath(target))
        other = planned.get(key)
        earlier = taken.get(key)
        if other is not None or earlier is not None:
            origin = (f'{other.source}:{other.node.line}' if other is not None else earlier)
            diagnostics.append(Diagnostic(
                Severity.ERROR, f'{target} would be written twice (also from {origin}); give the '
                'nodes different executables', (), item.source, item.node.line, item.node.column,
                code='NODL814'))
        else:
            planned[key] = item
    if has_errors(diagnostics):
        return [], _sorted(diagnostics)
    from nodl.writing import WriteError, check_replaceable, check_within, marked_text, output_is_input, write_marked

    written: list[str] = []
    texts = {key: render_converted(item) for key, item in planned.items()}
    read = [path, *inputs, *(item.source for item in converted)]  # a package.xml's exports too
    for key, item in planned.items():  # a refusal writes none of this input's files
        target = os.path.join(out_dir, item.file_name)
        refusal = check_within(target, out_dir) or output_is_input(target, read, '-o') or \
            check_replaceable(target, marked_text(target, texts[key]), force=force)
        if refusal is not None:
            raise _WriteFailed(WriteError(refusal), written, _sorted(diagnostics))
    for key, item in planned.items():
        target = os.path.join(out_dir, item.file_name)
        try:
            write_marked(target, texts[key], force=True, make_parents=True,  # checked above
                         within=out_dir)
        except WriteError as exc:
            raise _WriteFailed(exc, written, _sorted(diagnostics)) from None
        taken[key] = f'{item.source}:{item.node.line}'
        written.append(target)
    return written, _sorted(diagnostics)


class _WriteFailed(Exception):
    """Writing an output failed or was refused; carries what had been written before."""

    def __init__(self, error: WriteError, written: list[str],
                 diagnostics: list[Diagnostic]) -> None:
        super().__init__(str(error))
        self.error = error
        self.written = written
        #: The input's diagnostics, then the one saying why the output was not written.
        self.diagnostics = diagnostics + [error.diagnostic]


def convert_file(path: str | os.PathLike[str],
                 out_dir: str | os.PathLike[str]) -> tuple[list[Path], list[Diagnostic]]:
    """Convert a legacy ``.nodl.xml`` (or a package.xml exporting some) into ``out_dir``.

    Writes one ``<executable>.nodl.yaml`` per node, with a header saying what
    it was converted from, and returns the written paths and every
    diagnostic (file:line:column in the legacy files).  If any diagnostic is
    an error, nothing is written.  I/O errors reading ``path`` propagate as
    :class:`OSError`; an output that cannot be written, or would replace a file
    nodl did not write (or one edited since), raises
    :class:`~nodl.writing.WriteError`.
    """
    from pathlib import Path

    try:
        written, diagnostics = _convert(os.fspath(path), os.fspath(out_dir), {})
    except _WriteFailed as failure:  # private: the documented WriteError is what escapes
        raise failure.error from None
    return [Path(p) for p in written], diagnostics


def convert_files(paths: Iterable[str | os.PathLike[str]],
                  out_dir: str | os.PathLike[str], *, force: bool = False,
                  inputs: Sequence[str] = ()) -> list[FileConversion]:
    """Convert several inputs into ``out_dir`` (what ``nodl convert`` does).

    Never raises for bad input: an unreadable input is a
    :class:`FileConversion` with a ``problem``; two nodes that would be
    written to the same file are an error.  Outputs are written as
    :func:`nodl.writing.write_marked` writes them; one that cannot be
    written or replaced (an input: NODL033, this one or one of ``inputs``; a
    file nodl did not write or an edited one, unless ``force``: NODL031,
    NODL032; a failed write: NODL030) gives an empty ``problem`` and that
    diagnostic last.
    """
    out = os.fspath(out_dir)
    taken: dict[str, str] = {}
    results: list[FileConversion] = []
    for raw in paths:
        path = os.fspath(raw)
        try:
            written, diagnostics = _convert(path, out, taken, force, inputs)
        except _WriteFailed as failure:
            results.append(FileConversion(path, failure.written, failure.diagnostics, ''))
            continue
        except OSError as exc:  # reading the input
            results.append(FileConversion(path, problem=_reason(exc)))
            continue
        results.append(FileConversion(path, written, diagnostics))
    return results
