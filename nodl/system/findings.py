"""Findings: coded diagnostics about a launched system, with the nodes they concern.

A :class:`Finding` is a :class:`~nodl.diagnostics.Diagnostic` (code,
severity, message, the launch entry or parameter-file line that caused it,
related places such as the definition) plus what a system view needs: the
finding's kind (``duplicate-node``, ...), the final names of the nodes
involved, and the final name of the endpoint or parameter it is about.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace
from typing import Any

from nodl.codes import default_severity
from nodl.composition.entities import Location
from nodl.diagnostics import Diagnostic, Severity

__all__ = ['KINDS', 'KIND_OF_CODE', 'Finding', 'make_finding']

#: Every kind of finding -> its code (the catalogue in nodl.codes holds the
#: default severity and the explanation).  The one table of kinds.
KINDS: dict[str, str] = {
    'duplicate-node': 'NODL550',
    'multiple-publishers': 'NODL551',
    'type-mismatch': 'NODL552',
    'qos-incompatible': 'NODL553',
    'qos-warning': 'NODL554',
    'orphan-subscription': 'NODL555',
    'orphan-service-client': 'NODL556',
    'orphan-action-client': 'NODL557',
    'orphan-publisher': 'NODL558',
    'unused-remap': 'NODL559',
    'unknown-parameter': 'NODL560',
    'parameter-type': 'NODL561',
    'parameter-invalid': 'NODL562',
    'missing-parameter': 'NODL563',
    'no-definition': 'NODL564',
    'unnamed-node': 'NODL565',
    'not-analysable': 'NODL566',
    'broken-check': 'NODL567',
    'assumed-duplicate-node': 'NODL530',
    'type-definition-mismatch': 'NODL570',
    'draft-gaps': 'NODL568',
}
#: code -> kind.
KIND_OF_CODE: dict[str, str] = {code: kind for kind, code in KINDS.items()}

#: A severity's word -> the severity (``Severity(word)`` is an enum look-up per finding).
_SEVERITIES = {severity.value: severity for severity in Severity}


@dataclass(frozen=True, slots=True)  # (no __dict__: fewer objects for the collector to walk)
class Finding:
    """One finding (see the module docstring)."""

    diagnostic: Diagnostic
    kind: str
    #: The final names of the nodes involved.
    nodes: tuple[str, ...] = ()
    #: The final name of the topic, service or action it is about, if any.
    endpoint: str | None = None
    #: The parameter it is about, if any.
    parameter: str | None = None

    @property
    def code(self) -> str:
        """The finding's code."""
        return self.diagnostic.code

    @property
    def severity(self) -> Severity:
        """Its severity (after ``--ignore``/``--error`` and the configuration)."""
        return self.diagnostic.severity

    @property
    def message(self) -> str:
        """What is wrong."""
        return self.diagnostic.message

    def with_diagnostic(self, diagnostic: Diagnostic) -> Finding:
        """The same finding with another diagnostic (a promoted severity)."""
        return replace(self, diagnostic=diagnostic)

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: code, kind, severity, message, file, line, column, nodes, and
        ``endpoint`` or ``parameter`` where it applies, ``related`` places when there are
        some (``{file, line, column, message}``)."""
        d = self.diagnostic
        out: dict[str, Any] = {'code': d.code, 'kind': self.kind, 'severity': d.severity.value,
                               'message': d.message, 'file': d.file, 'line': d.line,
                               'column': d.column, 'nodes': list(self.nodes)}
        if self.endpoint is not None:
            out['endpoint'] = self.endpoint
        if self.parameter is not None:
            out['parameter'] = self.parameter
        if d.related:  # other places that matter (where a run-time let is used...)
            out['related'] = [{'file': f, 'line': li, 'column': c, 'message': m}
                              for f, li, c, m in d.related]
        return out

    def __str__(self) -> str:
        return str(self.diagnostic)


def make_finding(kind: str, message: str, location: Location, nodes: Iterable[str] = (), *,
                 endpoint: str | None = None, parameter: str | None = None,
                 related: Iterable[tuple[str, int, int, str]] = ()) -> Finding:
    """A finding of ``kind`` with the default severity of its code."""
    code = KINDS[kind]
    severity = default_severity(code)
    diagnostic = Diagnostic(_SEVERITIES.get(severity) or Severity(severity), message, (),
                            location.file, location.line, location.column, code=code,
                            related=related)
    return Finding(diagnostic, kind, tuple(dict.fromkeys(nodes)), endpoint, parameter)
