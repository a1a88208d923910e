"""Composing a node definition into its whole interface.

``compose`` resolves the node's layers -- its built-in base, each mixin
(through the resolver of the reference's scheme, or in place) and ``main`` --
and merges them.  Problems with a mixin (missing package or name,
unreadable or invalid file, a node definition used as a mixin, a path that
leaves the package) are errors placed at the mixin entry, saying what was
searched; the referenced file's own diagnostics follow with their positions.
"""

from __future__ import annotations

import os

from nodl_schema.composition.bases import DEFAULT_CLIENT_LIBRARY, base_layer, check_client_library
from nodl_schema.composition.layers import MAIN, Layer
from nodl_schema.composition.merge import Declaration, merge_traced
from nodl_schema.composition.resolvers import (
    ResolutionError, ResolveContext, Resolver, load_resolvers, package_root, scheme_of)
from nodl_schema.diagnostics import Diagnostic, Severity, ValidationError
from nodl_schema.frontends.source import Source
from nodl_schema.loading import Report, check_source
from nodl_schema.model import Interface, Node
from nodl_schema.validation.kinds import KIND_REASONS, Kind

__all__ = ['ComposedNode', 'compose', 'compose_report']

#: Composition codes (see :mod:`nodl_schema.codes`).
MIXIN_UNRESOLVED = 'NODL301'
MIXIN_INVALID = 'NODL302'
MIXIN_NOT_INTERFACE = 'NODL303'
NOT_A_NODE = 'NODL305'


class ComposedNode:
    """A node definition with its layers resolved and merged.

    Consumers that need each entity's kind, provider or source location ask
    the resolved node built on it (:func:`nodl_schema.system.resolve_node`).
    """

    def __init__(self, node: Node, file: str, layers: list[Layer], interface: Interface,
                 diagnostics: list[Diagnostic],
                 declarations: dict[tuple[str, str], list[Declaration]] | None = None,
                 client_library: str = DEFAULT_CLIENT_LIBRARY) -> None:
        #: The node definition as written.
        self.node = node
        self.file = file
        #: base, mixins (in order), main.
        self.layers = layers
        #: The merged interface; each entity's ``origin`` names its layer.
        self.interface = interface
        #: Info diagnostics (overrides), warnings and override errors found while composing.
        self.diagnostics = diagnostics
        #: (section or ``parameters``, name) -> every layer's declaration, first layer first.
        self.declarations = declarations if declarations is not None else {}
        #: The client library whose base the node inherits (``rclpy`` or ``rclcpp``).
        self.client_library = client_library

    def layer(self, label: str) -> Layer:
        """The layer called ``label``."""
        for layer in sorted(self.layers, key=lambda l: l.role == 'mixin'):  # base/main first
            if layer.label == label:
                return layer
        raise KeyError(label)


def _context(report: Report) -> ResolveContext:
    file = report.file
    if not os.path.isfile(file):
        return ResolveContext(None, None)
    return ResolveContext(file, package_root(os.path.dirname(os.path.abspath(file))))


