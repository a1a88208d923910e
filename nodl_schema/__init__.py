"""``nodl_schema``: the name of the reference implementation's Python package.

The toolkit's own library is :mod:`nodl` (it was called ``nodl_schema`` before). This
package keeps programs written against the toolkit's former paths working for one
release: ``nodl_schema.X`` is :mod:`nodl.X`, with a :class:`DeprecationWarning` saying so.
The reference implementation's own module names are not redirected: they belong to the
reference's API (see README, "The nodl_schema compatibility package").
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import types
import warnings
from typing import Any, Sequence

import nodl

#: Submodules of the reference implementation's ``nodl_schema``: never redirected to ``nodl``.
REFERENCE_MODULES = frozenset({'ament_resolver', 'composition', 'loader', 'local_resolver',
                               'models', 'rewrite', 'validation', 'schemas'})


def _moved(old: str, new: str) -> None:
    warnings.warn(f'{old} moved to {new}; import {new} (the nodl_schema path goes away in the '
                  'next release)', DeprecationWarning, stacklevel=3)


class _MovedModuleLoader(importlib.abc.Loader):
    """Loads ``nodl_schema.X`` as the already imported :mod:`nodl.X`."""

    def __init__(self, target: str) -> None:
        self.target = target

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        _moved(spec.name, self.target)
        return importlib.import_module(self.target)

    def exec_module(self, module: types.ModuleType) -> None:
        """The module is :mod:`nodl`'s, already executed."""


class _MovedModuleFinder(importlib.abc.MetaPathFinder):
    """Finds ``nodl_schema.X`` (X not a module of this package) as ``nodl.X``."""

    def find_spec(self, fullname: str, path: Sequence[str] | None,
                  target: types.ModuleType | None = None) -> importlib.machinery.ModuleSpec | None:
        prefix = __name__ + '.'
        if not fullname.startswith(prefix):
            return None
        first = fullname[len(prefix):].split('.', 1)[0]
        if first in REFERENCE_MODULES:
            return None
        moved = 'nodl.' + fullname[len(prefix):]
        if importlib.util.find_spec(moved) is None:
            return None
        return importlib.machinery.ModuleSpec(fullname, _MovedModuleLoader(moved))


if not any(isinstance(finder, _MovedModuleFinder) for finder in sys.meta_path):
    sys.meta_path.insert(0, _MovedModuleFinder())


def __getattr__(name: str) -> Any:
    """``nodl_schema.X`` for a name of :mod:`nodl` (deprecated: use ``nodl.X``)."""
    if name.startswith('__'):
        raise AttributeError(name)
    try:
        value = getattr(nodl, name)
    except AttributeError:
        raise AttributeError(f"module 'nodl_schema' has no attribute '{name}'") from None
    _moved(f'nodl_schema.{name}', f'nodl.{name}')
    return value
