"""NoDL's registrations in the ament index, read through :mod:`nodl.ament_index`.

* :mod:`~nodl.registry.registrations`: which definitions are registered where
  (``nodl_nodes``, ``nodl_interfaces``, the reference's ``nodl`` resource; definitions
  folders in force first), the documents they point at, ``nodl://`` look-ups, and the
  run's search path and snapshot;
* :mod:`~nodl.registry.node_info`: what a registration records besides its definition
  (plugin class, node name);
* :mod:`~nodl.registry.legacy`: packages that ship only legacy XML files (``nodl_desc``,
  ``package.xml`` exports).

Consumers ask the registry (or :mod:`nodl.targets`), never the ament reader, for NoDL's
resources.
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = ['Registration']


class Registration(NamedTuple):
    """One registered definition."""

    package: str
    #: The executable (node definitions) or the name (interface definitions).
    name: str
    #: ``node``, ``interface`` or ``legacy node``.
    kind: str
    #: The file the definition is read from (for index entries holding the
    #: document itself, the index entry).
    file: str
    #: Where it was found: ``index``, or ``overlay DIR`` (a definitions folder).
    origin: str = 'index'
