"""What ``nodl policy`` is given: node definitions placed by name, or a launch file.

Placing definitions is shared with ``nodl analyse DEFINITION...``, so it lives in the
shared targets layer (:mod:`nodl.targets.placement`); its names are kept here for
callers of this module.
"""

from __future__ import annotations

from nodl.targets.placement import (
    LAUNCH_SUFFIXES,
    Definition,
    default_node_name,
    instances_from_definitions,
    is_launch_file,
    split_node_name,
    split_targets,
)

__all__ = ['Definition', 'LAUNCH_SUFFIXES', 'is_launch_file', 'split_targets', 'default_node_name',
           'split_node_name', 'instances_from_definitions']
