"""Project configuration: ``nodl.toml`` or ``[tool.nodl]`` in ``pyproject.toml``.

The configuration of a checked file is the one found first going up from its
directory: a ``nodl.toml`` (its keys at the top level), else a
``pyproject.toml`` that has a ``[tool.nodl]`` table (a ``pyproject.toml``
without one is passed over).  Keys:

``ignore``
    a list of codes whose diagnostics are not reported;
``error``
    a list of codes whose diagnostics are errors whatever their severity;
``analyse``
    a table of settings of ``nodl analyse`` (:data:`ANALYSE_KEYS`, checked here by
    :func:`analyse_table`; :mod:`nodl.system.settings` makes the analysis's settings of it);
``definitions``
    a list of definitions folders (overlays, :mod:`nodl.registry.overlay`), relative
    to the configuration file's folder (:func:`definitions_of`).

Unknown keys, values that are not lists of strings and unknown codes are a
:class:`ConfigError` (a ``ValueError``) whose message names the file.
"""

from __future__ import annotations

import os
import re
from typing import Any

from nodl.overrides import Overrides, parse_code_list
from nodl.wording import did_you_mean

__all__ = ['ConfigError', 'CONFIG_FILES', 'KEYS', 'ANALYSE_TABLE', 'ANALYSE_KEYS', 'analyse_table',
           'find_config_file', 'load_config', 'overrides_for', 'ConfigCache', 'definitions_of']

#: The file names looked for in each directory, in order of precedence.
CONFIG_FILES = ('nodl.toml', 'pyproject.toml')
#: The keys of a configuration and what each holds.
KEYS = {'ignore': 'a list of codes to silence', 'error': 'a list of codes to report as errors',
        'analyse': 'a table of settings of nodl analyse (see nodl.system.settings)',
        'definitions': 'a list of definitions folders, relative to this file'}
#: The key of the table of ``nodl analyse`` settings.
ANALYSE_TABLE = 'analyse'
#: The keys of the ``[analyse]`` table of ``nodl.toml`` (``[tool.nodl.analyse]`` in
#: ``pyproject.toml``) and what each holds.
ANALYSE_KEYS = {
    'multiple_publishers_allow': 'a list of topics (fnmatch patterns such as "/tf" or '
                                 '"/diagnostics*") that several nodes may publish',
}


class ConfigError(ValueError):
    """A configuration file that cannot be used; the message is one ``FILE: error: ...`` line."""


def _toml() -> Any:
    try:
        import tomllib
        return tomllib
    except ImportError:  # Python 3.10
        try:
            import tomli
            return tomli
        except ImportError:
            return None


def _read(path: str) -> str:
    with open(path, encoding='utf-8') as stream:
        return stream.read()


def _table(path: str) -> dict[str, Any] | None:
    """The NoDL table of ``path`` (None: a pyproject.toml without ``[tool.nodl]``)."""
    try:
        text = _read(path)
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f'{path}: error: cannot read the configuration: '
                          f'{getattr(exc, "strerror", None) or exc}') from None
    pyproject = os.path.basename(path) == 'pyproject.toml'
    if pyproject and 'tool.nodl' not in text and re.search(r'^\s*nodl\s*=', text, re.M) is None:
        return None  # cheap: no table (not even an inline one under [tool]), no TOML parser
    toml = _toml()
    if toml is None:
        raise ConfigError(f'{path}: error: reading a TOML configuration needs Python 3.11 or '
                          "the 'tomli' package (pip install tomli)")
    try:
        data = toml.loads(text)
    except toml.TOMLDecodeError as exc:
        raise ConfigError(f'{path}: error: invalid TOML: {exc}') from None
    if pyproject:
        tool = data.get('tool')
        table = tool.get('nodl') if isinstance(tool, dict) else None
        return table if isinstance(table, dict) else None
    return dict(data)


def find_config_file(start: str) -> str | None:
    """The configuration file that applies to files in directory ``start``, or None."""
    directory = os.path.abspath(start)
    while True:
        for name in CONFIG_FILES:
            candidate = os.path.join(directory, name)
            if os.path.isfile(candidate) and (name == 'nodl.toml' or _table(candidate) is not None):
                return candidate
        parent = os.path.dirname(directory)
        if parent == directory:
            return None
        directory = parent


