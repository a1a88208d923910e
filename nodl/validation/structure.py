"""Structural validation: the shipped JSON Schemas, compiled into checks.

The schema files are the single source of truth for structure.  This module
interprets the subset of JSON Schema (draft 7) they use and turns each
failure into a diagnostic that says what was expected, instead of the
generic wording of a general-purpose validator:

* an unknown key names the closest valid one (``did you mean ...?``);
* an enum lists the allowed values;
* ``anyOf`` picks the branch that fits the value's kind and reports that
  branch's problems, or says which kinds were expected;
* a ``format`` the toolkit knows (ROS names, type names, parameter types,
  validator names, references) is checked by Python code that can say which
  rule a value breaks; the schema's approximate ``pattern`` is then only for
  editors.

Two extension keywords, ignored by other validators, refine the wording:
``x-nodl-key-hints`` (why a particular unknown key is wrong) and
``x-nodl-message`` (replaces the message of a failing subschema).

Schemas are compiled once into nested closures, which keeps validation well
below the cost of parsing the YAML.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

from nodl.diagnostics import Diagnostic, DocPath, Severity
from nodl.schemas import load_schema_file
from nodl.wording import described, did_you_mean, kind_of, one_of, show, subject

__all__ = ['Check', 'FormatCheck', 'SchemaCompiler']

#: A compiled check: appends diagnostics for ``value`` found at ``path``.
if TYPE_CHECKING:
    Check = Callable[[Any, DocPath, list[Diagnostic]], None]
else:
    Check = object
#: A format checker has the same shape as a compiled check.
FormatCheck = Check

_TYPE_TESTS: dict[str, Callable[[Any], bool]] = {
    'object': lambda v: isinstance(v, dict),
    'array': lambda v: isinstance(v, list),
    'string': lambda v: isinstance(v, str),
    'integer': lambda v: isinstance(v, int) and not isinstance(v, bool),
    'number': lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    'boolean': lambda v: isinstance(v, bool),
    'null': lambda v: v is None,
}
_TYPE_WORDS = {
    'object': 'a mapping', 'array': 'a list', 'string': 'a string', 'integer': 'an integer',
    'number': 'a number', 'boolean': 'a boolean (true or false)', 'null': 'null',
}
_ANNOTATIONS = frozenset({
    '$schema', '$id', 'title', 'description', 'default', 'examples', 'definitions',
    'x-nodl-key-hints', 'x-nodl-message', '$comment',
})


def _err(message: str, path: DocPath, code: str, anchor: str = 'value') -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, path, anchor=anchor, code=code)


class SchemaCompiler:
    """Compiles schema files into checks; references are resolved lazily."""

    def __init__(self, formats: dict[str, FormatCheck]) -> None:
        self.formats = formats
        self._compiled: dict[tuple[str, str], Check] = {}

    def compile_ref(self, file_name: str, pointer: str = '') -> Check:
        """The check for ``file_name#pointer`` (``''`` is the whole file)."""
        key = (file_name, pointer)
        if key not in self._compiled:
            cell: list[Check] = []
            # Placeholder first, so recursive references terminate.
            self._compiled[key] = lambda v, p, o: cell[0](v, p, o)
            schema: Any = load_schema_file(file_name)
            for part in [p for p in pointer.split('/') if p]:
                schema = schema[part]
            cell.append(self.compile(schema, file_name))
            self._compiled[key] = cell[0]
        return self._compiled[key]

    def _ref(self, ref: str, file_name: str) -> Check:
        target_file, _, pointer = ref.partition('#')
        return self.compile_ref(target_file or file_name, pointer)

    # -- compilation -------------------------------------------------------

    def compile(self, schema: dict[str, Any], file_name: str) -> Check:
        """Compile one schema object found in ``file_name``."""
        fmt = schema.get('format')
        if fmt in self.formats:
            return self.formats[fmt]
        if '$ref' in schema:
            return self._ref(schema['$ref'], file_name)

        checks: list[Check] = []
        types = schema.get('type')
        type_check = self._type(types) if types is not None else None
        if 'const' in schema:
            checks.append(self._const(schema['const']))
        if 'enum' in schema:
            checks.append(self._enum(schema['enum']))
        if any(k in schema for k in ('properties', 'required', 'additionalProperties',
                                      'propertyNames', 'patternProperties')):
            checks.append(self._object(schema, file_name))
        if any(k in schema for k in ('items', 'minItems', 'maxItems')):
            checks.append(self._array(schema, file_name))
        if 'minimum' in schema:
            checks.append(self._minimum(schema['minimum']))
        if 'minLength' in schema:
            checks.append(self._min_length(schema['minLength']))
        if 'pattern' in schema:
            checks.append(self._pattern(schema['pattern']))
        for keyword in ('anyOf', 'oneOf'):
            if keyword in schema:
                checks.append(self._any_of(schema[keyword], schema.get('description'), file_name,
                                           exclusive=keyword == 'oneOf'))
        for sub in schema.get('allOf', ()):
            checks.append(self.compile(sub, file_name))
        if 'if' in schema:
            checks.append(self._if_then(schema, file_name))
        unknown = set(schema) - _ANNOTATIONS - {
            'format', 'type', 'const', 'enum', 'properties', 'required', 'additionalProperties',
            'propertyNames', 'patternProperties', 'items', 'minItems', 'maxItems', 'minimum',
            'minLength', 'pattern', 'anyOf', 'oneOf', 'allOf', 'if', 'then', 'else'}
        if unknown:
            raise ValueError(f'schema keyword(s) not supported by the validator: {sorted(unknown)}')

        override = schema.get('x-nodl-message')
        body = _sequence(checks)
        if type_check is not None:
            body = _guarded(type_check, body)
        if override:
            return _override_message(body, override)
        return body

    def _type(self, types: str | list[str]) -> Check:
        names = [types] if isinstance(types, str) else list(types)
        tests = [_TYPE_TESTS[n] for n in names]
        expected = one_of(_TYPE_WORDS[n] for n in names)

        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            for test in tests:
                if test(value):
                    return
            out.append(_err(f'{subject(path)} must be {expected}, not {described(value)}', path, 'NODL103'))
        return check

    def _const(self, const: Any) -> Check:
        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            if not (value == const and type(value) is type(const)):
                out.append(_err(f'{subject(path)} must be {show(const)}, not {show(value)}', path, 'NODL104'))
        return check

    def _enum(self, options: list[Any]) -> Check:
        allowed = options
        words = [o for o in options if isinstance(o, str)]

        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            for option in allowed:
                if value == option and type(value) is type(option):
                    return
            out.append(_err(
                f'invalid value {show(value)} for {subject(path)}; expected one of: '
                f'{", ".join(map(str, allowed))}{did_you_mean(value, words)}', path, 'NODL104'))
        return check

    def _object(self, schema: dict[str, Any], file_name: str) -> Check:
        properties = {name: self.compile(sub, file_name)
                      for name, sub in schema.get('properties', {}).items()}
        required = list(schema.get('required', ()))
        additional = schema.get('additionalProperties', True)
        additional_check = (self.compile(additional, file_name)
                            if isinstance(additional, dict) else None)
        patterns = [(re.compile(p), self.compile(sub, file_name))
                    for p, sub in schema.get('patternProperties', {}).items()]
        names_check = (self.compile(schema['propertyNames'], file_name)
                       if 'propertyNames' in schema else None)
        hints: dict[str, str] = schema.get('x-nodl-key-hints', {})
        known = list(properties)

        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            if not isinstance(value, dict):
                return
            for name in required:
                if name not in value:
                    out.append(_err(f"missing required key '{name}'"
                                    f"{' in ' + subject(path) if path else ''}", path, 'NODL102', 'key'))
            for key, item in value.items():
                if not isinstance(key, str):
                    out.append(_err(f'key {show(key)} must be a string, not {kind_of(key)}',
                                    path + (key,), 'NODL103', 'key'))
                    continue
                child = path + (key,)
                if names_check is not None:
                    _at_key(names_check, key, child, out)
                sub = properties.get(key)
                if sub is not None:
                    sub(item, child, out)
                    continue
                matched = False
                for regex, pattern_check in patterns:
                    if regex.search(key):
                        matched = True
                        pattern_check(item, child, out)
                if matched:
                    continue
                if additional is False:
                    if key in hints:
                        out.append(_err(f'unknown key {show(key)}: {hints[key]}', child, 'NODL101', 'key'))
                    else:
                        suggestion = did_you_mean(key, known)
                        if not suggestion and known:
                            suggestion = f'; expected one of: {", ".join(known)}'
                        out.append(_err(f'unknown key {show(key)}{suggestion}', child, 'NODL101', 'key'))
                elif additional_check is not None:
                    additional_check(item, child, out)
        return check

    def _array(self, schema: dict[str, Any], file_name: str) -> Check:
        items = schema.get('items')
        item_check = self.compile(items, file_name) if isinstance(items, dict) else None
        low = schema.get('minItems')
        high = schema.get('maxItems')

        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            if not isinstance(value, list):
                return
            count = len(value)
            if low is not None and count < low:
                out.append(_err(f'{subject(path)} needs at least {low} item{"s" * (low != 1)}, '
                                f'got {count}', path, 'NODL105'))
            if high is not None and count > high:
                out.append(_err(f'{subject(path)} takes at most {high} item{"s" * (high != 1)}, '
                                f'got {count}', path, 'NODL105'))
            if item_check is not None:
                for index, item in enumerate(value):
                    item_check(item, path + (index,), out)
        return check

    def _minimum(self, minimum: float) -> Check:
        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            if _TYPE_TESTS['number'](value) and value < minimum:
                out.append(_err(f'{subject(path)} must be at least {minimum}, got {show(value)}', path,
                                'NODL105'))
        return check

    def _min_length(self, minimum: int) -> Check:
        expected = ('must not be empty' if minimum == 1 else
                    f'must be at least {minimum} characters long')

        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            if isinstance(value, str) and len(value) < minimum:
                out.append(_err(f'{subject(path)} {expected}', path, 'NODL105'))
        return check

    def _pattern(self, pattern: str) -> Check:
        regex = re.compile(pattern)

        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            if isinstance(value, str) and not regex.search(value):
                out.append(_err(f'{show(value)} does not match the pattern {pattern} '
                                f'required for {subject(path)}', path, 'NODL106'))
        return check

    def _any_of(self, branches: list[dict[str, Any]], description: str | None,
                file_name: str, exclusive: bool = False) -> Check:
        compiled = [(self._admits(b, file_name), self.compile(b, file_name)) for b in branches]
        expected = (description.rstrip('.') if description else
                    one_of(self._summary(b, file_name) for b in branches))

        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            fitting = [c for admits, c in compiled if admits(value)]
            if not fitting:
                out.append(_err(f'{subject(path)} must be {_lower_first(expected)}; '
                                f'got {described(value)}', path, 'NODL107'))
                return
            first_errors: list[Diagnostic] | None = None
            passed = 0
            for branch in fitting:
                errors: list[Diagnostic] = []
                branch(value, path, errors)
                if not errors:
                    if not exclusive:
                        return
                    passed += 1
                elif first_errors is None:
                    first_errors = errors
            if passed == 1:
                return
            if passed > 1:  # oneOf: exactly one branch may match
                out.append(_err(f'{subject(path)} fits more than one of the allowed forms '
                                f'({_lower_first(expected)}); it must fit exactly one', path,
                                'NODL107'))
                return
            if description:
                out.append(_err(f'invalid {subject(path)}: expected {_lower_first(expected)}; '
                                f'got {show(value)}', path, 'NODL107'))
            else:
                out.extend(first_errors or ())
        return check

    def _if_then(self, schema: dict[str, Any], file_name: str) -> Check:
        condition = self.compile(schema['if'], file_name)
        then = self.compile(schema['then'], file_name) if 'then' in schema else None
        otherwise = self.compile(schema['else'], file_name) if 'else' in schema else None

        def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
            probe: list[Diagnostic] = []
            condition(value, path, probe)
            branch = then if not probe else otherwise
            if branch is not None:
                branch(value, path, out)
        return check

    # -- helpers for anyOf -------------------------------------------------

    def _resolve(self, schema: dict[str, Any], file_name: str) -> tuple[dict[str, Any], str]:
        while '$ref' in schema and 'format' not in schema:
            target_file, _, pointer = schema['$ref'].partition('#')
            file_name = target_file or file_name
            schema = load_schema_file(file_name)
            for part in [p for p in pointer.split('/') if p]:
                schema = schema[part]
        return schema, file_name

    def _admits(self, schema: dict[str, Any], file_name: str) -> Callable[[Any], bool]:
        resolved, _ = self._resolve(schema, file_name)
        types = resolved.get('type')
        if types is None:
            return lambda value: True
        names = [types] if isinstance(types, str) else list(types)
        tests = [_TYPE_TESTS[n] for n in names]
        return lambda value: any(t(value) for t in tests)

    def _summary(self, schema: dict[str, Any], file_name: str) -> str:
        resolved, _ = self._resolve(schema, file_name)
        types = resolved.get('type')
        if types is None:
            return 'a valid value'
        names = [types] if isinstance(types, str) else list(types)
        return one_of(_TYPE_WORDS[n] for n in names)


def _lower_first(text: str) -> str:
    return text[:1].lower() + text[1:] if text[:2] != text[:2].upper() else text


def _sequence(checks: list[Check]) -> Check:
    if not checks:
        return lambda value, path, out: None
    if len(checks) == 1:
        return checks[0]

    def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
        for c in checks:
            c(value, path, out)
    return check


def _guarded(type_check: Check, body: Check) -> Check:
    def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
        before = len(out)
        type_check(value, path, out)
        if len(out) == before:
            body(value, path, out)
    return check


def _at_key(check: Check, key: str, path: DocPath, out: list[Diagnostic]) -> None:
    """Run a ``propertyNames`` check: what it finds is about the key, not its value."""
    found: list[Diagnostic] = []
    check(key, path, found)
    # (an anchor on a character of the key stays on that character)
    out.extend(d if d.anchor == 'key-char' else d.replace(anchor='key') for d in found)


def _override_message(body: Check, message: str) -> Check:
    def check(value: Any, path: DocPath, out: list[Diagnostic]) -> None:
        errors: list[Diagnostic] = []
        body(value, path, errors)
        if errors:
            # The wording is the schema's; the code is that of the first failure it replaces.
            out.append(_err(message, path, errors[0].code, errors[0].anchor))
    return check
