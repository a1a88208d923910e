"""The typed tree of an interface type, read with ROS's own parsers.

An installed type that has a ``.msg``, ``.srv`` or ``.action`` file is read
from it by rosidl_adapter's parser alone (the ``.idl`` installed beside it is
generated from it by rosidl_adapter, so the tree is the same, at a fraction of
the cost of rosidl_parser's grammar).  A type installed as ``.idl`` alone is
read by rosidl_parser; a package's source ``.msg``/``.srv``/``.action`` is
first turned into IDL by rosidl_adapter, as ``rosidl_generate_interfaces``
does, and parsed as IDL, as its build will.  Each type becomes a
:class:`MessageType`, :class:`ServiceType` or :class:`ActionType`; nested
types are expanded.  Every file is read once per index (one per run), and
only when a type it defines is asked for.

A file that cannot be read or parsed raises :class:`InterfaceFileError`,
placed at the line (and column) of the problem when the parser says where.
"""

from __future__ import annotations

import contextlib
import io
import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

    from nodl.interface_types.resolve import InterfaceIndex, TypeName

__all__ = ['FieldType', 'Field', 'Constant', 'MessageType', 'ServiceType', 'ActionType',
           'InterfaceFileError', 'UnknownTypeError', 'load_type', 'load_idl']


class InterfaceFileError(Exception):
    """An interface file that cannot be read or parsed, with where the problem is."""

    def __init__(self, message: str, file: str, line: int = 0, column: int = 0) -> None:
        super().__init__(message)
        self.message = message
        self.file = file
        self.line = line
        self.column = column

    def __str__(self) -> str:
        where = ':'.join(str(p) for p in (self.file, self.line, self.column) if p)
        return f'{where}: {self.message}'


class UnknownTypeError(LookupError):
    """A type name that the index does not define (its package or the type itself)."""


class FieldType:
    """The IDL type of a field or constant.

    ``base`` is the element type: an IDL basic type (``float``, ``uint8``,
    ``boolean``, ``octet``...), ``string``/``wstring``, or a full type name
    (``std_msgs/msg/Header``) for a nested type.  ``container`` is None, ``array``
    (fixed size ``size``), ``sequence`` (unbounded) or ``bounded_sequence``
    (at most ``size`` elements); ``string_bound`` is the maximum length of a
    bounded (w)string element.
    """

    __slots__ = ('base', 'container', 'size', 'string_bound', 'nested')

    def __init__(self, base: str, container: str | None = None, size: int | None = None,
                 string_bound: int | None = None, nested: bool = False) -> None:
        self.base = base
        self.container = container
        self.size = size
        self.string_bound = string_bound
        #: True when :attr:`base` is a message type.
        self.nested = nested

    @property
    def element_idl(self) -> str:
        """The element's IDL spelling: ``float``, ``string<10>``, ``std_msgs::msg::Header``."""
        if self.nested:
            return self.base.replace('/', '::')
        if self.string_bound is not None:
            return f'{self.base}<{self.string_bound}>'
        return self.base

    @property
    def idl(self) -> str:
        """The IDL spelling of the whole type: ``sequence<float, 5>``, ``double[3]``."""
        element = self.element_idl
        if self.container == 'array':
            return f'{element}[{self.size}]'
        if self.container == 'sequence':
            return f'sequence<{element}>'
        if self.container == 'bounded_sequence':
            return f'sequence<{element}, {self.size}>'
        return element

    def __eq__(self, other: object) -> bool:
        return isinstance(other, FieldType) and self.idl == other.idl

    def __hash__(self) -> int:
        return hash(self.idl)

    def __repr__(self) -> str:
        return f'FieldType({self.idl!r})'


