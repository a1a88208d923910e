"""Composing a node definition into its whole interface.

``compose`` resolves the node's layers -- its built-in base, each mixin
(through the resolver of the reference's scheme, or in place) and ``main`` --
and merges them.  Problems with a mixin (missing package or name,
unreadable or invalid file, a node definition used as a mixin, a path that
leaves the package) are errors placed at the mixin entry, saying what was
searched; the referenced file's own diagnostics follow with their positions.
"""

from __future__ import annotations

import copy
import dataclasses
import os
from collections.abc import Callable, Sequence

from nodl.composition.bases import (
    DEFAULT_CLIENT_LIBRARY,
    check_client_library,
    shared_base_layer,
)
from nodl.composition.layers import MAIN, Layer
from nodl.composition.merge import Declaration, merge_traced
from nodl.composition.resolvers import (
    ResolutionError,
    ResolveContext,
    Resolver,
    load_resolvers,
    package_root,
    scheme_of,
)
from nodl.diagnostics import Diagnostic, DocPath, Severity, ValidationError
from nodl.frontends.builtin import INCLUDE
from nodl.frontends.source import Source
from nodl.loading import CheckedSource, check_source
from nodl.model import Interface, Node
from nodl.model.node import Base
from nodl.validation.kinds import KIND_REASONS, Kind

__all__ = ['ComposedNode', 'compose', 'compose_report']

#: Composition codes (see :mod:`nodl.codes`).
MIXIN_UNRESOLVED = 'NODL301'
MIXIN_INVALID = 'NODL302'
MIXIN_NOT_INTERFACE = 'NODL303'
NOT_A_NODE = 'NODL305'
INCLUDE_CYCLE = 'NODL311'


