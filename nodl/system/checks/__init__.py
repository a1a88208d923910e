"""The ``nodl.checks`` extension point: checks over a launched system (NODL55x and more).

A check is a class registered in the ``nodl.checks`` entry point group,
normally a subclass of :class:`CheckExtension`.  It lists the kinds of finding
it reports (keys of :data:`nodl.system.findings.KINDS`, or its own
with codes it brings) and yields :class:`~nodl.system.findings.Finding`
objects from :meth:`CheckExtension.check`, given the :class:`AnalysisContext`.
The built-in checks are registered exactly as a plug-in registers its own; a
plug-in that cannot be loaded, or raises, is reported as a finding
(``broken-check``) and skipped.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from nodl.location import Location
from nodl.plugins import EXTENSION_POINTS, ExtensionPoint, instantiate_extensions
from nodl.system.context import AnalysisContext
from nodl.system.findings import Finding, make_finding

__all__ = ['CHECK_GROUP', 'CheckExtension', 'load_checks', 'run_checks']

#: The entry point group of checks.
CHECK_GROUP = 'nodl.checks'


class CheckExtension(ExtensionPoint):
    """Base class of analysis checks (the ``nodl.checks`` extension point, version 1.0:
    ``kinds``, ``check(context) -> Iterable[Finding]``)."""

    EXTENSION_POINT_VERSION = EXTENSION_POINTS[CHECK_GROUP].version

    #: The kinds of finding the check reports.
    kinds: tuple[str, ...] = ()

    def check(self, context: AnalysisContext) -> Iterable[Finding]:
        """Yield the findings about the system in ``context``."""
        raise NotImplementedError


def load_checks(names: Iterable[str] | None = None) -> tuple[dict[str, object], list[str]]:
    """The registered checks (by entry point name, by priority) and one line per broken one."""
    broken: list[str] = []
    checks = instantiate_extensions(
        CHECK_GROUP, names=names,
        on_error=lambda e: broken.append(f"check '{e.name}' ({e.value}) skipped: {e.error}"))
    return checks, broken


def run_checks(context: AnalysisContext, checks: dict[str, object] | None = None
               ) -> Iterator[Finding]:
    """Every finding of every check; a check that raises becomes a ``broken-check`` finding."""
    broken: list[str] = []
    if checks is None:
        checks, broken = load_checks()
    for line in broken:
        yield make_finding('broken-check', line, Location('<nodl.checks>', 0, 0))
    for name, check in checks.items():
        try:
            found = list(check.check(context))  # type: ignore[attr-defined]
            if not all(isinstance(f, Finding) for f in found):
                raise TypeError('it yielded something other than Finding objects')
        except Exception as exc:  # noqa: BLE001 - a broken plug-in must not stop the analysis
            yield make_finding('broken-check', f"check '{name}' skipped: it raised "
                               f'{type(exc).__name__}: {exc}', Location('<nodl.checks>', 0, 0))
            continue
        yield from found
