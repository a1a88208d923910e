"""Launch files read faithfully (XML, YAML, Python) into launched-node records.

``load_launch(path, {'name': 'value'})`` returns a :class:`LaunchResult`: every node
``ros2 launch`` would start (or load into a container) with its final namespace, remaps
in rcl's order, parameter sources in application order and source location, the
declared arguments, and coded diagnostics (NODL5xx) for every problem.  Nothing is started.
``parameter_overrides(node, fqn)`` resolves a node's parameter sources to the values it
receives, as rcl (processes) and launch_ros (composable nodes) resolve them.
"""

from __future__ import annotations

from nodl.launch.evaluate import load_launch
from nodl.launch.model import LaunchArgument, LaunchedNode, LaunchResult, ParameterSource, SourceLocation
from nodl.launch.parameter_values import (
                                      ParameterOverride,
                                      match_composable_parameter_keys,
                                      match_parameter_file_nodes,
                                      parameter_overrides,
)
from nodl.launch.params import load_parameter_file

__all__ = ['load_launch', 'LaunchResult', 'LaunchedNode', 'LaunchArgument', 'ParameterSource',
           'SourceLocation', 'load_parameter_file', 'match_parameter_file_nodes',
           'match_composable_parameter_keys', 'parameter_overrides', 'ParameterOverride']
