"""Validation: the JSON Schemas plus the checks a schema cannot express.

Checks yield :class:`~nodl_schema.diagnostics.Diagnostic` objects and never
raise for a problem in a document.
"""

from nodl_schema.validation.engine import validate_data
from nodl_schema.validation.kinds import Kind, detect_kind

__all__ = ['Kind', 'detect_kind', 'validate_data']
