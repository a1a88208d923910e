"""The one exception launch evaluation uses internally, and the launch limits.

Evaluation never lets an exception escape :func:`nodl.launch.load_launch`:
a :class:`LaunchProblem` raised while an action runs is caught by the walk,
turned into its :class:`~nodl.diagnostics.Diagnostic` (placed at the
action's launch entry when it carries no position of its own), and the walk
goes on with the next action.
"""

from __future__ import annotations

from nodl.diagnostics import Diagnostic, Severity

__all__ = ['LaunchProblem', 'Unevaluable', 'SubstitutionTooLarge', 'MAX_INCLUDE_DEPTH', 'MAX_ENTITIES',
           'MAX_XML_DEPTH', 'MAX_SUBSTITUTION_CHARS']

#: Includes nest at most this deep (a chain longer than this is reported, not followed).
MAX_INCLUDE_DEPTH = 40
#: At most this many launch entities are evaluated for one launch (a bound on work and memory).
MAX_ENTITIES = 200_000
#: XML and YAML launch files nest at most this deep (the NoDL frontends' limit).
MAX_XML_DEPTH = 100
#: A substitution's text (a ``let`` or ``arg`` value, ``$(var)``, a joined path...) is at
#: most this long: 16 MiB, well above real values (a ``robot_description`` is a few MB) and
#: far below what a doubling ``let`` chain reaches (20 lets: 12 GB in launch itself).
MAX_SUBSTITUTION_CHARS = 16 * 1024 * 1024


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
    """A value only a running launch can know (``$(command ...)``, an ``OpaqueFunction``).

    When the value is a launch configuration a ``let`` (or an ``arg`` default) sets,
    :attr:`origin` is where it is set, :attr:`configuration` its name and :attr:`reason` why
    it is unknown: the problem is then said once at the ``let``, each use a related place
    (:meth:`nodl.launch.context.LaunchContext.run_time`)."""

    #: Where the ``let``/``arg`` that sets the unknown configuration is written, if it is one.
    origin: tuple[str, int, int] | None = None
    #: The configuration's name (with :attr:`origin`).
    configuration: str = ''
    #: Why its value is unknown (with :attr:`origin`).
    reason: str = ''

    def __init__(self, message: str) -> None:
        super().__init__('NODL513', message, severity=Severity.WARNING)


class SubstitutionTooLarge(LaunchProblem):
    """A substitution's text would exceed :data:`MAX_SUBSTITUTION_CHARS` (NODL521); raised
    before the oversized text is made."""

    def __init__(self, message: str = '', file: str = '', line: int = 0, column: int = 0) -> None:
        super().__init__('NODL521', message or too_large_message(), file, line, column)

    def again(self) -> SubstitutionTooLarge:
        """The same problem, to raise again where the value is used (a fresh exception)."""
        return SubstitutionTooLarge(self.message, self.file, self.line, self.column)


def too_large_message(what: str = 'a substitution', *, made: bool = False) -> str:
    """The message of :class:`SubstitutionTooLarge` for ``what`` (``launch configuration 'x'``);
    ``made``: the text exists already (written so in a Python launch file), it is not used."""
    return (f'{what} {"is" if made else "would be"} longer than the substitution limit of 16 MiB '
            f'({MAX_SUBSTITUTION_CHARS:,} characters); {"not used" if made else "stopped before making it"}. '
            'Real values '
            '(a robot_description) are a few MB: look for a let or arg that repeats its own '
            'value ($(var x)$(var x)) or a value joined with itself')