class Field:
    """One field of a message: name, type, default, comment, unit and the nested type."""

    __slots__ = ('name', 'type', 'default', 'comment', 'unit', 'message')

    def __init__(self, name: str, type: FieldType, default: Any = None, comment: str = '',
                 unit: str = '', message: MessageType | None = None) -> None:
        self.name = name
        self.type = type
        #: The default value as the IDL file writes it (a string for strings and sequences), or None.
        self.default = default
        self.comment = comment
        self.unit = unit
        #: The nested message type, expanded (None for a basic or string field).
        self.message = message

    def __repr__(self) -> str:
        return f'Field({self.name!r}, {self.type.idl!r})'


class Constant:
    """A constant of a message: name, type, value and comment."""

    __slots__ = ('name', 'type', 'value', 'comment')

    def __init__(self, name: str, type: FieldType, value: Any, comment: str = '') -> None:
        self.name = name
        self.type = type
        self.value = value
        self.comment = comment

    def __repr__(self) -> str:
        return f'Constant({self.name!r}, {self.type.idl!r}, {self.value!r})'


class MessageType:
    """A message (or a service's request/response, an action's goal/result/feedback)."""

    kind = 'msg'

    def __init__(self, name: str, fields: list[Field], constants: list[Constant], comment: str,
                 file: str) -> None:
        #: The full type name (``std_msgs/msg/String``, ``std_srvs/srv/Trigger_Request``).
        self.name = name
        self.fields = fields
        self.constants = constants
        self.comment = comment
        #: The file it was read from.
        self.file = file

    def field(self, name: str) -> Field | None:
        """The field called ``name``, or None."""
        return next((f for f in self.fields if f.name == name), None)

    def __repr__(self) -> str:
        return f'<MessageType {self.name}: {", ".join(f.name for f in self.fields)}>'


class ServiceType:
    """A service: its request and response messages."""

    kind = 'srv'

    def __init__(self, name: str, request: MessageType, response: MessageType, file: str) -> None:
        self.name = name
        self.request = request
        self.response = response
        self.file = file

    def __repr__(self) -> str:
        return f'<ServiceType {self.name}>'


class ActionType:
    """An action: its goal, result and feedback messages."""

    kind = 'action'

    def __init__(self, name: str, goal: MessageType, result: MessageType, feedback: MessageType,
                 file: str) -> None:
        self.name = name
        self.goal = goal
        self.result = result
        self.feedback = feedback
        self.file = file

    def __repr__(self) -> str:
        return f'<ActionType {self.name}>'


#: Any interface type: a message, a service or an action.
InterfaceType = MessageType | ServiceType | ActionType


# -- reading files ------------------------------------------------------------------------------

def load_idl(index: InterfaceIndex, package: str, namespace: str, name: str) -> Any:
    """The parsed IDL (``rosidl_parser.definition.IdlContent``) of one interface file, read once
    per index.  UnknownTypeError if the index has no such type; InterfaceFileError if its
    file cannot be read or parsed."""
    key = ('idl', package, namespace, name)
    cache = index.cache
    if key in cache:
        found = cache[key]
        if isinstance(found, InterfaceFileError):
            raise found
        return found
    owner = index.package(package)
    path = owner.file(namespace, name) if owner is not None else None
    if owner is None or path is None:
        raise UnknownTypeError(f'{package}/{namespace}/{name}')
    try:
        content = _parse(path, owner.share, package, namespace, name)
    except InterfaceFileError as exc:
        cache[key] = exc
        raise
    cache[key] = content
    return content


def _read_text(path: str) -> str:
    """The text of an interface file; InterfaceFileError if it cannot be read, is larger than
    10 MB or is not UTF-8."""
    try:
        with open(path, 'rb') as handle:
            raw = handle.read(10 * 1024 * 1024 + 1)
    except OSError as exc:
        raise InterfaceFileError(f'cannot be read: {exc.strerror or exc}', path) from None
    if len(raw) > 10 * 1024 * 1024:
        raise InterfaceFileError('is larger than the 10 MB limit', path)
    try:
        return raw.decode('utf-8')
    except UnicodeDecodeError as exc:
        line = raw.count(b'\n', 0, exc.start) + 1
        raise InterfaceFileError('is not UTF-8 text', path, line) from None


