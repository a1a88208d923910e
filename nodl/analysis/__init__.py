"""The ``analyse`` feature (``nodl analyse``): a launched system's findings, reported.

The launched system itself (launch records -> system nodes -> instances -> system), the
run that builds and checks it, and the checks (the ``nodl.checks`` extension point) are the
shared layer :mod:`nodl.system`, which every consumer asks; the pictures of a system are
:mod:`nodl.graph`.  This package holds what only ``nodl analyse`` shows:

* :mod:`~nodl.analysis.report`: the report as JSON, text, SARIF and JUnit;
* :mod:`~nodl.analysis.log`: the log file (``--log``).

The names below are the shared layer's, importable from here as before.
"""

from __future__ import annotations

from nodl.system.checks import CheckExtension
from nodl.system.context import AnalysisContext, AnalysisSettings
from nodl.system.findings import KINDS, Finding
from nodl.system.launched import ParameterSetting, SystemNode
from nodl.system.run import (
           Analysis,
           analyse_definitions,
           analyse_entries,
           analyse_launch,
)

#: The former name of :class:`~nodl.system.launched.SystemNode`.
AnalysedNode = SystemNode

__all__ = [
           'KINDS',
           'AnalysedNode',
           'Analysis',
           'AnalysisContext',
           'AnalysisSettings',
           'CheckExtension',
           'Finding',
           'ParameterSetting',
           'SystemNode',
           'analyse_definitions',
           'analyse_entries',
           'analyse_launch',
]
