"""``--live``: the policy of the running graph, with the gaps of a graph snapshot closed.

Every node of the graph is observed as ``nodl describe`` observes it
(:mod:`nodl.live`): actions are folded from their hidden ``_action``
topics and services into ``<actions>`` grants, service clients are included,
and the base's entities are granted as the node's client library creates
them (the description is composed with its base, so a parameter service or
``/clock`` that did not show at the moment of observation is still granted).
What could not be observed is returned in words: hidden nodes (names
starting with ``_``) left out, nodes that vanished, observation notes.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from nodl.composition.instance import NodeInstance
from nodl.composition.resolved import resolve_node
from nodl.live.describe import describe_observed
from nodl.live.describe_all import _discover
from nodl.live.observe import observe_node
from nodl.live.session import LiveError, is_hidden_node, ros_session
from nodl.loading import dump_nodl
from nodl.policy.distros import DEFAULT_DISTRO
from nodl.policy.enclaves import EnclaveMapping
from nodl.policy.generate import PolicyResult, policy_for_instances
from nodl.policy.model import Source

__all__ = ['LivePolicy', 'live_policy']


class LivePolicy(NamedTuple):
    """The policy of the running graph and what could not be observed."""

    result: PolicyResult
    #: Node fully qualified names observed.
    nodes: list[str]
    #: What could not be observed, in words (one line each).
    unobserved: list[str]


def _instance(observed: Any, client_library: str | None) -> Any:
    description = describe_observed(observed, client_library)
    text = dump_nodl(description.node, 'yaml')
    resolved = resolve_node(text, file=f'<observed {observed.fully_qualified_name}>',
                            client_library=description.client_library)
    overrides = {}
    if observed.parameters and 'use_sim_time' in observed.parameters:
        overrides['use_sim_time'] = observed.parameters['use_sim_time'].value
    return NodeInstance(resolved, observed.name, observed.namespace, None, overrides)


def live_policy(*, timeout: float = 5.0, settle: float = 3.5, distro: str = DEFAULT_DISTRO,
                enclaves: str | EnclaveMapping = 'node', client_library: str | None = None
                ) -> LivePolicy:
    """Observe every node of the graph and make its policy.

    Discovery is given up to ``timeout`` seconds (at least ``settle`` seconds
    once a node is seen).  Raises :class:`~nodl.live.session.LiveError`
    when the graph is empty.
    """
    instances = []
    unobserved: list[str] = []
    observed_names: list[str] = []
    with ros_session() as node:
        names = _discover(node, timeout, settle)
        for fqn in names:
            if is_hidden_node(fqn):
                unobserved.append(f'{fqn}: a hidden node, left out')
                continue
            try:
                observed = observe_node(fqn, timeout=timeout, parameters=True, session=node,
                                        watch=settle)
            except LiveError as exc:
                unobserved.append(f'{fqn}: {exc}')
                continue
            unobserved += [f'{fqn}: {note}' for note in observed.warnings + observed.notes]
            instances.append(_instance(observed, client_library))
            observed_names.append(fqn)
    if not instances:
        raise LiveError('no nodes in the graph to write a policy for (check ROS_DOMAIN_ID and '
                        'ROS_AUTOMATIC_DISCOVERY_RANGE)' + (f'; left out: {len(unobserved)}'
                                                            if unobserved else ''))
    result = policy_for_instances(instances, distro=distro, enclaves=enclaves,
                                  notes=['Observed from the running graph by nodl policy --live.'])
    for _, profile in result.policy.profiles():
        profile.definition = ''
        profile.notes.insert(0, 'observed in the running graph; base entities as its client '
                             'library creates them')
        for grant in profile.grants.values():
            grant.sources = [s if s.what.startswith('client library') else
                             Source(s.what.split(' (')[0] + ' (observed)') for s in grant.sources]
    return LivePolicy(result, observed_names, unobserved)
