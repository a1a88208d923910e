"""The built-in bases ``node`` and ``lifecycle_node``, shipped as interface definitions."""

from __future__ import annotations

import os
from functools import lru_cache

from nodl_schema.composition.layers import Layer
from nodl_schema.model import Base

__all__ = ['BASES_DIR', 'base_file', 'base_layer']

BASES_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'bases')


def base_file(base: Base | str) -> str:
    """The file that defines a built-in base."""
    return os.path.join(BASES_DIR, f'{Base(base).value}.nodl.yaml')


@lru_cache(maxsize=None)
def _report(name: str):  # type: ignore[no-untyped-def]
    from nodl_schema.loading import check_source
    from nodl_schema.validation.kinds import Kind

    with open(base_file(name), 'rb') as f:
        report = check_source(f.read(), kind=Kind.INTERFACE, file=base_file(name))
    if report.has_errors():  # a broken installation, not a user error
        raise RuntimeError(f'built-in base {name} is invalid: {report.errors}')
    return report


def base_layer(base: Base | str) -> Layer:
    """The layer a node inherits from ``base``."""
    name = Base(base).value
    report = _report(name)
    return Layer(f'base:{name}', report.model(), report.place, role='base')
