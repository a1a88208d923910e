"""Which parameters a definition exports to other formats, and under what default name.

``nodl export genparamlib DEF`` writes the parameters a node's own code
declares: those of ``main`` (the base's are declared by the client library,
mixins' by other code), or with ``with_mixins`` the mixins' too.  An
interface definition exports all its parameters.
"""

from __future__ import annotations

import os
import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from nodl.model import ParameterDefinition

from nodl.diagnostics import Diagnostic, Severity

__all__ = ['ExportSource', 'default_name', 'parameters_of_file', 'parameters_of_registered']

_SUFFIX = re.compile(r'(\.nodl)?\.(ya?ml|json)$')


class ExportSource:
    """The parameters to export (None on errors), the diagnostics, and a default name."""

    def __init__(self, parameters: dict[str, ParameterDefinition] | None,
                 diagnostics: list[Diagnostic], name: str, source: str,
                 files: list[str] | None = None) -> None:
        self.parameters = parameters
        self.diagnostics = diagnostics
        #: A name for the exported document (the file's stem, or the executable).
        self.name = name
        #: Where the definition was read from.
        self.source = source
        #: Every file read: the definition, then its mixins (an export must overwrite none).
        self.files: list[str] = files if files is not None else [source]


def default_name(path: str) -> str:
    """``my_node`` for ``nodl/my_node.nodl.yaml``."""
    return _SUFFIX.sub('', os.path.basename(path))


def _from_composed(composed, with_mixins: bool) -> dict[str, ParameterDefinition]:  # type: ignore[no-untyped-def]
    parameters: dict[str, ParameterDefinition] = {}
    for layer in composed.layers:
        if layer.role == 'base' or (layer.role == 'mixin' and not with_mixins):
            continue
        parameters.update(layer.interface.parameters or {})
    return parameters


def parameters_of_file(path: str, with_mixins: bool = False) -> ExportSource:
    """The exported parameters of the node or interface definition in ``path`` (OSError propagates)."""
    from pathlib import Path

    from nodl.loading import check_source
    from nodl.validation.kinds import Kind

    report = check_source(Path(path), file=path)
    name = default_name(path)
    if report.has_errors():
        return ExportSource(None, report.diagnostics, name, path)
    if report.kind is Kind.NODE:
        from nodl.composition import compose_report

        composed, diagnostics = compose_report(report)
        if composed is None:
            return ExportSource(None, diagnostics, name, path)
        return ExportSource(_from_composed(composed, with_mixins), diagnostics, name, path,
                            [path, *composed.files])
    if report.kind is Kind.INTERFACE:
        model = report.model()
        return ExportSource(dict(model.parameters or {}), report.diagnostics, name, path)  # type: ignore[union-attr]
    return ExportSource(None, [Diagnostic(
        Severity.ERROR, 'a parameter definition has no parameter name; export a node or interface '
        'definition', (), path, 1, 1)], name, path)


def parameters_of_registered(package: str, executable: str, with_mixins: bool = False) -> ExportSource:
    """The exported parameters of the node definition of ``package``'s ``executable`` (looked
    up in the definitions folders in force, then the ament index)."""
    from nodl.targets.resolve import resolve_target

    found = resolve_target([package, executable])
    if found.node is None:
        return ExportSource(None, found.diagnostics, executable, found.source)
    return ExportSource(_from_composed(found.node.composed, with_mixins), found.diagnostics,
                        executable, found.source, [found.source, *found.node.files])