def read_spec(path: str, package: str, namespace: str, name: str) -> Any:
    """A ``.msg``/``.srv``/``.action`` file read by rosidl_adapter's parser (its
    ``MessageSpecification``, ``ServiceSpecification`` or ``ActionSpecification``), printing
    nothing.  InterfaceFileError (at the first line the parser refuses) if the file is
    malformed or cannot be read."""
    text = _read_text(path)
    return _adapter_spec(text, path, package, namespace, name)


def _adapter_spec(text: str, path: str, package: str, namespace: str, name: str) -> Any:
    from rosidl_adapter import parser as adapter

    parse = {'msg': adapter.parse_message_string, 'srv': adapter.parse_service_string,
             'action': adapter.parse_action_string}[namespace]
    try:
        with _quiet():  # rosidl_adapter prints its errors as well as raising them
            return parse(package, name, text)
    except Exception as exc:  # InvalidSpecification, InvalidValue, ValueError...
        line = _bad_line(text, package, name)
        reason = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise InterfaceFileError(f'is not a valid interface definition: {reason}', path,
                                 line, 1 if line else 0) from None


def _parse(path: str, share: str, package: str, namespace: str, name: str) -> Any:
    text = _read_text(path)
    idl = text if path.endswith('.idl') else _to_idl(text, path, package, namespace, name)
    from rosidl_parser.parser import parse_idl_string

    try:
        content = parse_idl_string(idl)
    except Exception as exc:  # lark's and rosidl_parser's own errors alike
        line, column = getattr(exc, 'line', 0), getattr(exc, 'column', 0)
        if not path.endswith('.idl'):
            line, column = 0, 0  # a position in the generated IDL means nothing to the user
        reason = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise InterfaceFileError(f'is not a valid interface definition: {reason}', path,
                                 line if isinstance(line, int) and line > 0 else 0,
                                 column if isinstance(column, int) and column > 0 else 0) from None
    from rosidl_parser.definition import Action, Message, Service

    wanted = {'msg': Message, 'srv': Service, 'action': Action}[namespace]
    if not any(isinstance(e, wanted) and _element_name(e) == name for e in content.elements):
        raise InterfaceFileError(f'does not define {package}/{namespace}/{name}', path)
    return content


def _element_name(element: Any) -> str:
    typed = element.structure.namespaced_type if hasattr(element, 'structure') else element.namespaced_type
    return str(typed.name)


def _to_idl(text: str, path: str, package: str, namespace: str, name: str) -> str:
    """A ``.msg``/``.srv``/``.action`` file's IDL, as rosidl_adapter writes it."""
    from rosidl_adapter.resource import evaluate_template

    spec = _adapter_spec(text, path, package, namespace, name)
    data = {'pkg_name': package, 'relative_input_file': f'{namespace}/{os.path.basename(path)}',
            namespace: spec}
    with _quiet():
        result: str = evaluate_template(f'{namespace}.idl.em', data)  # type: ignore[arg-type]
    return result


def _quiet() -> Any:
    """Standard output and error captured (the library never prints)."""
    stack = contextlib.ExitStack()
    stack.enter_context(contextlib.redirect_stdout(io.StringIO()))
    stack.enter_context(contextlib.redirect_stderr(io.StringIO()))
    return stack


def _bad_line(text: str, package: str, name: str) -> int:
    """The first line of a .msg/.srv/.action text that rosidl_adapter refuses on its own."""
    from rosidl_adapter.parser import parse_message_string

    for number, line in enumerate(text.splitlines(), 1):
        if not line.strip() or line.strip().startswith('#') or line.strip() == '---':
            continue
        try:
            with _quiet():
                parse_message_string(package, name, line)
        except Exception:
            return number
    return 0


# -- the tree -----------------------------------------------------------------------------------

