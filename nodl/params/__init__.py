"""Parameter files and node definitions, without ROS.

* :func:`~nodl.plan.defaults_file.defaults_yaml` (from the shared plan): a node's defaults as a
  ready ``ros__parameters`` file (``nodl params DEFINITION -o FILE``);
* :func:`~nodl.params.check.check_parameter_files`: parameter files
  checked against a node's definition (``nodl params check``): node keys and
  wildcards matched as rcl matches them, unknown names with a suggestion,
  types as strictly as a node types them, every built-in validator, required
  parameters never set; each a coded diagnostic (NODL70x) at ``FILE:LINE:COL``.

The parameter semantics (types, validators) are the generators' parameter
plan (:mod:`nodl.plan.parameter_plan`), so a file that passes here
starts a generated or runtime node.
"""

from __future__ import annotations

from nodl.params.check import check_launch_parameters, check_parameter_files
from nodl.plan.defaults_file import defaults_yaml

__all__ = ['check_parameter_files', 'check_launch_parameters', 'defaults_yaml']
