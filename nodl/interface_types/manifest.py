"""A package's ``package.xml``: its name and which packages it depends on, and how.

Format 2 and 3 manifests: ``<depend>`` is a build and a run-time dependency,
``<exec_depend>`` and ``<build_export_depend>`` run-time ones,
``<build_depend>`` a build-time one only.  A manifest with a DTD is refused
(an XML entity could make it huge); conditions (``condition="..."``) are
not evaluated: a dependency counts whatever its condition.
"""

from __future__ import annotations

import os
import re
import xml.etree.ElementTree as ET
from xml.parsers import expat

__all__ = ['Manifest', 'read_manifest', 'RUN_TIME', 'BUILD_TIME']

#: Dependency tags that make a package available when the node runs.
RUN_TIME = frozenset({'depend', 'exec_depend', 'run_depend', 'build_export_depend'})
#: Dependency tags that make a package available only to the build.
BUILD_TIME = frozenset({'build_depend', 'buildtool_depend'})


class Manifest:
    """What a ``package.xml`` says; :attr:`problem` when it could not be read."""

    def __init__(self, file: str, name: str | None = None,
                 depends: dict[str, dict[str, int]] | None = None, problem: str | None = None) -> None:
        #: The manifest's path.
        self.file = file
        #: ``<name>``, or None.
        self.name = name
        #: dependency -> {tag: line of its first such element}.
        self.depends: dict[str, dict[str, int]] = depends or {}
        #: Why the manifest could not be read (missing, malformed), or None.
        self.problem = problem

    def run_time(self, package: str) -> bool:
        """True if ``package`` is a run-time dependency (``depend``, ``exec_depend``...)."""
        return bool(RUN_TIME & set(self.depends.get(package, ())))

    def build_only(self, package: str) -> bool:
        """True if ``package`` is listed, but only as a build-time dependency."""
        tags = set(self.depends.get(package, ()))
        return bool(tags) and not (RUN_TIME & tags)

    def line_of(self, package: str) -> int:
        """The line of the first element naming ``package`` (0 when it is not listed)."""
        lines = self.depends.get(package, {}).values()
        return min(lines) if lines else 0


def read_manifest(folder: str) -> Manifest:
    """Read ``folder/package.xml`` (never raises: a problem is :attr:`Manifest.problem`)."""
    path = os.path.join(folder, 'package.xml')
    try:
        with open(path, 'rb') as handle:
            raw = handle.read(1024 * 1024 + 1)
    except OSError as exc:
        return Manifest(path, problem=f'cannot be read: {exc.strerror or exc}')
    if len(raw) > 1024 * 1024:
        return Manifest(path, problem='is larger than 1 MB')
    if b'<!DOCTYPE' in raw or b'<!ENTITY' in raw:
        return Manifest(path, problem='holds a DTD, which is not read')
    depends: dict[str, dict[str, int]] = {}
    try:
        root = ET.fromstring(raw)
    except ET.ParseError as exc:
        line, column = exc.position
        return Manifest(path, problem=f'is not well-formed XML (line {line}, column {column + 1}: '
                                      f'{expat.ErrorString(exc.code)})')
    if root.tag != 'package':
        return Manifest(path, problem=f'has the root element <{root.tag}>, not <package>')
    name = (root.findtext('name') or '').strip() or None
    # ElementTree keeps no line numbers: find each element's line in the text.
    text = raw.decode('utf-8', 'replace')
    for child in root:
        tag = child.tag if isinstance(child.tag, str) else ''
        if tag in RUN_TIME or tag in BUILD_TIME:
            dependency = (child.text or '').strip()
            if dependency:
                depends.setdefault(dependency, {}).setdefault(tag, _line(text, tag, dependency))
    return Manifest(path, name, depends)


def _line(text: str, tag: str, dependency: str) -> int:
    match = re.search(rf'<{tag}(\s[^>]*)?>\s*{re.escape(dependency)}\s*</{tag}>', text)
    return text.count('\n', 0, match.start()) + 1 if match else 0
