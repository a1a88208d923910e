"""Which client library's base a node inherits, and why.

Asked for explicitly (``--client-library``), that library.  For a node
registered by a package, the package's build type says it: ``ament_python``
packages hold rclpy nodes, ``ament_cmake`` packages rclcpp nodes (read from
``<export><build_type>`` of the installed ``package.xml``).  Otherwise rclpy,
the library the bases are verified against.
"""

from __future__ import annotations

import os
from typing import NamedTuple

from nodl import ament_index
from nodl.composition.bases import DEFAULT_CLIENT_LIBRARY, check_client_library
from nodl.vocabulary import BUILD_TYPE_LIBRARIES

__all__ = ['ClientLibraryChoice', 'BUILD_TYPE_LIBRARIES', 'choose_client_library',
           'package_build_type']



class ClientLibraryChoice(NamedTuple):
    """A client library and the reason it was chosen (for the output)."""

    name: str
    reason: str

    def __str__(self) -> str:
        return f'{self.name} ({self.reason})'


def package_build_type(package: str, prefixes: list[str] | None = None) -> str | None:
    """The ``<export><build_type>`` of an installed package's package.xml (None if unknown).

    Read once per package within an :func:`nodl.ament_index.snapshot`.
    """
    key = ('build_type', package, tuple(prefixes) if prefixes is not None else None)
    return ament_index.remembered(key, lambda: _read_build_type(package, prefixes))


def _read_build_type(package: str, prefixes: list[str] | None) -> str | None:
    prefix = ament_index.package_prefix(package, prefixes)
    if prefix is None:
        return None
    manifest = os.path.join(prefix, 'share', package, 'package.xml')
    if not os.access(manifest, os.F_OK):
        return None  # asked first: a failed open raises, which costs more than asking
    try:
        import xml.etree.ElementTree as ElementTree

        root = ElementTree.parse(manifest).getroot()
    except (OSError, ElementTree.ParseError):
        return None
    build_type = root.find('export/build_type')
    if build_type is None or not (build_type.text or '').strip():
        return None
    return (build_type.text or '').strip()


def choose_client_library(requested: str | None = None, package: str | None = None,
                          prefixes: list[str] | None = None) -> ClientLibraryChoice:
    """The client library to use: ``requested``, else from ``package``'s build type, else rclpy.

    ValueError for an unknown ``requested`` library.
    """
    if requested is not None:
        return ClientLibraryChoice(check_client_library(requested), 'as requested')
    if package is not None:
        build_type = package_build_type(package, prefixes)
        library = BUILD_TYPE_LIBRARIES.get(build_type or '')
        if library is not None:
            return ClientLibraryChoice(library, f"package '{package}' is built with {build_type}")
        why = f'build type {build_type}' if build_type else 'no build type'
        return ClientLibraryChoice(DEFAULT_CLIENT_LIBRARY, f"package '{package}' has {why}; "
                                   f'{DEFAULT_CLIENT_LIBRARY} by default')
    return ClientLibraryChoice(DEFAULT_CLIENT_LIBRARY, 'the default; choose with --client-library')
