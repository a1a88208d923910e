"""What the runtime reports about a definition it cannot run."""

from __future__ import annotations

__all__ = ['RuntimeDefinitionError']


class RuntimeDefinitionError(Exception):
    """The definition cannot run as given: a type not installed, a callback missing, a parameter
    required or invalid.  The message says what and what to do (one problem per line)."""
