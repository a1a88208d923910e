"""Former path of :mod:`nodl.system.run` (the run over a launched system: it is a run, not a
system, so it moved and was renamed)."""

from __future__ import annotations

from nodl.system.run import (
    DEFINITIONS_KIND,
    LAUNCH_KIND,
    Analysis,
    analyse_definitions,
    analyse_entries,
    analyse_launch,
)

__all__ = [
    'DEFINITIONS_KIND',
    'LAUNCH_KIND',
    'Analysis',
    'analyse_definitions',
    'analyse_entries',
    'analyse_launch',
]