class ComposedNode:
    """A node definition with its layers resolved and merged.

    Consumers that need each entity's kind, provider or source location ask
    the resolved node built on it (:func:`nodl.composition.resolved.resolve_node`).
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

    @property
    def files(self) -> list[str]:
        """Every file the composition read: the node definition, then each mixin's (nested
        includes too), each once."""
        found = [self.file] + [layer.file for layer in self.layers if layer.file is not None]
        return list(dict.fromkeys(f for f in found if f and not f.startswith('<')))  # <string>: no file

    def layer(self, label: str) -> Layer:
        """The layer called ``label``."""
        for layer in sorted(self.layers, key=lambda each: each.role == 'mixin'):  # base/main first
            if layer.label == label:
                return layer
        raise KeyError(label)


def _context(file: str, prefixes: tuple[str, ...] | None) -> ResolveContext:
    """What the resolvers know of the document ``file`` refers from."""
    if not os.path.isfile(file):
        return ResolveContext(None, None, prefixes)
    return ResolveContext(file, package_root(os.path.dirname(os.path.abspath(file))), prefixes)


class _IncludeTree:
    """What one composition has seen while following mixins, nested ones included.

    The reference implementation's include dialect nests: a document it
    includes may include others (``local://`` relative to itself), to any
    depth; a cycle, or a document included twice, is an error.  Each
    included document becomes mixin layers in place of its entry: what it
    includes first, then its own flat interface.
    """

    def __init__(self, resolvers: dict[str, Resolver], out: list[Diagnostic],
                 root_file: str | None, root_is_include: bool,
                 prefixes: tuple[str, ...] | None = None) -> None:
        self.resolvers = resolvers
        #: The ament prefixes every document of the tree resolves ``nodl://`` in.
        self.prefixes = prefixes
        self.out = out
        self.root_keys: tuple[str, ...] = (os.path.realpath(root_file),) if root_file else ()
        self.root_is_include = root_is_include
        #: Real path of each document reached -> (its chain of references, reached through an include?).
        self.seen: dict[str, tuple[str, bool]] = {}
        #: Base descriptions included by nested documents: (base, chain).
        self.bases: list[tuple[str, str]] = []


def _mixin_layers(reference: str, path: DocPath, place: Callable[[Diagnostic], Diagnostic],
                  context: ResolveContext, tree: _IncludeTree, chain: tuple[str, ...] = (),
                  keys: tuple[str, ...] = (),
                  related: tuple[tuple[str, int, int, str], ...] = ()) -> list[Layer] | None:
    """The layers of one mixin entry (several when it is an include-dialect document), or None.

    ``path`` is the entry in the document ``place`` places diagnostics in;
    ``chain`` the references that led there (empty for the node's own mixins).
    """
    def fail(message: str, code: str = MIXIN_UNRESOLVED) -> None:
        tree.out.append(place(Diagnostic(Severity.ERROR, message, path, code=code, related=related)))

    scheme = scheme_of(reference)
    resolver = tree.resolvers.get(scheme)
    if resolver is None:
        known = ', '.join(f'{s}://' for s in sorted(tree.resolvers) if s != 'file')
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
    label = ' > '.join(chain + (reference,))
    key = os.path.realpath(resolved.file) if os.path.isfile(resolved.file) else resolved.file
    if key in tree.root_keys + keys:
        fail(f"mixin '{reference}' ({resolved.file}) includes itself: {label} leads back to it; "
             'remove the include that closes the cycle', INCLUDE_CYCLE)
        return None
    nested = bool(chain) or tree.root_is_include
    if key in tree.seen and (nested or tree.seen[key][1]):
        fail(f"mixin '{reference}' ({resolved.file}) is included twice: {label} and "
             f'{tree.seen[key][0]}; include it once', INCLUDE_CYCLE)
        return None
    tree.seen.setdefault(key, (label, nested))
    sub = check_source(resolved.text, file=resolved.file)
    if sub.has_errors():
        fail(f"mixin '{reference}' ({resolved.file}) is not a valid interface definition: "
             f'{len(sub.errors)} error(s), listed below', MIXIN_INVALID)
        tree.out.extend(sub.diagnostics)
        return None
    if sub.kind is Kind.NODE and sub.dialect == INCLUDE:
        return _included_layers(sub, label, resolved.file, tree, chain + (reference,), keys + (key,),
                                related or _related_entry(place, path, reference))
    if sub.kind is not Kind.INTERFACE:
        assert sub.kind is not None  # a kind is known once there are no errors
        why = KIND_REASONS[sub.kind] + ('; mixins are single-level (only documents in the include '
                                        'dialect include others)' if sub.kind is Kind.NODE else '')
        fail(f"mixin '{reference}' ({resolved.file}) is a {sub.kind} definition, not an interface "
             f'definition: {why}', MIXIN_NOT_INTERFACE)
        return None
    return [Layer(label, sub.model(), sub.place, role='mixin',  # type: ignore[arg-type]
                  file=resolved.file)]


def _related_entry(place: Callable[[Diagnostic], Diagnostic], path: DocPath,
                   reference: str) -> tuple[tuple[str, int, int, str], ...]:
    """Where the node includes ``reference`` (named in errors about what that document includes)."""
    entry = place(Diagnostic(Severity.INFO, '', path))
    return ((entry.file, entry.line, entry.column, f"included through '{reference}' here"),)


def _included_layers(sub: CheckedSource, label: str, file: str, tree: _IncludeTree, chain: tuple[str, ...],
                     keys: tuple[str, ...], related: tuple[tuple[str, int, int, str], ...]
                     ) -> list[Layer] | None:
    """The layers of an included include-dialect document: what it includes, then itself."""
    included: Node = sub.model()  # type: ignore[assignment]
    if included.base is not None:
        tree.bases.append((included.base.value, label))
    context = _context(file, tree.prefixes)
    layers: list[Layer] = []
    complete = True
    for index, mixin in enumerate(included.mixins or []):
        assert isinstance(mixin, str)  # the include dialect has references only
        found = _mixin_layers(mixin, ('mixins', index), sub.place, context, tree, chain, keys, related)
        if found is None:
            complete = False
        else:
            layers += found
    if not complete:
        return None
    layers.append(Layer(label, included.main, sub.place, ('main',), role='mixin', file=file))
    return layers


def compose_report(report: CheckedSource, resolvers: dict[str, Resolver] | None = None, *,
                   client_library: str = DEFAULT_CLIENT_LIBRARY,
                   prefixes: Sequence[str] | None = None
                   ) -> tuple[ComposedNode | None, list[Diagnostic]]:
    """Compose a checked node definition; returns the result (None on errors) and all diagnostics.

    The base is the one of ``client_library`` (``rclpy`` or ``rclcpp``; ValueError
    for another).  ``prefixes``: the ament prefixes ``nodl://`` mixins (nested ones
    included) are looked up in (default: ``AMENT_PREFIX_PATH``).  An override the policy forbids (see
    :mod:`nodl.composition.merge`) is an error diagnostic and gives None.
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
    tree: _IncludeTree | None = None
    if node.mixins:
        searched = tuple(prefixes) if prefixes is not None else None
        context = _context(report.file, searched)
        available = resolvers if resolvers is not None else load_resolvers()
        tree = _IncludeTree(available, errors, context.node_file, report.dialect == INCLUDE, searched)
        for index, mixin in enumerate(node.mixins):
            if isinstance(mixin, str):
                found = _mixin_layers(mixin, ('mixins', index), report.place, context, tree)
                layers += found or []
            else:
                layers.append(Layer(f'mixins[{index}]', mixin, report.place, ('mixins', index),
                                    role='mixin', file=report.file))
    if tree is not None and tree.bases:
        # A base description included by an included document is the node's base too
        # (lifecycle_node's includes node's: the larger one wins, as for the node's own includes).
        bases = [b for b, _ in tree.bases] + ([node.base.value] if node.base is not None else [])
        strongest = 'lifecycle_node' if 'lifecycle_node' in bases else 'node'
        if node.base is None or node.base.value != strongest:
            node = dataclasses.replace(node, base=Base(strongest))
    if node.base is not None:
        layers.insert(0, shared_base_layer(node.base, client_library))
    layers.append(Layer(MAIN, node.main, report.place, ('main',), role='main', file=report.file))
    if errors:
        return None, diagnostics + errors
    merged = merge_traced(layers)
    diagnostics += merged.diagnostics
    if any(d.severity is Severity.ERROR for d in merged.diagnostics):
        return None, diagnostics
    if node.codegen is not None:  # the node's code generator settings, as written (not merged)
        merged.interface.codegen = copy.deepcopy(node.codegen)
    return ComposedNode(node, report.file, layers, merged.interface, diagnostics,
                        merged.declarations, client_library), diagnostics


def compose(source: Source, *, file: str | None = None,
            resolvers: dict[str, Resolver] | None = None,
            client_library: str = DEFAULT_CLIENT_LIBRARY,
            prefixes: Sequence[str] | None = None) -> ComposedNode:
    """Load a node definition and compose it: base (of ``client_library``), mixins, main
    (``nodl://`` mixins looked up in ``prefixes``, default ``AMENT_PREFIX_PATH``).

    Raises :class:`~nodl.diagnostics.ValidationError` with every
    diagnostic if the node or any mixin is invalid or cannot be resolved.
    """
    composed, diagnostics = compose_report(check_source(source, kind=Kind.NODE, file=file), resolvers,
                                           client_library=client_library, prefixes=prefixes)
    if composed is None:
        raise ValidationError(diagnostics)
    return composed

