"""The one exception launch evaluation uses internally, and the launch limits.

Evaluation never lets an exception escape :func:`nodl_schema.launch.load_launch`:
a :class:`LaunchProblem` raised while an action runs is caught by the walk,
turned into its :class:`~nodl_schema.diagnostics.Diagnostic` (placed at the
action's launch entry when it carries no position of its own), and the walk
goes on with the next action.
"""

from __future__ import annotations

from nodl_schema.diagnostics import Diagnostic, Severity

__all__ = ['LaunchProblem', 'Unevaluable', 'MAX_INCLUDE_DEPTH', 'MAX_ENTITIES', 'MAX_XML_DEPTH']

#: Includes nest at most this deep (a chain longer than this is reported, not followed).
MAX_INCLUDE_DEPTH = 40
#: At most this many launch entities are evaluated for one launch (a bound on work and memory).
MAX_ENTITIES = 200_000
#: XML and YAML launch files nest at most this deep (the NoDL frontends' limit).
MAX_XML_DEPTH = 100


class LaunchProblem(Exception):
    """A problem in a launch file that stops the current action (never the whole walk)."""

    def __init__(self, code: str, message: str, file: str = '', line: int = 0, column: int = 0,
                 severity: Severity = Severity.ERROR) -> None:
        super().__init__(message)
        self.code = code
        self.message = message
        self.file = file
        self.line = line
        self.column = column
        self.severity = severity

    def diagnostic(self, file: str = '', line: int = 0, column: int = 0) -> Diagnostic:
        """The diagnostic, placed at its own position or else at ``file:line:column``."""
        if self.file and self.line:
            file, line, column = self.file, self.line, self.column
        return Diagnostic(self.severity, self.message, (), self.file or file or '<launch>', line,
                          column, code=self.code)


class Unevaluable(LaunchProblem):
    """A value only a running launch can know (``$(command ...)``, an ``OpaqueFunction``)."""

    def __init__(self, message: str) -> None:
        super().__init__('NODL513', message, severity=Severity.WARNING)
