"""SROS 2 access-control policies from node definitions, launched systems or a running graph.

* :func:`policy_for_instances` -- the least-privilege policy of node
  instances (a launched system, or definitions placed by name), with coded
  diagnostics for what keeps it from being exact;
* :func:`write_policy` -- the policy document, deterministic and canonically
  ordered, with comments tracing every grant; never one SROS 2 would reject;
* :func:`check_policy_file` -- an existing policy against what the system
  needs: missing and extra grants, each placed in the file;
* :func:`live_policy` -- the policy of the running graph (actions as
  ``<actions>``, base entities as the client library creates them);
* :func:`check_policy_structure` -- the structure of ``policy.xsd``.

Names are imported lazily, like the package's other ``__init__`` modules.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

_EXPORTS = {
    'POLICY_VERSION': 'model', 'PERMISSIONS': 'model', 'Grant': 'model', 'Source': 'model',
    'Profile': 'model', 'Enclave': 'model', 'Policy': 'model',
    'DISTROS': 'distros', 'DEFAULT_DISTRO': 'distros',
    'profile_for_instance': 'grants',
    'written_name': 'names', 'resolve_policy_name': 'names', 'dds_topics': 'names',
    'ENCLAVE_MODES': 'enclaves', 'load_enclave_mapping': 'enclaves', 'assign_enclaves': 'enclaves',
    'MissingNode': 'generate', 'PolicyResult': 'generate', 'policy_for_instances': 'generate',
    'write_policy': 'writer', 'PolicyNotWritable': 'writer',
    'read_policy': 'schema_check', 'check_policy_structure': 'schema_check',
    'check_policy_file': 'check', 'granted_names': 'check',
    'instances_from_definitions': 'targets', 'split_targets': 'targets',
    'live_policy': 'live',
}

__all__ = sorted(_EXPORTS)

if TYPE_CHECKING:  # pragma: no cover
    from nodl.policy.check import check_policy_file, granted_names
    from nodl.policy.distros import DEFAULT_DISTRO, DISTROS
    from nodl.policy.enclaves import ENCLAVE_MODES, assign_enclaves, load_enclave_mapping
    from nodl.policy.generate import MissingNode, PolicyResult, policy_for_instances
    from nodl.policy.grants import profile_for_instance
    from nodl.policy.live import live_policy
    from nodl.policy.model import (
        PERMISSIONS, POLICY_VERSION, Enclave, Grant, Policy, Profile, Source)
    from nodl.policy.names import dds_topics, resolve_policy_name, written_name
    from nodl.policy.schema_check import check_policy_structure, read_policy
    from nodl.policy.targets import instances_from_definitions, split_targets
    from nodl.policy.writer import PolicyNotWritable, write_policy


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    value = getattr(importlib.import_module(f'{__name__}.{module}'), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
