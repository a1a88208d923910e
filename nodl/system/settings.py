"""The analysis settings of a project: the ``analyse`` table of its configuration.

In ``nodl.toml``::

    [analyse]
    multiple_publishers_allow = ["/tf", "/diagnostics*"]

or ``[tool.nodl.analyse]`` in ``pyproject.toml``; the configuration found upward
from the launch file applies (the same file as ``ignore`` / ``error``).
"""

from __future__ import annotations

import os

from nodl.config import ConfigError
from nodl.system.context import SETTINGS_KEYS, AnalysisSettings

__all__ = ['TABLE', 'load_settings', 'settings_from_table']

#: The configuration key holding the analysis settings.
TABLE = 'analyse'


def settings_from_table(table: object, where: str) -> AnalysisSettings:
    """The settings of an ``analyse`` table (ConfigError naming ``where`` if it is wrong)."""
    if not isinstance(table, dict):
        raise ConfigError(f"{where}: error: '{TABLE}' must be a table")
    for key, value in table.items():
        if key not in SETTINGS_KEYS:
            import difflib

            close = difflib.get_close_matches(str(key), list(SETTINGS_KEYS), n=1)
            hint = f"; did you mean '{close[0]}'?" if close else \
                f'; expected {", ".join(SETTINGS_KEYS)}'
            raise ConfigError(f"{where}: error: unknown key '{TABLE}.{key}'{hint}")
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise ConfigError(f"{where}: error: '{TABLE}.{key}' must be {SETTINGS_KEYS[key]}")
    return AnalysisSettings(tuple(table.get('multiple_publishers_allow', ())))


def load_settings(launch_file: str) -> AnalysisSettings:
    """The settings that apply to ``launch_file`` (defaults if no configuration has any)."""
    from nodl.config import _table, find_config_file

    config = find_config_file(os.path.dirname(os.path.abspath(launch_file)))
    if config is None:
        return AnalysisSettings()
    table = (_table(config) or {}).get(TABLE)
    if table is None:
        return AnalysisSettings()
    where = config + (' [tool.nodl]' if os.path.basename(config) == 'pyproject.toml' else '')
    return settings_from_table(table, where)
