"""Names in a policy, written so that SROS 2 resolves them to the node's final names.

How SROS 2 reads a name in a profile (``<profile ns="NS" node="NODE">``),
when it turns the policy into DDS permissions (its ``permissions.xsl``):

* a name starting with ``/`` is taken as it is;
* a name starting with ``~`` becomes ``NS`` (with a ``/`` added unless it
  ends with one) + ``NODE`` + the rest of the name after the ``~``, so
  ``~/scan`` is ``/NS/NODE/scan`` (but ``~scan`` would be ``/NS/NODEscan``:
  it is never written);
* any other name is appended to ``NS`` (with a ``/`` added unless it ends
  with one).

Nothing else is expanded (no ``{node}``, no remapping), so the toolkit writes
the final name, relative to the profile where that reads the same.  Each
granted name then becomes one or more DDS topic names: ``rt`` + name for a
topic, ``rq`` + name + ``Request`` and ``rr`` + name + ``Reply`` for a
service, and the ``/_action/...`` services and topics of an action.
DDS permissions compare names as patterns (``*``, ``?``, ``[...]``), which
ROS names never contain: a name holding one would grant more than itself.
"""

from __future__ import annotations

import re

from nodl.naming import full_name_error

__all__ = ['written_name', 'resolve_policy_name', 'dds_topics', 'WILDCARD', 'has_wildcard',
           'written_name_error']

#: Characters DDS permissions read as patterns (fnmatch-like).
WILDCARD = re.compile(r'[*?\[\]]')


def has_wildcard(name: str) -> bool:
    """True if DDS would read ``name`` as a pattern."""
    return WILDCARD.search(name) is not None


def _delimited(namespace: str) -> str:
    return namespace if namespace.endswith('/') else namespace + '/'


def resolve_policy_name(name: str, namespace: str, node: str) -> str:
    """The name SROS 2 makes of ``name`` written in the profile of ``node`` in ``namespace``."""
    if name.startswith('/'):
        return name
    if name.startswith('~'):
        return _delimited(namespace) + node + name[1:]
    return _delimited(namespace) + name


def written_name(final: str, namespace: str, node: str) -> str:
    """How to write the final name ``final`` in the profile of ``node`` in ``namespace``.

    ``~/x`` for the node's private names, a name relative to the namespace
    for names under it, the absolute name otherwise; in every case
    :func:`resolve_policy_name` gives ``final`` back.
    """
    own = _delimited(namespace) + node + '/'
    if final.startswith(own):
        return '~/' + final[len(own):]
    prefix = _delimited(namespace)
    if final.startswith(prefix) and len(final) > len(prefix):
        return final[len(prefix):]
    return final


def written_name_error(final: str) -> str | None:
    """Why the final name ``final`` cannot be granted (None: it can)."""
    if has_wildcard(final):
        return 'DDS would read it as a pattern and grant more than the name'
    return full_name_error(final)


#: communication -> access -> (DDS side, [(prefix, suffix)]): the DDS topics a grant covers.
_TOPICS: dict[str, dict[str, tuple[tuple[str, str, str], ...]]] = {
    'topic': {'publish': (('publish', 'rt', ''),), 'subscribe': (('subscribe', 'rt', ''),)},
    'service': {
        'request': (('publish', 'rq', 'Request'), ('subscribe', 'rr', 'Reply')),
        'reply': (('publish', 'rr', 'Reply'), ('subscribe', 'rq', 'Request')),
    },
}
_ACTION_SERVICES = ('cancel_goal', 'get_result', 'send_goal')
_ACTION_TOPICS = ('feedback', 'status')


def dds_topics(communication: str, access: str, final: str) -> list[tuple[str, str]]:
    """The ``(publish|subscribe, DDS topic)`` pairs a grant of ``access`` on ``final`` allows."""
    if communication == 'action':
        server = access == 'execute'
        out = []
        for service in _ACTION_SERVICES:
            out += dds_topics('service', 'reply' if server else 'request',
                              f'{final}/_action/{service}')
        for topic in _ACTION_TOPICS:
            out += dds_topics('topic', 'publish' if server else 'subscribe', f'{final}/_action/{topic}')
        return sorted(out)
    return sorted((side, f'{prefix}{final}{suffix}')
                  for side, prefix, suffix in _TOPICS[communication][access])