def _mixin_layer(reference: str, index: int, report: Report, context: ResolveContext,
                 resolvers: dict[str, Resolver], out: list[Diagnostic]) -> Layer | None:
    path = ('mixins', index)

    def fail(message: str, code: str = MIXIN_UNRESOLVED) -> None:
        out.append(report.place(Diagnostic(Severity.ERROR, message, path, code=code)))

    scheme = scheme_of(reference)
    resolver = resolvers.get(scheme)
    if resolver is None:
        known = ', '.join(f'{s}://' for s in sorted(resolvers) if s != 'file')
        fail(f"cannot resolve mixin '{reference}': no resolver for the scheme '{scheme}' "
             f'(known: {known or "none"}, and paths relative to the node file)')
        return None
    try:
        resolved = resolver.resolve(reference, context)
    except ResolutionError as exc:
        searched = f' (searched: {", ".join(exc.searched)})' if exc.searched else ''
        fail(f"cannot resolve mixin '{reference}': {exc.message}{searched}")
        return None
    except Exception as exc:  # noqa: BLE001 - a resolver plugin with a bug
        fail(f"cannot resolve mixin '{reference}': the {scheme} resolver failed "
             f'({type(exc).__name__}: {exc})')
        return None
    sub = check_source(resolved.text, file=resolved.file)
    if sub.has_errors():
        fail(f"mixin '{reference}' ({resolved.file}) is not a valid interface definition: "
             f'{len(sub.errors)} error(s), listed below', MIXIN_INVALID)
        out.extend(sub.diagnostics)
        return None
    if sub.kind is not Kind.INTERFACE:
        assert sub.kind is not None  # a kind is known once there are no errors
        why = KIND_REASONS[sub.kind] + ('; mixins are single-level' if sub.kind is Kind.NODE else '')
        fail(f"mixin '{reference}' ({resolved.file}) is a {sub.kind} definition, not an interface "
             f'definition: {why}', MIXIN_NOT_INTERFACE)
        return None
    return Layer(reference, sub.model(), sub.place, role='mixin')  # type: ignore[arg-type]


def compose_report(report: Report, resolvers: dict[str, Resolver] | None = None, *,
                   client_library: str = DEFAULT_CLIENT_LIBRARY
                   ) -> tuple[ComposedNode | None, list[Diagnostic]]:
    """Compose a checked node definition; returns the result (None on errors) and all diagnostics.

    The base is the one of ``client_library`` (``rclpy`` or ``rclcpp``; ValueError
    for another).  An override the policy forbids (see
    :mod:`nodl_schema.composition.merge`) is an error diagnostic and gives None.
    """
    check_client_library(client_library)
    if report.has_errors():
        return None, list(report.diagnostics)
    if report.kind is not Kind.NODE:
        return None, [Diagnostic(Severity.ERROR, f'only a node definition can be composed; '
                                 f'{report.file} is a {report.kind} definition', (), report.file, 1, 1,
                                 code=NOT_A_NODE)]
    node: Node = report.model()  # type: ignore[assignment]
    diagnostics = list(report.diagnostics)
    errors: list[Diagnostic] = []
    layers: list[Layer] = []
    if node.base is not None:
        layers.append(base_layer(node.base, client_library))
    if node.mixins:
        context = _context(report)
        available = resolvers if resolvers is not None else load_resolvers()
        for index, mixin in enumerate(node.mixins):
            if isinstance(mixin, str):
                layer = _mixin_layer(mixin, index, report, context, available, errors)
                if layer is not None:
                    layers.append(layer)
            else:
                layers.append(Layer(f'mixins[{index}]', mixin, report.place, ('mixins', index),
                                    role='mixin'))
    layers.append(Layer(MAIN, node.main, report.place, ('main',), role='main'))
    if errors:
        return None, diagnostics + errors
    merged = merge_traced(layers)
    diagnostics += merged.diagnostics
    if any(d.severity is Severity.ERROR for d in merged.diagnostics):
        return None, diagnostics
    return ComposedNode(node, report.file, layers, merged.interface, diagnostics,
                        merged.declarations, client_library), diagnostics


def compose(source: Source, *, file: str | None = None,
            resolvers: dict[str, Resolver] | None = None,
            client_library: str = DEFAULT_CLIENT_LIBRARY) -> ComposedNode:
    """Load a node definition and compose it: base (of ``client_library``), mixins, main.

    Raises :class:`~nodl_schema.diagnostics.ValidationError` with every
    diagnostic if the node or any mixin is invalid or cannot be resolved.
    """
    composed, diagnostics = compose_report(check_source(source, kind=Kind.NODE, file=file), resolvers,
                                           client_library=client_library)
    if composed is None:
        raise ValidationError(diagnostics)
    return composed

