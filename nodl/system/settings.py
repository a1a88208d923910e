"""The settings of the system checks: the ``analyse`` table of a project's configuration.

In ``nodl.toml``::

    [analyse]
    multiple_publishers_allow = ["/tf", "/diagnostics*"]

or ``[tool.nodl.analyse]`` in ``pyproject.toml``; the configuration found upward
from the launch file applies (the same file as ``ignore`` / ``error``).  The
configuration checks the table itself (:func:`nodl.config.analyse_table`, so a wrong
table fails every verb alike); this module makes the checks' settings of it.
"""

from __future__ import annotations

import fnmatch
import os
from dataclasses import dataclass

from nodl.config import (
    ANALYSE_KEYS,
    ANALYSE_TABLE,
    _table,
    analyse_table,
    find_config_file,
)

__all__ = ['SETTINGS_KEYS', 'TABLE', 'AnalysisSettings', 'load_settings', 'settings_from_table']

#: The configuration key holding the analysis settings.
TABLE = ANALYSE_TABLE
#: The keys of the ``[analyse]`` table of ``nodl.toml`` (``[tool.nodl.analyse]`` in
#: ``pyproject.toml``) and what each holds.
SETTINGS_KEYS = ANALYSE_KEYS


@dataclass(frozen=True)
class AnalysisSettings:
    """Settings of the checks (from the configuration, see :data:`SETTINGS_KEYS`)."""

    #: Topics several nodes may publish without a ``multiple-publishers`` finding.
    multiple_publishers_allow: tuple[str, ...] = ()

    def publishers_allowed(self, topic: str) -> bool:
        """True if ``topic`` is on the allow list."""
        return any(fnmatch.fnmatchcase(topic, pattern) for pattern in self.multiple_publishers_allow)


def settings_from_table(table: object, where: str) -> AnalysisSettings:
    """The settings of an ``analyse`` table (ConfigError naming ``where`` if it is wrong)."""
    return AnalysisSettings(**analyse_table(table, where))


def load_settings(launch_file: str) -> AnalysisSettings:
    """The settings that apply to ``launch_file`` (defaults if no configuration has any)."""
    config = find_config_file(os.path.dirname(os.path.abspath(launch_file)))
    if config is None:
        return AnalysisSettings()
    table = (_table(config) or {}).get(TABLE)
    if table is None:
        return AnalysisSettings()
    where = config + (' [tool.nodl]' if os.path.basename(config) == 'pyproject.toml' else '')
    return settings_from_table(table, where)
