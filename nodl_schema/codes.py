"""The catalogue of diagnostic codes: every code the toolkit reports, once.

A code is stable: once released it keeps its meaning, so that users can look
it up, silence it (``--ignore``) or promote it (``--error``).  Codes are
grouped by the stage that reports them:

=========  ===============================================================
range      stage
=========  ===============================================================
NODL0xx    reading files: I/O, encodings, YAML/JSON/XML syntax, limits
NODL1xx    structure (the JSON Schemas): keys, types, required values
NODL2xx    semantic rules: ROS names, interface types, parameters,
           validators, QoS, duplicates, descriptions, references
NODL3xx    composition: bases, mixins, overrides, client libraries
NODL4xx    live: drift between a definition and a running node
NODL5xx    system analysis: launch files, instances, connections
NODL6xx    SROS 2 policies
NODL7xx    parameter files and code generation
NODL8xx    dialects and conversion: legacy XML, ``include``, generate_parameter_library
=========  ===============================================================

Each entry: code -> (default severity, one-line explanation).  A test keeps
this table and the code in step (every code used is listed here, and every
code listed here is used).
"""

from __future__ import annotations

__all__ = ['CODES', 'explain']

#: code -> (default severity, one-line explanation).
CODES: dict[str, tuple[str, str]] = {
}


def explain(code: str) -> str:
    """The one-line explanation of ``code`` (KeyError for an unknown code)."""
    return CODES[code][1]