def load_config(path: str) -> Overrides:
    """The overrides a configuration file sets (ConfigError if it is not valid)."""
    # The catalogue of codes is read only when a configuration needs it: `nodl validate`'s
    # start-up budget (issue 16) does not pay for it otherwise.
    from nodl.codes import close_codes

    table = _table(path) or {}
    where = path + (' [tool.nodl]' if os.path.basename(path) == 'pyproject.toml' else '')
    values: dict[str, list[str]] = {'ignore': [], 'error': []}
    for key, value in table.items():
        if key not in KEYS:
            hint = did_you_mean(str(key), KEYS) or f'; expected {" or ".join(KEYS)}'
            raise ConfigError(f"{where}: error: unknown key '{key}'{hint}")
        if key == ANALYSE_TABLE:  # checked here, so that a wrong table fails every verb alike
            analyse_table(value, where)
            continue
        if key == 'definitions':  # folders, not codes: read by definitions_of
            _folder_list(value, where)
            continue
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise ConfigError(f"{where}: error: '{key}' must be {KEYS[key]} "
                              '(for example ["NODL216"])')
        codes, unknown = parse_code_list(value)
        if unknown:
            close = close_codes(unknown[0])
            hint = f"; did you mean '{close[0]}'?" if close else ' (see docs/diagnostics.md)'
            raise ConfigError(f"{where}: error: unknown code '{unknown[0]}' in '{key}'{hint}")
        values[key] = codes
    both = set(values['ignore']) & set(values['error'])
    if both:
        raise ConfigError(f"{where}: error: {sorted(both)[0]} is both ignored and an error; "
                          'keep it in one list')
    return Overrides(values['ignore'], values['error'])


def analyse_table(table: object, where: str) -> dict[str, tuple[str, ...]]:
    """The settings an ``analyse`` table gives, by key of :data:`ANALYSE_KEYS` (ConfigError
    naming ``where`` if the table is wrong)."""
    if not isinstance(table, dict):
        raise ConfigError(f"{where}: error: '{ANALYSE_TABLE}' must be a table")
    for key, value in table.items():
        if key not in ANALYSE_KEYS:
            hint = did_you_mean(str(key), ANALYSE_KEYS) or f'; expected {", ".join(ANALYSE_KEYS)}'
            raise ConfigError(f"{where}: error: unknown key '{ANALYSE_TABLE}.{key}'{hint}")
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise ConfigError(f"{where}: error: '{ANALYSE_TABLE}.{key}' must be {ANALYSE_KEYS[key]}")
    return {key: tuple(value) for key, value in table.items()}


def _folder_list(value: Any, where: str) -> list[str]:
    if not isinstance(value, list) or not all(isinstance(v, str) and v.strip() for v in value):
        raise ConfigError(f"{where}: error: 'definitions' must be {KEYS['definitions']} "
                          '(for example ["nodl_definitions"])')
    return list(value)


def definitions_of(path: str) -> list[str]:
    """The definitions folders the configuration file ``path`` lists, each relative to the
    file's folder made a path from there, in order (ConfigError if the list is not valid)."""
    table = _table(path) or {}
    where = path + (' [tool.nodl]' if os.path.basename(path) == 'pyproject.toml' else '')
    if 'definitions' not in table:
        return []
    base = os.path.dirname(path)
    return [os.path.normpath(os.path.join(base, os.path.expanduser(folder)))
            for folder in _folder_list(table['definitions'], where)]


class ConfigCache:
    """Finds and loads configurations once per directory (many files share one)."""

    def __init__(self) -> None:
        self._by_directory: dict[str, Overrides] = {}
        self._by_file: dict[str, Overrides] = {}

    def overrides_for(self, file: str) -> Overrides:
        """The overrides of the configuration that applies to ``file`` (empty if none)."""
        directory = os.path.dirname(os.path.abspath(file))
        cached = self._by_directory.get(directory)
        if cached is not None:
            return cached
        config = find_config_file(directory)
        if config is None:
            result = Overrides()
        else:
            result = self._by_file.get(config) or load_config(config)
            self._by_file[config] = result
        self._by_directory[directory] = result
        return result


def overrides_for(file: str) -> Overrides:
    """The overrides of the configuration that applies to ``file`` (empty if none)."""
    return ConfigCache().overrides_for(file)
