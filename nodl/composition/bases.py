"""The built-in bases ``node`` and ``lifecycle_node``, per client library.

A base is assembled from interface definitions shipped under ``bases/``, so
that no entity is written twice:

* ``node.nodl.yaml``: what every client library gives a node (rcl, the
  parameter services); for rclpy that is the whole ``node`` base;
* ``lifecycle_node.nodl.yaml``: what a lifecycle node adds (rcl_lifecycle);
* ``<library>/node.nodl.yaml``: what a client library adds to every node
  (rclcpp: the time source's ``/parameter_events`` subscription).

The rclpy bases are checked against real rclpy nodes by the tests; the
rclcpp additions are derived from rclcpp's documented behaviour (their
description says so), as rclcpp cannot run here.
"""

from __future__ import annotations

import os
from functools import cache
from typing import Any

from nodl import ament_index
from nodl.composition.layers import Layer
from nodl.diagnostics import Diagnostic, DocPath
from nodl.loading import check_source
from nodl.model import ENDPOINT_SECTIONS, Base, Interface
from nodl.validation.kinds import Kind
from nodl.vocabulary import CLIENT_LIBRARIES

__all__ = ['BASES_DIR', 'CLIENT_LIBRARIES', 'DEFAULT_CLIENT_LIBRARY', 'base_file', 'base_files',
           'base_layer', 'shared_base_layer', 'check_client_library']

BASES_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'bases')

#: The default client library (the one the bases are verified against).
DEFAULT_CLIENT_LIBRARY = CLIENT_LIBRARIES[0]

#: base -> the shared parts it is made of, in order (file stems under ``bases/``).
_SHARED_PARTS = {Base.NODE: ('node',), Base.LIFECYCLE_NODE: ('node', 'lifecycle_node')}
#: client library -> what it adds to every base (file stems under ``bases/``).
_LIBRARY_PARTS: dict[str, tuple[str, ...]] = {'rclpy': (), 'rclcpp': ('rclcpp/node',)}


def check_client_library(client_library: str) -> str:
    """``client_library`` if it is known; ValueError saying what is expected otherwise."""
    if client_library not in CLIENT_LIBRARIES:
        raise ValueError(f'unknown client library {client_library!r}; expected one of: '
                         f'{", ".join(CLIENT_LIBRARIES)}')
    return client_library


def _path(stem: str) -> str:
    return os.path.join(BASES_DIR, *stem.split('/')) + '.nodl.yaml'


def base_file(base: Base | str) -> str:
    """The file holding what ``base`` itself declares (``lifecycle_node``: its additions only)."""
    return _path(Base(base).value)


def base_files(base: Base | str, client_library: str = DEFAULT_CLIENT_LIBRARY) -> list[str]:
    """Every file a base is assembled from for ``client_library``, in merge order."""
    parts = _SHARED_PARTS[Base(base)] + _LIBRARY_PARTS[check_client_library(client_library)]
    return [_path(stem) for stem in parts]


@cache
def _report(path: str):  # type: ignore[no-untyped-def]
    with open(path, 'rb') as f:
        report = check_source(f.read(), kind=Kind.INTERFACE, file=path)
    if report.has_errors():  # a broken installation, not a user error
        raise RuntimeError(f'built-in base file {path} is invalid: {report.errors}')
    return report


class _Assembled:
    """Places a diagnostic about the assembled base in the part file that declares the entity."""

    def __init__(self) -> None:
        #: (section or 'parameters', index or name in the assembled base) -> (report, path in its file)
        self.origins: dict[tuple[Any, Any], tuple[Any, DocPath]] = {}
        self.first: Any = None

    def __call__(self, diagnostic: Diagnostic) -> Diagnostic:
        path = diagnostic.path
        found = self.origins.get((path[0], path[1])) if len(path) >= 2 else None
        if found is None:
            placed: Diagnostic = self.first.place(diagnostic)
            return placed
        report, own = found
        placed = report.place(diagnostic.replace(path=own + tuple(path[2:])))
        return placed


@cache
def _assemble(base: Base, client_library: str) -> tuple[dict[str, Any], _Assembled]:
    """The assembled base as the mapping a file holds (a fresh model is made from it per
    layer: cheaper than a deep copy), and where each of its entities is written."""
    placer = _Assembled()
    result = Interface(nodl_version=2)
    descriptions = []
    for path in base_files(base, client_library):
        report = _report(path)
        placer.first = placer.first or report
        part: Interface = report.model()
        if part.description:
            descriptions.append(part.description)
        for name, param in (part.parameters or {}).items():
            if result.parameters is None:
                result.parameters = {}
            result.parameters[name] = param
            placer.origins[('parameters', name)] = (report, ('parameters', name))
        for section in ENDPOINT_SECTIONS:
            entries = getattr(part, section)
            if not entries:
                continue
            merged = getattr(result, section)
            if merged is None:
                merged = []
                setattr(result, section, merged)
            for index, entity in enumerate(entries):
                placer.origins[(section, len(merged))] = (report, (section, index))
                merged.append(entity)
    result.description = ' '.join(descriptions) or None
    return result.to_dict(), placer


def base_layer(base: Base | str, client_library: str = DEFAULT_CLIENT_LIBRARY) -> Layer:
    """The layer a node inherits from ``base`` when it is written with ``client_library``.

    Its label is ``base:<base>`` whatever the library; diagnostics about an
    entity of the base are placed in the part file that declares it.
    """
    name = Base(base)
    data, placer = _assemble(name, check_client_library(client_library))
    # A fresh model each time: callers may stamp or edit what they get, the cache stays as shipped.
    return Layer(f'base:{name.value}', Interface.from_dict(data), placer, role='base')


def shared_base_layer(base: Base | str, client_library: str = DEFAULT_CLIENT_LIBRARY) -> Layer:
    """:func:`base_layer`, one for a whole run inside :func:`nodl.ament_index.snapshot`
    (an analysis of a launched system: every node of that base then shares one layer, and
    the merged copies and resolved entities derived from it, see :attr:`Layer.shared`); a
    fresh layer outside one.  Composition reads a base layer and never edits it."""
    name, library = Base(base), check_client_library(client_library)

    def make() -> Layer:
        layer = base_layer(name, library)
        layer.shared = {}
        return layer

    return ament_index.remembered(('base layer', name, library), make) if ament_index.in_snapshot() \
        else base_layer(name, library)
