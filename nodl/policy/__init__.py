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
"""

from __future__ import annotations

from nodl.policy.check import check_policy_file, granted_names
from nodl.policy.distros import DEFAULT_DISTRO, DISTROS
from nodl.policy.enclaves import ENCLAVE_MODES, assign_enclaves, load_enclave_mapping
from nodl.policy.generate import MissingNode, PolicyResult, policy_for_instances
from nodl.policy.grants import profile_for_instance
from nodl.policy.live import live_policy
from nodl.policy.model import (
    PERMISSIONS,
    POLICY_VERSION,
    Enclave,
    Grant,
    Policy,
    Profile,
    Source,
)
from nodl.policy.names import dds_topics, resolve_policy_name, written_name
from nodl.policy.schema_check import check_policy_structure, read_policy
from nodl.policy.targets import instances_from_definitions, split_targets
from nodl.policy.writer import PolicyNotWritable, write_policy

__all__ = [
    'DEFAULT_DISTRO', 'DISTROS', 'ENCLAVE_MODES', 'PERMISSIONS', 'POLICY_VERSION', 'Enclave', 'Grant',
    'MissingNode', 'Policy', 'PolicyNotWritable', 'PolicyResult', 'Profile', 'Source',
    'assign_enclaves', 'check_policy_file', 'check_policy_structure', 'dds_topics', 'granted_names',
    'instances_from_definitions', 'live_policy', 'load_enclave_mapping', 'policy_for_instances',
    'profile_for_instance', 'read_policy', 'resolve_policy_name', 'split_targets', 'write_policy',
    'written_name',
]