def load_type(index: InterfaceIndex, name: TypeName | str) -> MessageType | ServiceType | ActionType:
    """The typed tree of a full type name (nested types expanded), built once per index.

    ``name`` may also name a service's or an action's part (``std_srvs/srv/Trigger_Request``,
    ``test_msgs/action/Fibonacci_Feedback``), which is a :class:`MessageType`.
    UnknownTypeError if it is not defined; InterfaceFileError for a malformed file.
    """
    text = str(name)
    key = ('tree', text)
    cache = index.cache
    if key in cache:
        found: MessageType | ServiceType | ActionType = cache[key]
        return found
    package, namespace, type_name = _split(text)
    base = type_name.split('_', 1)[0]
    spec = _plain_spec(index, package, namespace, base)
    if spec is not None:
        return _tree_from_spec(index, text, namespace, type_name, base, spec)
    content = load_idl(index, package, namespace, base)
    from rosidl_parser.definition import Action, Message, Service

    result: MessageType | ServiceType | ActionType | None = None
    for element in content.elements:
        if isinstance(element, Message):
            messages = [element]
        elif isinstance(element, Service):
            if type_name == base:
                result = ServiceType(text, _message(index, element.request_message),
                                     _message(index, element.response_message), index.file(text) or '')
                break
            messages = [element.request_message, element.response_message, element.event_message]
        elif isinstance(element, Action):
            if type_name == base:
                result = ActionType(text, _message(index, element.goal),
                                    _message(index, element.result),
                                    _message(index, element.feedback), index.file(text) or '')
                break
            messages = [element.goal, element.result, element.feedback, element.feedback_message]
        else:
            continue
        for message in messages:
            if _full_name(message.structure.namespaced_type) == text:
                result = _message(index, message)
                break
        if result is not None:
            break
    if result is None:
        raise UnknownTypeError(text)
    cache[key] = result
    return result


def _split(text: str) -> tuple[str, str, str]:
    parts = text.split('/')
    if len(parts) != 3 or not all(parts):
        raise UnknownTypeError(text)
    return parts[0], parts[1], parts[2]


def _full_name(namespaced: Any) -> str:
    return '/'.join(namespaced.namespaced_name())


def _comment(annotated: Any) -> str:
    texts = [a.value['text'] for a in getattr(annotated, 'annotations', ())
             if a.name == 'verbatim' and isinstance(a.value, dict)
             and a.value.get('language') == 'comment']
    return '\n'.join(str(t) for t in texts)


def _unit(annotated: Any) -> str:
    for a in getattr(annotated, 'annotations', ()):
        if a.name == 'unit' and isinstance(a.value, dict):
            return str(a.value.get('value', ''))
    return ''


def field_type(rosidl_type: Any) -> FieldType:
    """A :class:`FieldType` from a rosidl_parser type."""
    from rosidl_parser import definition as d

    container: str | None = None
    size: int | None = None
    element = rosidl_type
    if isinstance(rosidl_type, d.Array):
        container, size, element = 'array', rosidl_type.size, rosidl_type.value_type
    elif isinstance(rosidl_type, d.BoundedSequence):
        container, size, element = 'bounded_sequence', rosidl_type.maximum_size, rosidl_type.value_type
    elif isinstance(rosidl_type, d.UnboundedSequence):
        container, element = 'sequence', rosidl_type.value_type
    if isinstance(element, d.BasicType):
        return FieldType(element.typename, container, size)
    if isinstance(element, d.AbstractGenericString):
        bound: Any = getattr(element, 'maximum_size', None) if element.has_maximum_size() else None
        return FieldType('wstring' if isinstance(element, d.AbstractWString) else 'string',
                         container, size, int(bound) if bound is not None else None)
    if isinstance(element, d.NamespacedType):
        return FieldType(_full_name(element), container, size, nested=True)
    raise InterfaceFileError(f'unsupported IDL type {type(element).__name__}', '')


