"""Former path of :mod:`nodl.system.settings` (the ``analyse`` table of a configuration)."""

from __future__ import annotations

from nodl.system.settings import TABLE, load_settings, settings_from_table

__all__ = ['TABLE', 'load_settings', 'settings_from_table']
