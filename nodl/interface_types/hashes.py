"""RIHS01 type hashes and type descriptions, from rosidl's type-description generator.

The description of a type is what ``rosidl_generator_type_description`` builds
at a package's build (and what a running node serves on
``~/get_type_description``): the type's fields and, sorted, every type it
references.  Its hash (``RIHS01_<sha256>``) is what the middleware reports
for each endpoint.  Here both are computed from the interface files the
index finds (the generator's own functions do the serializing and hashing),
so a type is hashed as it is installed now, or as a package's source
defines it before it is built.
"""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

    from nodl.interface_types.resolve import InterfaceIndex, TypeName

from nodl.interface_types.tree import UnknownTypeError, load_idl

__all__ = ['type_description', 'type_hash', 'installed_hash', 'description_differences',
           'field_type_name']


def _individual(index: InterfaceIndex, package: str, namespace: str, base: str) -> dict[str, Any]:
    """Every individual description one interface file defines (a service's or an action's
    parts included), by full type name."""
    key = ('individual', package, namespace, base)
    if key in index.cache:
        cached: dict[str, Any] = index.cache[key]
        return cached
    import rosidl_generator_type_description as generator
    from rosidl_parser.definition import Action, Message, Service

    content = load_idl(index, package, namespace, base)
    interfaces: dict[str, Any] = {}
    for element in content.elements:
        if isinstance(element, Message):
            generator.add_msg(element, interfaces)
        elif isinstance(element, Service):
            generator.add_srv(element, interfaces)
        elif isinstance(element, Action):
            generator.add_action(element, interfaces)
    found = {name: generator.serialize_individual_type_description(i.namespaced_type, i.members)
             for name, i in interfaces.items()}
    index.cache[key] = found
    return found


def type_description(index: InterfaceIndex, name: TypeName | str) -> dict[str, Any]:
    """The full type description of ``name`` (``type_description`` and the sorted
    ``referenced_type_descriptions``), as rosidl's generator writes it in the
    installed ``.json`` file.  UnknownTypeError / InterfaceFileError as
    :func:`nodl.interface_types.tree.load_type`."""
    import rosidl_generator_type_description as generator

    text = str(name)
    lookup: dict[str, Any] = {}
    expanded: set[str] = set()
    pending = [text]
    while pending:
        current = pending.pop()
        if current in expanded:
            continue
        expanded.add(current)
        parts = current.split('/')
        if len(parts) != 3 or not all(parts):
            raise UnknownTypeError(current)
        if current not in lookup:
            lookup.update(_individual(index, parts[0], parts[1], parts[2].split('_', 1)[0]))
        if current not in lookup:
            raise UnknownTypeError(current)
        pending += [f['type']['nested_type_name'] for f in lookup[current]['fields']
                    if f['type']['nested_type_name']]
    description: dict[str, Any] = generator.extract_full_type_description(text, lookup)
    return description


def type_hash(index: InterfaceIndex, name: TypeName | str) -> str:
    """The RIHS01 hash of ``name`` computed from its interface files (once per index)."""
    key = ('hash', str(name))
    if key not in index.cache:
        import rosidl_generator_type_description as generator

        index.cache[key] = generator.calculate_type_hash(type_description(index, name))
    found: str = index.cache[key]
    return found


def installed_hash(index: InterfaceIndex, name: TypeName | str) -> str | None:
    """The hash the package's build wrote in ``<share>/<ns>/<Type>.json`` (None when the
    package ships no such file, or it cannot be read)."""
    parts = str(name).split('/')
    package = index.package(parts[0]) if len(parts) == 3 else None
    if package is None or package.origin != 'installed':
        return None
    path = os.path.join(package.share, parts[1], parts[2].split('_', 1)[0] + '.json')
    try:
        with open(path, encoding='utf-8') as handle:
            data = json.load(handle)
        for entry in data['type_hashes']:
            if entry['type_name'] == str(name):
                return str(entry['hash_string'])
    except (OSError, ValueError, KeyError, TypeError):
        return None
    return None


def field_type_name(field_type: dict[str, Any]) -> str:
    """A described field type in words: ``string``, ``float64[3]``, ``std_msgs/msg/Header[<=5]``."""
    from rosidl_generator_type_description import FIELD_TYPE_ID_TO_NAME

    type_id = int(field_type.get('type_id', 0))
    name = str(FIELD_TYPE_ID_TO_NAME.get(type_id, f'type {type_id}')).lower()
    base = field_type.get('nested_type_name') or name.removeprefix('field_type_')
    for suffix, shape in (('_unbounded_sequence', '[]'), ('_bounded_sequence', '[<={capacity}]'),
                          ('_array', '[{capacity}]')):
        if base.endswith(suffix):
            base = base[:-len(suffix)]
            return base + shape.format(capacity=field_type.get('capacity', ''))
        if name.endswith(suffix):
            return base + shape.format(capacity=field_type.get('capacity', ''))
    if field_type.get('string_capacity'):
        base += f'<={field_type["string_capacity"]}'
    return str(base)


def description_differences(installed: dict[str, Any], running: dict[str, Any]) -> list[str]:
    """What differs between two full type descriptions, field by field, in words.

    Each line names the type and the field: present in one only, or of another
    type (its IDL type, bounds or nested type).  Empty when they agree on every
    field (the hash may still differ, e.g. on a field's order).
    """
    def by_type(description: dict[str, Any]) -> dict[str, list[dict[str, Any]]]:
        out = {description['type_description']['type_name']:
               list(description['type_description']['fields'])}
        for referenced in description.get('referenced_type_descriptions', ()):
            out[referenced['type_name']] = list(referenced['fields'])
        return out

    ours, theirs = by_type(installed), by_type(running)
    lines: list[str] = []
    for type_name in sorted(set(ours) | set(theirs)):
        if type_name not in theirs:
            lines.append(f'{type_name} is used by the installed definition only')
            continue
        if type_name not in ours:
            lines.append(f'{type_name} is used by the running node only')
            continue
        mine = {f['name']: f for f in ours[type_name]}
        other = {f['name']: f for f in theirs[type_name]}
        for field in ours[type_name]:
            if field['name'] not in other:
                lines.append(f"{type_name}: field '{field['name']}' "
                             f"({field_type_name(field['type'])}) is in the installed definition, "
                             "not in the running node's")
            elif _shape(field['type']) != _shape(other[field['name']]['type']):
                lines.append(f"{type_name}: field '{field['name']}' is "
                             f"{field_type_name(field['type'])} in the installed definition, "
                             f"{field_type_name(other[field['name']]['type'])} in the running node")
        for field in theirs[type_name]:
            if field['name'] not in mine:
                lines.append(f"{type_name}: field '{field['name']}' "
                             f"({field_type_name(field['type'])}) is in the running node's "
                             "definition, not in the installed one")
        if not lines and [f['name'] for f in ours[type_name]] != [f['name'] for f in theirs[type_name]]:
            lines.append(f'{type_name}: the fields are in another order')
    return lines


def _shape(field_type: dict[str, Any]) -> tuple[Any, ...]:
    return (int(field_type.get('type_id', 0)), int(field_type.get('capacity', 0)),
            int(field_type.get('string_capacity', 0)), field_type.get('nested_type_name') or '')