def _message(index: InterfaceIndex, message: Any) -> MessageType:
    name = _full_name(message.structure.namespaced_type)
    key = ('tree', name)
    if key in index.cache:
        cached: MessageType = index.cache[key]
        return cached
    package, namespace, type_name = _split(name)
    file = index.file(f'{package}/{namespace}/{type_name.split("_", 1)[0]}') or ''
    result = MessageType(name, [], [], _comment(message.structure), file)
    index.cache[key] = result  # before the fields: a (forbidden) recursive type stays finite
    for member in message.structure.members:
        ftype = field_type(member.type)
        default = (member.get_annotation_value('default')['value']
                   if member.has_annotation('default') else None)
        nested = None
        if ftype.nested:
            loaded = load_type(index, ftype.base)
            assert isinstance(loaded, MessageType)
            nested = loaded
        result.fields.append(Field(member.name, ftype, default, _comment(member), _unit(member),
                                   nested))
    for constant in message.constants:
        result.constants.append(Constant(constant.name, field_type(constant.type), constant.value,
                                         _comment(constant)))
    return result


# -- the fast path: an installed .msg/.srv/.action read by rosidl_adapter alone -----------------
#
# An installed package's .idl is generated from its .msg/.srv/.action by rosidl_adapter, so the
# adapter's own reading of the plain file holds the same fields, bounds, defaults, constants,
# comments and units; it costs a fraction of parsing the generated IDL with rosidl_parser's
# Earley grammar.  A package's source types, and a type installed as .idl alone, are still
# parsed as IDL (as the package's build will).

#: rosidl_adapter's primitive type names -> the IDL basic types of the generated .idl.
_IDL_BASIC = {'bool': 'boolean', 'byte': 'octet', 'char': 'uint8', 'float32': 'float',
              'float64': 'double', 'string': 'string', 'wstring': 'wstring'}


def _plain_spec(index: InterfaceIndex, package: str, namespace: str, name: str) -> Any:
    """rosidl_adapter's specification of an installed type that has a ``.msg``/``.srv``/
    ``.action`` file, read once per index; None when the type is to be parsed as IDL (a source
    package's, one installed as ``.idl`` alone, or one not defined at all)."""
    key = ('spec', package, namespace, name)
    cache = index.cache
    if key in cache:
        found = cache[key]
        if isinstance(found, InterfaceFileError):
            raise found
        return found
    owner = index.package(package)
    files = owner.types.get((namespace, name), []) if owner is not None else []
    plain = [f for f in files if not f.endswith('.idl')]
    if owner is None or owner.origin == 'source' or not plain:
        cache[key] = None
        return None
    try:
        spec = read_spec(os.path.join(owner.share, plain[0]), package, namespace, name)
    except InterfaceFileError as exc:
        cache[key] = exc
        raise
    cache[key] = spec
    return spec


def _spec_field_type(adapter_type: Any) -> FieldType:
    """A :class:`FieldType` from a rosidl_adapter type, spelled as the generated IDL spells it."""
    container: str | None = None
    size: int | None = None
    if adapter_type.is_array:
        if adapter_type.array_size is None:
            container = 'sequence'
        else:
            container = 'bounded_sequence' if adapter_type.is_upper_bound else 'array'
            size = int(adapter_type.array_size)
    if not adapter_type.is_primitive_type():
        return FieldType(f'{adapter_type.pkg_name}/msg/{adapter_type.type}', container, size,
                         nested=True)
    base = _IDL_BASIC.get(adapter_type.type, adapter_type.type)
    bound = adapter_type.string_upper_bound if base in ('string', 'wstring') else None
    return FieldType(base, container, size, int(bound) if bound is not None else None)


def _spec_value(ftype: FieldType, value: Any) -> Any:
    """A default or constant value as rosidl_parser reads it back from the generated IDL: the
    text of the tuple for an array or sequence, else the scalar itself."""
    if value is None:
        return None
    if ftype.container is not None:
        return repr(tuple(value))
    return value


def _spec_comment(annotations: Any) -> str:
    return '\n'.join(str(line) for line in annotations.get('comment', ()))


