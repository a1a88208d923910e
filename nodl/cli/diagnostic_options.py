"""``--ignore CODE`` / ``--error CODE`` for every verb that reports diagnostics.

A verb calls :func:`add_diagnostic_options` in ``add_arguments`` and builds a
:class:`DiagnosticPolicy` in ``main``; the policy applies, per file, the
configuration found upward from it (``nodl.toml`` / ``[tool.nodl]``) and then
the command line, which wins.  Bad codes and bad configuration files are
usage errors (:class:`PolicyError`, exit status 2), reported on one line.
"""

from __future__ import annotations

import argparse
import os
from typing import TYPE_CHECKING

from nodl.config import ConfigCache, ConfigError
from nodl.overrides import Overrides, apply_overrides, parse_code_list

if TYPE_CHECKING:
    from nodl.config import ConfigCache
    from nodl.diagnostics import Diagnostic
    from nodl.overrides import Overrides

__all__ = ['add_diagnostic_options', 'DiagnosticPolicy', 'PolicyError']


class PolicyError(ValueError):
    """A usage error in the options or the configuration; the message is the line to print."""


def add_diagnostic_options(parser: argparse.ArgumentParser) -> None:
    """Declare ``--ignore`` and ``--error`` (repeatable, comma-separated)."""
    parser.add_argument('--ignore', action='append', default=[], metavar='CODE',
                        help='do not report diagnostics with this code (repeatable, or '
                             'CODE,CODE); see docs/diagnostics.md')
    parser.add_argument('--error', action='append', default=[], metavar='CODE',
                        help='report diagnostics with this code as errors (repeatable, or '
                             'CODE,CODE)')


def _codes(values: list[str], option: str, verb: str) -> list[str]:
    if not values:
        return []  # the usual case: the catalogue is not even imported
    from nodl.codes import close_codes
    codes, unknown = parse_code_list(values)
    if unknown:
        close = close_codes(unknown[0])
        hint = f"; did you mean '{close[0]}'?" if close else ' (the codes are listed in docs/diagnostics.md)'
        raise PolicyError(f"{verb}: error: unknown code '{unknown[0]}' for {option}{hint}")
    return codes


class DiagnosticPolicy:
    """What the command line and the configuration files say about codes."""

    def __init__(self, args: argparse.Namespace, verb: str, use_config: bool = True) -> None:
        ignore = _codes(getattr(args, 'ignore', None) or [], '--ignore', verb)
        error = _codes(getattr(args, 'error', None) or [], '--error', verb)
        both = sorted(set(ignore) & set(error))
        if both:
            raise PolicyError(f'{verb}: error: {both[0]} is given to both --ignore and --error')
        self.command_line: Overrides = Overrides(ignore, error)
        self._configs: ConfigCache | None = None
        self.use_config = use_config

    def overrides_for(self, file: str | None) -> Overrides:
        """The overrides for diagnostics of ``file`` (None: only the command line's)."""
        if not self.use_config or file is None or file.startswith('<'):
            return self.command_line
        if not os.path.exists(file):
            return self.command_line
        if self._configs is None:
            self._configs = ConfigCache()
        try:
            found = self._configs.overrides_for(file)
        except ConfigError as exc:
            raise PolicyError(str(exc)) from None
        return found.then(self.command_line)

    def apply(self, file: str | None, diagnostics: list[Diagnostic]) -> list[Diagnostic]:
        """``diagnostics`` of ``file`` with the overrides applied."""
        overrides = self.overrides_for(file)
        if not overrides or not diagnostics:
            return diagnostics
        return apply_overrides(diagnostics, overrides)
