"""Targets: every way to name a definition, resolved once, with its provenance.

* :mod:`~nodl.registry.overlay`: definitions folders (overlays) laid out by
  package, their layout checked, and the folders in force for a run;
* :mod:`~nodl.targets.resolve`: ``FILE``, ``PACKAGE EXECUTABLE`` and
  ``nodl://PACKAGE/NAME`` -> a definition, looked up in the definitions folders
  (``--definitions`` > ``NODL_PATH`` > ``nodl.toml``) before the ament index, with
  where it came from (index, overlay, extracted, described);
* :mod:`~nodl.targets.placement`: definitions placed as nodes by name
  (``nodl policy`` and ``nodl analyse DEFINITION...``).

Names are imported lazily, like the package's other ``__init__`` modules: the index
imports :mod:`~nodl.registry.overlay` alone.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

_EXPORTS = {
    'Definitions': 'overlay', 'DefinitionFolder': 'overlay', 'read_folder': 'overlay',
    'Provenance': 'resolve', 'Target': 'resolve', 'gather_definitions': 'resolve',
    'resolve_target': 'resolve', 'provenance_of': 'resolve',
    'Definition': 'placement', 'instances_from_definitions': 'placement',
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    value = getattr(importlib.import_module(f'{__name__}.{module}'), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