def _spec_message(index: InterfaceIndex, name: str, file: str, spec: Any) -> MessageType:
    key = ('tree', name)
    if key in index.cache:
        cached: MessageType = index.cache[key]
        return cached
    result = MessageType(name, [], [], _spec_comment(spec.annotations), file)
    index.cache[key] = result  # before the fields: a (forbidden) recursive type stays finite
    for member in spec.fields:
        ftype = _spec_field_type(member.type)
        nested = None
        if ftype.nested:
            loaded = load_type(index, ftype.base)
            assert isinstance(loaded, MessageType)
            nested = loaded
        result.fields.append(Field(member.name, ftype, _spec_value(ftype, member.default_value),
                                   _spec_comment(member.annotations),
                                   str(member.annotations.get('unit', '')), nested))
    if not spec.fields:  # rosidl_adapter's IDL (and so every generated message) holds one
        result.fields.append(Field('structure_needs_at_least_one_member', FieldType('uint8')))
    for constant in spec.constants:
        base = _IDL_BASIC.get(constant.type, constant.type)
        # rosidl_parser bounds a string constant's type by its value's length
        ctype = FieldType(base, string_bound=len(constant.value)
                          if base in ('string', 'wstring') else None)
        result.constants.append(Constant(constant.name, ctype, constant.value,
                                         _spec_comment(constant.annotations)))
    return result


def _synthetic(index: InterfaceIndex, name: str, file: str,
               members: list[tuple[str, FieldType]]) -> MessageType:
    """A message rosidl adds to a service or action (its event message, an action's feedback
    message), as rosidl_parser builds it: no comment, no defaults."""
    key = ('tree', name)
    if key in index.cache:
        cached: MessageType = index.cache[key]
        return cached
    result = MessageType(name, [], [], '', file)
    index.cache[key] = result
    for field_name, ftype in members:
        loaded = load_type(index, ftype.base)
        assert isinstance(loaded, MessageType)
        result.fields.append(Field(field_name, ftype, message=loaded))
    return result


def _tree_from_spec(index: InterfaceIndex, text: str, namespace: str, type_name: str, base: str,
                    spec: Any) -> MessageType | ServiceType | ActionType:
    package = text.split('/', 1)[0]
    prefix = f'{package}/{namespace}/{base}'
    file = index.file(prefix) or ''
    result: MessageType | ServiceType | ActionType
    if namespace == 'msg':
        if type_name != base:
            raise UnknownTypeError(text)
        return _spec_message(index, text, file, spec)
    if namespace == 'srv':
        parts = {'Request': spec.request, 'Response': spec.response}
        made = {suffix: _spec_message(index, f'{prefix}_{suffix}', file, part)
                for suffix, part in parts.items()}
        if type_name == base:
            result = ServiceType(text, made['Request'], made['Response'], file)
        elif type_name == f'{base}_Event':
            result = _synthetic(index, text, file, [
                ('info', FieldType('service_msgs/msg/ServiceEventInfo', nested=True)),
                ('request', FieldType(f'{prefix}_Request', 'bounded_sequence', 1, nested=True)),
                ('response', FieldType(f'{prefix}_Response', 'bounded_sequence', 1, nested=True))])
        else:
            found = made.get(type_name[len(base) + 1:]) if type_name.startswith(f'{base}_') else None
            if found is None:
                raise UnknownTypeError(text)
            result = found
    else:
        parts = {'Goal': spec.goal, 'Result': spec.result, 'Feedback': spec.feedback}
        made = {suffix: _spec_message(index, f'{prefix}_{suffix}', file, part)
                for suffix, part in parts.items()}
        if type_name == base:
            result = ActionType(text, made['Goal'], made['Result'], made['Feedback'], file)
        elif type_name == f'{base}_FeedbackMessage':
            result = _synthetic(index, text, file, [
                ('goal_id', FieldType('unique_identifier_msgs/msg/UUID', nested=True)),
                ('feedback', FieldType(f'{prefix}_Feedback', nested=True))])
        else:
            found = made.get(type_name[len(base) + 1:]) if type_name.startswith(f'{base}_') else None
            if found is None:
                raise UnknownTypeError(text)
            result = found
    index.cache[('tree', text)] = result
    return result
