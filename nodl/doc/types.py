"""The appendix of a node page: one field table per interface type its endpoints use.

Each type is read from the installed packages (or source folders) by the
interface-type layer (:mod:`nodl.interface_types`): fields with their
IDL, C++ and Python types (as the installed rosidl generators give them),
defaults, comments and units, then constants.  A service's request and
response, an action's goal, result and feedback each get a table; every
nested message type gets its own, linked from the field that holds it.

A type that cannot be read is a finding, never a crash: its section says
the table is unavailable and what to install (NODL270, NODL271, NODL272).
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

from nodl.diagnostics import Diagnostic, Severity
from nodl.doc.blocks import (
    Block,
    Heading,
    Inline,
    Link,
    Literal,
    Note,
    Paragraph,
    Table,
    label,
)
from nodl.interface_types.mapping import cpp_type, python_type
from nodl.interface_types.resolve import parse_type_name
from nodl.interface_types.tree import (
    ActionType,
    InterfaceFileError,
    MessageType,
    ServiceType,
    UnknownTypeError,
    load_type,
)

if TYPE_CHECKING:
    from typing import Any

    from nodl.composition.entities import Location
    from nodl.interface_types.resolve import InterfaceIndex
    from nodl.interface_types.tree import Field, FieldType, MessageType

__all__ = ['type_label', 'type_appendix', 'FIELD_COLUMNS']

#: The columns of a field table.
FIELD_COLUMNS = ('Field', 'IDL type', 'C++ type', 'Python type', 'Default', 'Comment')


def type_label(page: str, type_name: str) -> str:
    """The explicit target of a type's field table on the page whose label is ``page``
    (targets are global to a Sphinx project: each page has its own)."""
    return label(page, 'type', type_name)


def _value(value: Any) -> str:
    if value is None:
        return ''
    if isinstance(value, bool):
        return 'true' if value else 'false'
    return str(value)


def _comment(field: Field | Any) -> str:
    text = ' '.join(line.strip() for line in (field.comment or '').splitlines() if line.strip())
    unit = getattr(field, 'unit', '')
    return f'{text} [{unit}]'.strip() if unit else text


@functools.lru_cache(maxsize=4096)  # every page that uses a type shows the same field types
def _language_types(field_type: FieldType) -> tuple[Inline, Inline]:
    """The C++ and Python type cells of a field type."""
    return Literal(cpp_type(field_type)), Literal(python_type(field_type))


def _field_rows(page: str, message: MessageType, pending: list[str]) -> tuple[tuple[tuple[Inline, ...], ...], ...]:
    rows: list[tuple[tuple[Inline, ...], ...]] = []
    for field in message.fields:
        kind: tuple[Inline, ...] = (Literal(field.type.idl),)
        if field.type.nested:
            if field.type.base not in pending:
                pending.append(field.type.base)
            kind = (Link(field.type.idl, type_label(page, field.type.base)),)
        cpp, python = _language_types(field.type)
        rows.append(((Literal(field.name),), kind, (cpp,), (python,), (_value(field.default),),
                     (_comment(field),)))
    return tuple(rows)


def _message_blocks(page: str, message: MessageType, level: int, title: str | None,
                    pending: list[str]) -> list[Block]:
    blocks: list[Block] = []
    if title is not None:
        blocks.append(Heading(level, title, type_label(page, message.name)))
    comment = ' '.join(line.strip() for line in message.comment.splitlines() if line.strip())
    if comment:
        blocks.append(Paragraph((comment,)))
    if message.fields:
        blocks.append(Table(FIELD_COLUMNS, _field_rows(page, message, pending)))
    else:
        blocks.append(Paragraph(('No fields.',)))
    if message.constants:
        blocks.append(Table(('Constant', 'IDL type', 'Value', 'Comment'), tuple(
            ((Literal(c.name),), (Literal(c.type.idl),), (Literal(_value(c.value)),), (_comment(c),))
            for c in message.constants)))
    return blocks


def _unavailable(index: InterfaceIndex, type_name: str, where: Location | None
                 ) -> tuple[str, Diagnostic]:
    file, line, column = (where.file, where.line, where.column) if where is not None else ('', 0, 0)
    try:
        parsed = parse_type_name(type_name)
        load_type(index, type_name)
    except ValueError:
        text = f"'{type_name}' is not a full interface type name: no field table"
        return text, Diagnostic(Severity.WARNING, text, file=file, line=line, column=column,
                                code='NODL271')
    except InterfaceFileError as exc:
        text = (f'the field table of {type_name} is unavailable: its file {exc.file} cannot be read '
                f'({exc.message}); reinstall the package {parsed.package}')
        return text, Diagnostic(Severity.WARNING, text, file=file, line=line, column=column,
                                code='NODL272')
    except UnknownTypeError:
        if index.package(parsed.package) is None:
            text = (f'the field table of {type_name} is unavailable: the package {parsed.package} '
                    'is not installed; install it (for example: apt install '
                    f"ros-$ROS_DISTRO-{parsed.package.replace('_', '-')}) and build the pages again")
        else:
            text = (f'the field table of {type_name} is unavailable: the installed package '
                    f'{parsed.package} defines no such {parsed.namespace} type; check the type name')
        return text, Diagnostic(Severity.WARNING, text, file=file, line=line, column=column,
                                code='NODL270' if index.package(parsed.package) is None else 'NODL271')
    raise AssertionError('the type loads')  # pragma: no cover  (called only when it does not)


def type_appendix(index: InterfaceIndex, page: str, used: dict[str, Location | None],
                  level: int = 2) -> tuple[list[Block], list[Diagnostic]]:
    """The field tables, on the page labelled ``page``, of the types ``used`` (type name -> where it
    is first used, for the findings), in the order given, then the nested types they hold; and the
    findings."""
    blocks: list[Block] = []
    findings: list[Diagnostic] = []
    pending = list(used)
    done: set[str] = set()
    while pending:
        name = pending.pop(0)
        if name in done:
            continue
        done.add(name)
        blocks.append(Heading(level + 1, name, type_label(page, name)))
        try:
            loaded = load_type(index, name)
        except (ValueError, UnknownTypeError, InterfaceFileError):
            text, finding = _unavailable(index, name, used.get(name))
            blocks.append(Note('warning', (text,)))
            findings.append(finding)
            continue
        nested: list[str] = []
        if isinstance(loaded, MessageType):
            blocks += _message_blocks(page, loaded, level + 2, None, nested)
        elif isinstance(loaded, ServiceType):
            for title, part in (('Request', loaded.request), ('Response', loaded.response)):
                blocks += _message_blocks(page, part, level + 2, f'{name}: {title}', nested)
        elif isinstance(loaded, ActionType):
            for title, part in (('Goal', loaded.goal), ('Result', loaded.result),
                                ('Feedback', loaded.feedback)):
                blocks += _message_blocks(page, part, level + 2, f'{name}: {title}', nested)
        pending += [n for n in nested if n not in done and n not in pending]
    return blocks, findings

