"""System analysis before launch (``nodl analyse``): launch files + definitions -> findings.

* :func:`analyse_launch` / :func:`analyse_entries` -> :class:`Analysis`
  (the launched nodes with their final names, and every :class:`Finding`);
* :mod:`~nodl.analysis.matching`: launched node -> registered definition;
* :mod:`~nodl.analysis.instances`: final names, remaps and parameters;
* :mod:`~nodl.analysis.checks`: the ``nodl.checks`` extension point and
  the built-in checks, one module per family;
* :mod:`~nodl.analysis.report`: JSON, text, SARIF, JUnit;
  :mod:`~nodl.analysis.log`: the log file;
  :mod:`~nodl.analysis.graph`: ``.dot``, ``.svg`` and ``.html`` pictures.

Names are imported lazily, like the package's other ``__init__`` modules.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # typing costs the command line start-up time; only type checkers need it
if TYPE_CHECKING:
    from typing import Any

_EXPORTS = {
    'Analysis': 'system', 'analyse_entries': 'system', 'analyse_launch': 'system',
    'AnalysisSettings': 'context', 'AnalysisContext': 'context',
    'LaunchEntry': 'entries', 'ParameterSetting': 'entries', 'ParameterFile': 'entries',
    'Finding': 'findings', 'KINDS': 'findings',
    'AnalysedNode': 'instances',
    'CheckExtension': 'checks',
}

__all__ = ['Analysis', 'AnalysedNode', 'AnalysisContext', 'AnalysisSettings', 'CheckExtension',
           'Finding', 'KINDS', 'LaunchEntry', 'ParameterFile', 'ParameterSetting',
           'analyse_entries', 'analyse_launch']

if TYPE_CHECKING:  # pragma: no cover
    from nodl.analysis.checks import CheckExtension
    from nodl.analysis.context import AnalysisContext, AnalysisSettings
    from nodl.analysis.entries import LaunchEntry, ParameterFile, ParameterSetting
    from nodl.analysis.findings import KINDS, Finding
    from nodl.analysis.instances import AnalysedNode
    from nodl.analysis.system import Analysis, analyse_entries, analyse_launch


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    value = getattr(importlib.import_module(f'{__name__}.{module}'), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
