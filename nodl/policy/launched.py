"""The policy of a launched system: the launch file resolved exactly as ``nodl analyse`` resolves it.

The launch file is read and its nodes matched, named, remapped and given
their parameters by :func:`nodl.system.run.analyse_launch` (no checks
run: the policy needs the instances, not the findings).  Launch-file problems
are reported as they are; a node without a usable definition is a gap
(NODL601).
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import TYPE_CHECKING

from nodl.policy.distros import DEFAULT_DISTRO
from nodl.policy.enclaves import EnclaveMapping
from nodl.policy.generate import (
    MissingNode,
    PolicyResult,
    gapped_nodes,
    policy_for_instances,
)
from nodl.policy.grants import display_path
from nodl.system.launched import node_provenance
from nodl.system.run import analyse_launch

if TYPE_CHECKING:
    from nodl.launch.sandbox import LaunchLimits
    from nodl.registry.overlay import Definitions

__all__ = ['launch_policy']


def launch_policy(path: str | os.PathLike[str], arguments: Mapping[str, str] | None = None, *,
                  client_library: str | None = None, distro: str = DEFAULT_DISTRO,
                  enclaves: str | EnclaveMapping = 'node', allow_missing: bool = False,
                  prefixes: list[str] | None = None, limits: LaunchLimits | None = None,
                  definitions: Definitions | None = None, allow_gaps: bool = False) -> PolicyResult:
    """The policy of the system ``path`` launches with ``arguments`` (``limits``: how the
    launch's Python code runs, if at all; see :class:`~nodl.launch.sandbox.LaunchLimits`).

    ``definitions``: definitions folders looked in before the index (what is wrong with
    their layout is among the diagnostics).  OSError if the launch file cannot be read at
    all; ValueError if it cannot be parsed (its diagnostics in the message).
    """
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise OSError(2, 'No such file or directory' if not os.path.isdir(path) else 'is a directory',
                      path)
    analysis = analyse_launch(path, dict(arguments or {}), client_library=client_library,
                              prefixes=prefixes, checks={}, limits=limits, definitions=definitions)
    launch_problems = [f.diagnostic for f in analysis.findings]
    if analysis.unreadable:
        raise ValueError('; '.join(str(d) for d in launch_problems) or f'{path} cannot be read')
    instances = []
    missing = []
    for node in analysis.nodes:
        if node.instance is not None:
            instances.append(node.instance)
            continue
        if node.match.resolved is None:
            reason = (f'{node.executable_label}: its definition does not resolve' if node.match.file
                      else f'nothing registered for {node.executable_label}')
        else:
            reason = f'{node.executable_label}: its name or remapping cannot be resolved'
        missing.append(MissingNode(node.fqn, reason, node.location))
    containers = {node.fqn: node.entry.container for node in analysis.nodes if node.entry.container}
    gapped = gapped_nodes((node.fqn, node.match.file, node.location) for node in analysis.nodes
                          if node.instance is not None)
    result = policy_for_instances(
        instances, missing=missing, distro=distro, enclaves=enclaves, allow_missing=allow_missing,
        containers=containers, gapped=gapped, allow_gaps=allow_gaps,
        notes=[f'Least-privilege SROS 2 policy written by nodl policy for the system '
               f'{display_path(os.path.abspath(path))} launches.'])
    sources = tuple(node_provenance(node) for node in analysis.nodes)
    return result._replace(diagnostics=launch_problems + result.diagnostics, sources=sources,
                           files=tuple(dict.fromkeys([path, *analysis.files()])))
