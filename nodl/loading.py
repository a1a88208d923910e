"""The public load/validate/dump API.

``load_nodl`` detects the kind of a document; ``load_parameter``,
``load_interface`` and ``load_node`` enforce one.  All of them accept YAML
or JSON as text, bytes, a file object or a :class:`pathlib.Path`, and raise
:class:`~nodl.diagnostics.ValidationError` once, with every
diagnostic, for an invalid document.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, Severity, ValidationError, has_errors
from nodl.frontends.frontend import Placer, read_document
from nodl.frontends.source import Source, read_source
from nodl.validation import Kind, detect_kind, validate_data
from nodl.validation.kinds import KIND_REASONS
from nodl.wording import article, kind_of

__all__ = [
    'Document',
    'CheckedSource',
    'check_source',
    'dump_nodl',
    'load_interface',
    'load_node',
    'load_nodl',
    'load_parameter',
    'model_from_data',
    'validate_interface',
    'validate_node',
    'validate_parameter',
]

if TYPE_CHECKING:
    from nodl.model import Interface, Node, ParameterDefinition

#: Any loaded NoDL document.
if TYPE_CHECKING:
    Document = Interface | Node | ParameterDefinition
else:
    Document = object


def _model_class(kind: Kind) -> Any:
    # The model is imported on first use: `nodl validate` never needs it.
    from nodl import model

    return {Kind.PARAMETER: model.ParameterDefinition, Kind.INTERFACE: model.Interface,
            Kind.NODE: model.Node}[kind]



class CheckedSource:
    """The outcome of checking one document: its kind, data and diagnostics."""

    def __init__(self, file: str, kind: Kind | None, data: Any,
                 raw: list[Diagnostic] | None = None, parsed: Placer | None = None) -> None:
        self.file = file
        self.kind = kind
        self.data = data
        self._raw: list[Diagnostic] = raw or []
        self._parsed = parsed
        self._placed: list[Diagnostic] | None = None
        #: The dialect the document was written in (``include``, ``genparamlib``), None for NoDL v2.
        self.dialect: str | None = None

    @property
    def diagnostics(self) -> list[Diagnostic]:
        """Every diagnostic, placed at ``file:line:column`` and in source order."""
        if self._placed is None:
            placed = [self.place(d) for d in self._raw]
            placed.sort(key=lambda d: (d.line, d.column))
            self._placed = placed
        return self._placed

    def place(self, diagnostic: Diagnostic) -> Diagnostic:
        """Place a diagnostic about this document (given by path) at file:line:column."""
        if self._parsed is not None:
            return self._parsed.place(diagnostic)
        return diagnostic.at(self.file, diagnostic.line, diagnostic.column)

    @property
    def errors(self) -> list[Diagnostic]:
        """Diagnostics of severity error."""
        return [d for d in self.diagnostics if d.severity is Severity.ERROR]

    @property
    def warnings(self) -> list[Diagnostic]:
        """Diagnostics of severity warning."""
        return [d for d in self.diagnostics if d.severity is Severity.WARNING]

    def has_errors(self, strict: bool = False) -> bool:
        """True if the document is invalid (with ``strict``, warnings count too)."""
        return has_errors(self._raw, strict)

    def model(self) -> Document:
        """The typed document (only for a report without errors)."""
        if self.kind is None or self.has_errors():
            raise ValidationError(self.diagnostics)
        document: Document = _model_class(self.kind).from_dict(self.data)
        return document


def check_source(source: Source, *, kind: Kind | str | None = None,
                 file: str | None = None, installed: bool = False) -> CheckedSource:
    """Read, parse and validate one document; never raises for bad content.

    ``kind`` enforces a kind of document (default: detect it).  ``file``
    names the document in diagnostics (default: the path, or ``<string>``).
    ``installed``: the document is one the reference implementation's
    ``ament_nodl_register`` installed (ament resource type ``nodl``), read as
    a node definition even without ``include`` (see
    :class:`nodl.frontends.builtin.IncludeFrontend`).
    I/O errors such as a missing file propagate as :class:`OSError`.
    """
    wanted = Kind(kind) if kind is not None else None
    text, problem = read_source(source, file)
    if text is None:
        assert problem is not None
        return CheckedSource(problem.file, None, None, [problem])
    # The frontends (nodl.frontends) read the text: YAML or JSON, a dialect read as NoDL v2
    # (its diagnostics land on the original text), or something that is not NoDL (XML, a
    # generate_parameter_library file), said to be what it is.
    reading = read_document(text, installed=installed)
    parsed, early = reading.document, reading.diagnostics
    if reading.data is None:
        report = CheckedSource(text.file, None, reading.raw, early, parsed)
        report.dialect = reading.dialect
        return report
    detected = detect_kind(reading.data)
    if wanted is not None and wanted is not detected:
        mismatch = Diagnostic(
            Severity.ERROR, f'expected {article(wanted)} definition, but this is '
            f'{article(detected)} definition ({KIND_REASONS[detected]})', (), text.file, 1, 1,
            code='NODL108')
        return CheckedSource(text.file, wanted, reading.data, early + [mismatch], parsed)
    diagnostics = early + validate_data(reading.data, detected)
    if diagnostics and text.text.startswith('#'):
        # A leading '# nodl: ignore=CODE' comment silences warnings of those codes for this
        # file (what describe and convert write for the descriptions they cannot know).
        from nodl.overrides import apply_directives

        diagnostics = apply_directives(text.text, diagnostics)
    report = CheckedSource(text.file, detected, reading.data, diagnostics, parsed)
    report.dialect = reading.dialect
    return report


_PATH_SUFFIXES = ('.yaml', '.yml', '.json', '.xml')


def _looks_like_a_path(source: Source) -> bool:
    """A one-line str that names a file (a str is read as document text, never as a path)."""
    if not isinstance(source, str):
        return False
    text = source.strip()
    if not text or '\n' in text or ': ' in text or text.startswith(('{', '[')):
        return False
    import os

    return text.lower().endswith(_PATH_SUFFIXES) or os.path.isfile(text)


def _load(source: Source, kind: Kind | None, strict: bool, file: str | None) -> Document:
    report = check_source(source, kind=kind, file=file)
    if report.has_errors(strict):
        if _looks_like_a_path(source):
            text = str(source).strip()
            raise ValidationError([Diagnostic(
                Severity.ERROR, f'{text!r} was given as a str, which is read as the document '
                f'text itself; to load the file, pass a path: pathlib.Path({text!r})', (),
                file or '<string>', 1, 1, code='NODL011')])
        raise ValidationError(report.diagnostics)
    return report.model()


def load_nodl(source: Source, *, strict: bool = False, file: str | None = None) -> Document:
    """Load any NoDL document, detecting whether it is a parameter, interface or node definition.

    With ``strict``, warnings make the document invalid too.
    """
    return _load(source, None, strict, file)


def load_parameter(source: Source, *, strict: bool = False,
                   file: str | None = None) -> ParameterDefinition:
    """Load a parameter definition (any other kind is an error)."""
    return _load(source, Kind.PARAMETER, strict, file)  # type: ignore[return-value]


def load_interface(source: Source, *, strict: bool = False, file: str | None = None) -> Interface:
    """Load an interface definition (any other kind is an error)."""
    return _load(source, Kind.INTERFACE, strict, file)  # type: ignore[return-value]


def load_node(source: Source, *, strict: bool = False, file: str | None = None) -> Node:
    """Load a node definition (any other kind is an error)."""
    return _load(source, Kind.NODE, strict, file)  # type: ignore[return-value]


def _validate(data: Any, kind: Kind) -> list[Diagnostic]:
    if not isinstance(data, dict):
        raise ValidationError([Diagnostic(
            Severity.ERROR, f'{article(kind)} definition is a mapping, not {kind_of(data)}',
            (), '<dict>', code='NODL011')])
    diagnostics = [d.at('<dict>', 0, 0) for d in validate_data(data, kind)]
    if has_errors(diagnostics):
        raise ValidationError(diagnostics)
    return diagnostics


def validate_parameter(data: dict[str, Any]) -> list[Diagnostic]:
    """Validate a plain dict as a parameter definition; returns the warnings."""
    return _validate(data, Kind.PARAMETER)


def validate_interface(data: dict[str, Any]) -> list[Diagnostic]:
    """Validate a plain dict as an interface definition; returns the warnings."""
    return _validate(data, Kind.INTERFACE)


def validate_node(data: dict[str, Any]) -> list[Diagnostic]:
    """Validate a plain dict as a node definition; returns the warnings."""
    return _validate(data, Kind.NODE)


def model_from_data(data: dict[str, Any]) -> Document:
    """Validate a plain dict of any kind and return its typed model."""
    kind = detect_kind(data)
    _validate(data, kind)
    document: Document = _model_class(kind).from_dict(data)
    return document


def dump_nodl(doc: Document | dict[str, Any], format: str = 'yaml', *,
              validate: bool = True) -> str:
    """Serialize a document (model or plain dict) as ``yaml`` or ``json`` text.

    The document is validated first: one with errors is refused with
    :class:`ValidationError` (what is written always loads again).
    ``validate=False`` skips that, for callers that report the errors of
    the text themselves.
    """
    if format not in ('yaml', 'json'):
        raise ValueError(f"unsupported format {format!r}; expected 'yaml' or 'json'")
    data = doc if isinstance(doc, dict) else doc.to_dict()
    if validate:
        _validate(data, detect_kind(data))
    if format == 'json':
        import json

        from nodl.text_safety import json_escapes

        return json_escapes(json.dumps(data, indent=2, ensure_ascii=False)) + '\n'
    if format == 'yaml':
        from nodl.text_safety import dump_yaml

        return dump_yaml(data)
    raise ValueError(f"unsupported format {format!r}; expected 'yaml' or 'json'")
