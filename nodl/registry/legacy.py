"""Packages that ship only legacy (XML) NoDL files.

Two ways a legacy package announces its files:

* the ``nodl_desc`` ament resource (spec 001): ``resource_index/nodl_desc/<package>``,
  empty or holding the file's path relative to ``share/<package>``; when empty,
  every ``*.nodl.xml`` in ``share/<package>`` is read;
* its ``package.xml`` (spec 000): ``<export><interface path="..."/></export>``.

Each ``<node>`` becomes a registration named after its executable (or its
name where there is none); showing or checking it converts it to v2 in memory,
and what is said about it points into the XML file.
"""

from __future__ import annotations

import os
from pathlib import Path

from nodl import ament_index
from nodl.composition import compose_report
from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.legacy_xml import interface_files_from_package_xml, parse_legacy_xml
from nodl.legacy import convert_legacy
from nodl.legacy.converted_document import converted_report
from nodl.registry import Registration
from nodl.vocabulary import LEGACY_RESOURCE

__all__ = ['legacy_registrations', 'legacy_files', 'compose_legacy']

LEGACY_KIND = 'legacy node'


def legacy_files(package: str | None, prefixes: list[str]) -> list[tuple[str, str]]:
    """``(package, file)`` for every legacy NoDL file found."""
    found: list[tuple[str, str]] = []
    for name, prefix in ament_index.get_resources(LEGACY_RESOURCE, prefixes).items():
        if package is not None and name != package:
            continue
        share = os.path.join(prefix, 'share', name)
        resource = ament_index.get_resource(LEGACY_RESOURCE, name, [prefix])
        content = resource.content.strip() if resource else ''
        if content:
            found += [(name, os.path.join(share, line.strip()))
                      for line in content.splitlines() if line.strip()]
        elif os.path.isdir(share):
            found += [(name, os.path.join(share, f)) for f in sorted(os.listdir(share))
                      if f.endswith('.nodl.xml')]
    for name, prefix in ament_index.get_resources('packages', prefixes).items():
        if package is not None and name != package:
            continue
        manifest = os.path.join(prefix, 'share', name, 'package.xml')
        try:
            with open(manifest, encoding='utf-8', errors='replace') as f:
                if '<interface' not in f.read():
                    continue
            paths, _ = interface_files_from_package_xml(manifest)
        except OSError:
            continue
        found += [(name, str(p)) for p in paths if (name, str(p)) not in found]
    return found


def legacy_registrations(package: str | None, prefixes: list[str]) -> list[Registration]:
    """Legacy node definitions, one per ``<node>`` of every legacy file."""
    registrations = []
    for name, file in legacy_files(package, prefixes):
        if not os.path.isfile(file):
            continue
        document = parse_legacy_xml(Path(file), file)
        for node in document.nodes:
            key = node.executable or node.name
            if key:
                registrations.append(Registration(name, key, LEGACY_KIND, file))
    return registrations


def _converted(registration: Registration):  # type: ignore[no-untyped-def]
    document = parse_legacy_xml(Path(registration.file), registration.file)
    diagnostics = list(document.diagnostics)
    for converted in convert_legacy(document):
        if (converted.node.executable or converted.node.name) == registration.name:
            return converted, diagnostics + converted.diagnostics
    return None, diagnostics + [Diagnostic(
        Severity.ERROR, f'no node for {registration.name!r} in this legacy file', (),
        registration.file, code='NODL306')]


def compose_legacy(registration: Registration,  # type: ignore[no-untyped-def]
                   client_library: str = 'rclpy'):
    """The legacy node converted to v2 and composed: ``(composed or None, diagnostics)``.

    Every diagnostic, and every entity's location in the composed node, is
    placed in the legacy XML file (``registration.file``), at the element or
    attribute the entry came from (see :mod:`nodl.legacy.converted_document`).
    """
    converted, diagnostics = _converted(registration)
    if converted is None or not converted.ok:
        return None, diagnostics
    composed, more = compose_report(converted_report(converted), client_library=client_library)
    # Warnings about the in-memory v2 document (no descriptions, ...) say nothing the
    # conversion has not said already; only errors matter here.
    return composed, diagnostics + [d for d in more if d.severity is Severity.ERROR]
