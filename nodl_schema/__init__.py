"""``nodl_schema``: the name of the reference implementation's Python package.

The toolkit's own library is :mod:`nodl` (it was called ``nodl_schema`` before). This
package keeps programs written against the toolkit's former paths working for one
release: ``nodl_schema.X`` is :mod:`nodl.X`, with a :class:`DeprecationWarning` saying so.
The reference implementation's own module names are not redirected: they belong to the
reference's API (see README, "The nodl_schema compatibility package").

The package is also the reference implementation's Python API, built on :mod:`nodl`:
the names of its ``__all__`` below, and its modules ``composition``, ``loader``,
``validation``, ``models``, ``ament_resolver``, ``local_resolver`` and ``rewrite``.
One difference: where the reference raises jsonschema's ``ValidationError``, this package
raises :class:`nodl_schema.ValidationError`, a :class:`ValueError` carrying the toolkit's
diagnostics.  The models (and so the loader) need pydantic, ``rewrite_references``
ruamel.yaml: ``pip install 'nodl-toolkit[reference]'``.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import types
import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import nodl
from nodl_schema.ament_resolver import AmentIndexResolver
from nodl_schema.composition import (
    ResolutionError,
    Resolver,
    get_resolvers,
    register_resolver,
    resolver_registered,
    unregister_resolver,
)
from nodl_schema.local_resolver import LocalResolver
from nodl_schema.validation import ValidationError, load_schema, validate

if TYPE_CHECKING:
    from nodl_schema.loader import dump_nodl, load_nodl, load_nodl_with_doc_tree, parse_nodl, resolve_document
    from nodl_schema.rewrite import rewrite_references

#: The reference implementation's ``__all__``, and :class:`ValidationError`.
__all__ = [
    'AmentIndexResolver', 'ResolutionError', 'Resolver', 'dump_nodl', 'load_nodl',
    'load_nodl_with_doc_tree', 'load_schema', 'get_resolvers', 'parse_nodl', 'register_resolver',
    'resolve_document', 'resolver_registered', 'rewrite_references', 'unregister_resolver',
    'validate', 'ValidationError',
]

#: Names of the reference's API defined in a module that needs an optional dependency.
_LAZY = {'dump_nodl': 'loader', 'load_nodl': 'loader', 'load_nodl_with_doc_tree': 'loader',
         'parse_nodl': 'loader', 'resolve_document': 'loader', 'rewrite_references': 'rewrite'}

# The built-in schemes, as in the reference (a later registration shadows them).
register_resolver(AmentIndexResolver())
register_resolver(LocalResolver())

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
    if name in _LAZY:
        value = getattr(importlib.import_module(f'{__name__}.{_LAZY[name]}'), name)
        globals()[name] = value
        return value
    try:
        value = getattr(nodl, name)
    except AttributeError:
        raise AttributeError(f"module 'nodl_schema' has no attribute '{name}'") from None
    _moved(f'nodl_schema.{name}', f'nodl.{name}')
    return value
