"""Names and descriptions hold no control characters and no Trojan Source bidi controls.

A description or a name is shown in terminals, generated code, documentation
and reports.  A control character there can move the cursor or recolour a
terminal, and a bidirectional override (U+202A-202E, U+2066-2069) can make
generated code or a review read differently from what it is.  Both are
errors, placed at the offending character: NODL219 for a C0 or C1 control
character (tab and newline are ordinary text), NODL220 for a bidi control.
LRM and RLM (U+200E, U+200F) stay allowed for right-to-left text.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.text_safety import describe_character, first_unsafe, is_bidi_control

__all__ = ['CONTROL_CHARACTER', 'BIDI_CONTROL', 'TEXT_FIELDS', 'unsafe_problem', 'unsafe_text', 'check_text',
           'check_text_fields']

#: The code of a control character in a name or description.
CONTROL_CHARACTER = 'NODL219'
#: The code of a bidi control in a name or description.
BIDI_CONTROL = 'NODL220'
#: The free-text fields of a parameter, interface or endpoint definition.
TEXT_FIELDS = ('description', 'additional_constraints')


def unsafe_problem(value: str, what: str) -> tuple[bool, str] | None:
    """``(is_bidi, message)`` for the first unsafe character of ``value`` (``what`` says what
    it is: 'description', 'node name'), or None when it holds none: the wording every check of
    unsafe text shares (definitions here, launch files in :mod:`nodl.launch.text_checks`)."""
    index = first_unsafe(value)
    if index < 0:
        return None
    char = value[index]
    if is_bidi_control(char):
        return True, (f'{what} holds {describe_character(char)} (character {index + 1}), a '
                      'bidirectional control that makes text read differently from what it is '
                      '(Trojan Source); remove it (U+200E/U+200F marks are allowed for '
                      'right-to-left text)')
    return False, (f'{what} holds {describe_character(char)} (character {index + 1}), a control '
                   'character that terminals and generated files would obey or break on; remove '
                   'it (tab and newline are allowed)')


def unsafe_text(value: str, what: str, path: DocPath, anchor: str = 'value') -> Diagnostic | None:
    """The error for ``value`` (``what`` says what it is: 'description', 'parameter name') if it
    holds an unsafe character, else None.  The anchor ``value-char`` (or ``key-char``) asks the
    document to place it at that character, not at the start of the value."""
    found = unsafe_problem(value, what)
    if found is None:
        return None
    bidi, message = found
    return Diagnostic(Severity.ERROR, message, path, anchor=f'{anchor}-char',
                      code=BIDI_CONTROL if bidi else CONTROL_CHARACTER)


def check_text(value: Any, what: str, path: DocPath, out: list[Diagnostic],
               anchor: str = 'value') -> bool:
    """Append the error for an unsafe ``value`` (see :func:`unsafe_text`); True if there was one.
    A value that is not a string is left to the structural checks."""
    if not isinstance(value, str):
        return False
    found = unsafe_text(value, what, path, anchor)
    if found is None:
        return False
    out.append(found)
    return True


def check_text_fields(data: Any, path: DocPath, out: list[Diagnostic]) -> None:
    """Check the free-text fields (:data:`TEXT_FIELDS`) of the definition ``data`` at ``path``."""
    if not isinstance(data, dict):
        return
    for field in TEXT_FIELDS:
        if field in data:
            check_text(data[field], field.replace('_', ' '), path + (field,), out)
