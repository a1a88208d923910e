"""Targets: every way to name a definition, resolved once, with its provenance.

* the definitions folders (overlays) it looks in first are the registry's
  (:mod:`nodl.registry.overlay`);
* :mod:`~nodl.targets.resolve`: ``FILE``, ``PACKAGE EXECUTABLE`` and
  ``nodl://PACKAGE/NAME`` -> a definition, looked up in the definitions folders
  (``--definitions`` > ``NODL_PATH`` > ``nodl.toml``) before the ament index, with
  where it came from (index, overlay, extracted, described);
* :mod:`~nodl.targets.drafts`: what an extracted draft still leaves open (``# GAP``);
* :mod:`~nodl.targets.placement`: definitions placed as nodes by name
  (``nodl policy`` and ``nodl analyse DEFINITION...``).
"""

from __future__ import annotations

from nodl.targets.placement import Definition, instances_from_definitions
from nodl.targets.resolve import (
           Provenance,
           ResolvedTarget,
           gather_definitions,
           provenance_of,
           resolve_target,
           target_name,
)

__all__ = ['Definition', 'Provenance', 'ResolvedTarget', 'gather_definitions', 'instances_from_definitions',
           'provenance_of', 'resolve_target', 'target_name']
