"""Validation: the JSON Schemas plus the checks a schema cannot express.

Checks yield :class:`~nodl.diagnostics.Diagnostic` objects and never
raise for a problem in a document.
"""

from nodl.validation.engine import validate_data
from nodl.validation.kinds import Kind, detect_kind

__all__ = ['Kind', 'detect_kind', 'validate_data']
