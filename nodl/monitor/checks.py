"""What the monitor checks, as coded findings.

Endpoint and parameter drift is decided by :func:`nodl.live.conformance.compare`,
exactly as ``nodl check`` decides it (NODL401-408); connections as ``nodl analyse``
names them (NODL552 type mismatch, NODL553/554 QoS, through
:func:`nodl.qos_compat.check_qos_compatible`); namesakes as NODL550.  The
monitor's own findings are NODL430-440 (see :mod:`nodl.codes`).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from nodl.composition.entities import Location
from nodl.diagnostics import Diagnostic, Severity
from nodl.live.conformance import UNPLACED, LiveDiagnostic

if TYPE_CHECKING:
    from nodl.monitor.expected import DeadlineTopic, ExpectedNode
    from nodl.monitor.graph import LiveTopicEndpoint

__all__ = ['StatusFinding', 'from_difference', 'endpoint_findings', 'connection_findings',
           'parameter_event_findings', 'rate_finding', 'LEVELS']

#: Diagnostic levels (diagnostic_msgs/DiagnosticStatus), by severity.
LEVELS = {'info': 0, 'warning': 1, 'error': 2}


@dataclass(frozen=True)
class StatusFinding:
    """One coded finding about a node (or the system)."""

    code: str
    #: ``error``, ``warning`` or ``info``.
    severity: str
    #: What it is about (an entity, a topic, a node name): with the code, its identity.
    subject: str
    message: str
    #: Where it points (a declaration, a launch entry), when known.
    location: Location | None = None

    @property
    def level(self) -> int:
        """The diagnostic level it gives a status (OK 0, WARN 1, ERROR 2)."""
        return LEVELS[self.severity]

    @property
    def key(self) -> tuple[str, str]:
        """``(code, subject)``: what stays the same while the finding lasts."""
        return self.code, self.subject

    def diagnostic(self, default: Location | None = None) -> Diagnostic:
        """The finding as a :class:`~nodl.diagnostics.Diagnostic`, at its location
        (else ``default``, else ``<graph>``)."""
        where = self.location or default
        if where is None:
            return Diagnostic(Severity(self.severity), self.message, (), '<graph>', code=self.code)
        return Diagnostic(Severity(self.severity), self.message, (), str(where.file),
                          int(where.line), int(where.column), code=self.code)


def _place_of(diagnostic: LiveDiagnostic) -> Location | None:
    """Where a ``nodl check`` diagnostic points: the entity's declaration, or for what is
    observed but not declared the section of the definition it would belong in; None when it
    was not placed."""
    if diagnostic.file == UNPLACED:
        return diagnostic.location
    return Location(diagnostic.file, diagnostic.line, diagnostic.column)


def from_difference(difference: LiveDiagnostic) -> StatusFinding:
    """A ``nodl check`` diagnostic as a finding (its code, severity, message and place)."""
    return StatusFinding(difference.code, difference.severity.value,
                         f'{difference.section} {difference.name}',
                         f'{difference.kind}: {difference.message}', _place_of(difference))


def endpoint_findings(differences: Iterable[LiveDiagnostic]) -> list[StatusFinding]:
    """The findings of ``nodl check``'s diagnostics; what cannot be verified is stated once
    (one NODL408 finding listing every such thing), not one finding each."""
    out: list[StatusFinding] = []
    unverifiable: list[LiveDiagnostic] = []
    for difference in differences:
        if difference.kind == 'unverifiable':
            unverifiable.append(difference)
        else:
            out.append(from_difference(difference))
    if unverifiable:
        first = unverifiable[0]
        more = f' (and {len(unverifiable) - 1} more)' if len(unverifiable) > 1 else ''
        out.append(StatusFinding('NODL408', 'info', 'unverifiable',
                                 f'cannot be verified: {first.message}{more}', _place_of(first)))
    return out


def _qos_text(endpoint: LiveTopicEndpoint) -> str:
    qos = endpoint.qos_dict
    return ', '.join(f'{k} {qos[k]}' for k in ('reliability', 'durability', 'deadline_ns')
                     if k in qos)


def connection_findings(topics: dict[str, list[LiveTopicEndpoint]]) -> dict[str, list[StatusFinding]]:
    """Per node (fully qualified name): the problems of the connections it takes part in.

    * NODL552: the endpoints of a topic disagree on its type;
    * NODL437: they agree on the type name but their type hashes differ (version skew);
    * NODL553 / NODL554: a publisher and a subscription the middleware would not match
      (or would match with a warning), as :func:`~nodl.qos_compat.check_qos_compatible`
      decides.

    Each finding is given to both nodes of the pair.
    """
    from nodl.qos_compat import check_qos_compatible

    out: dict[str, list[StatusFinding]] = {}

    def add(node: str, finding: StatusFinding) -> None:
        found = out.setdefault(node, [])
        if finding not in found:
            found.append(finding)

    for topic, endpoints in sorted(topics.items()):
        types = sorted({e.type for e in endpoints})
        if len(types) > 1:
            for endpoint in endpoints:
                add(endpoint.node, StatusFinding('NODL552', 'error', f'topic {topic}',
                                                 f"type-mismatch: the endpoints of topic '{topic}' "
                                                 f"disagree on its type: {', '.join(types)}"))
            continue
        hashes = sorted({e.type_hash for e in endpoints if e.type_hash})
        if len(hashes) > 1:
            by_hash: dict[str, list[str]] = {}
            for endpoint in endpoints:
                if endpoint.type_hash:
                    by_hash.setdefault(endpoint.type_hash, []).append(endpoint.node)
            detail = '; '.join(f'{h[:18]}...: {", ".join(sorted(set(n)))}'
                               for h, n in sorted(by_hash.items()))
            for endpoint in endpoints:
                add(endpoint.node, StatusFinding('NODL437', 'error', f'topic {topic}',
                                                 f"version skew: the endpoints of topic '{topic}' "
                                                 f'({types[0]}) have different type hashes ({detail})'))
        publishers = [e for e in endpoints if e.kind == 'publisher']
        subscriptions = [e for e in endpoints if e.kind == 'subscription']
        for publisher in publishers:
            for subscription in subscriptions:
                verdict, reason = check_qos_compatible(publisher.qos_dict,
                                                       subscription.qos_dict)
                if verdict == 'ok':
                    continue
                code, severity = (('NODL553', 'error') if verdict == 'error'
                                  else ('NODL554', 'warning'))
                message = (f"qos-{'incompatible' if verdict == 'error' else 'warning'}: topic "
                           f"'{topic}': publisher {publisher.node} ({_qos_text(publisher)}) and "
                           f'subscription {subscription.node} ({_qos_text(subscription)}): '
                           f'{reason}')
                subject = f'topic {topic} {publisher.node} -> {subscription.node}'
                finding = StatusFinding(code, severity, subject, message)
                add(publisher.node, finding)
                add(subscription.node, finding)
    return out


def parameter_event_findings(expected: ExpectedNode, name: str, type_name: str,
                             value: Any, changed: bool) -> list[StatusFinding]:
    """What a parameter event (``name`` set to ``value`` of ``type_name``; ``changed``: it
    held a value before) says that the current value alone does not: a parameter the
    definition declares read-only was changed at run time (NODL438)."""
    if expected.resolved is None or not changed:
        return []
    declared = (expected.resolved.interface.parameters or {}).get(name)
    if declared is None or not declared.read_only:
        return []
    where = {id(e.definition): e.location for e in expected.resolved.entities}.get(id(declared))
    return [StatusFinding('NODL438', 'error', f'parameters {name}',
                          f"parameter '{name}' is declared read_only but was changed at run time "
                          f'(to {value!r}, {type_name})', where)]


def rate_finding(deadline: DeadlineTopic, count: int, window: float, tolerance: float
                 ) -> StatusFinding | None:
    """The rate of a topic with a declared deadline, measured as ``count`` messages in the
    last ``window`` seconds: ERROR (NODL435) when nothing arrived, WARN (NODL436) below
    ``(1 - tolerance) / deadline``, else None."""
    expected = deadline.expected_rate
    subject = f'rate {deadline.topic}'
    if count == 0:
        return StatusFinding('NODL435', 'error', subject,
                             f"no message on '{deadline.topic}' in the last {window:g} s (its deadline "
                             f'asks for {expected:g} Hz)', deadline.location)
    rate = count / window
    if rate < expected * (1.0 - tolerance):
        return StatusFinding('NODL436', 'warning', subject,
                             f"'{deadline.topic}' is published at {rate:.3g} Hz, slower than the "
                             f'{expected:g} Hz its deadline of {deadline.deadline_ns / 1e6:g} ms asks '
                             f'for (tolerance {tolerance:.0%}, window {window:g} s)', deadline.location)
    return None
