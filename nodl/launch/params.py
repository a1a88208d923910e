"""Parameters as launch types them, and parameter files as rcl and launch_ros match them.

* Values: a value written in a frontend (``value="1"``) or built from substitutions is
  typed by YAML rules exactly as launch does (``coerce_to_type``, ``evaluate_parameter_dict``):
  ``1`` is an int, ``1.0`` a float, ``true`` a bool, ``'1'`` a string, lists must be uniform.
* Files: :func:`load_parameter_file` keeps the data and the line of every node key and
  parameter, so that a later check can point into the file.
* Matching (which keys apply to a node) and rcl's typing of values are in
  :mod:`nodl.launch.rcl_yaml`; precedence (which value wins) is in
  :mod:`nodl.launch.parameter_values`.
"""

from __future__ import annotations

import os
import re
from functools import cache
from typing import Any, NamedTuple

from nodl.diagnostics import Diagnostic, Severity
from nodl.launch.errors import LaunchProblem
from nodl.launch.rcl_yaml import (
    match_composable_parameter_keys,
    match_parameter_file_nodes,
    rcl_node_value,
)

__all__ = ['ParameterValue', 'RuntimeValue', 'coerce_to_type', 'get_typed_value', 'evaluate_value',
           'ParameterFileNode', 'ParameterFile', 'load_parameter_file', 'parse_parameter_text',
           'read_parameter_text', 'unsafe_parameter_text',
           'match_parameter_file_nodes', 'match_composable_parameter_keys', 'flatten_parameters',
           'SCALAR_TYPES']

SCALAR_TYPES = (bool, int, float, str)
_TYPE_NAMES = {'str': str, 'int': int, 'float': float, 'bool': bool,
               'list_of_str': ('list', str), 'list_of_int': ('list', int),
               'list_of_float': ('list', float), 'list_of_bool': ('list', bool)}


def _uniform(values: list[Any], can_be_str: bool = False) -> bool:
    if not values:
        return True
    member = next((type(x) for x in values if type(x) is not str), str)
    if member not in SCALAR_TYPES:
        return False
    allowed: tuple[type, ...] = (member, str) if can_be_str else (member,)
    return all(isinstance(x, allowed) and (type(x) is not bool or member is bool or member is str)
               for x in values)


#: Text that YAML reads as one plain scalar (no indicator, space, quote, colon or comment):
#: typed by PyYAML's resolver and constructor alone, exactly as ``yaml.safe_load`` types it,
#: without its (pure Python) scanner and parser, which cost a launch file of thousands of
#: parameters seconds.
_PLAIN_WORD = re.compile(r'[-+.]?[A-Za-z0-9_][A-Za-z0-9_.+\-/]*')


#: Decimal numbers without underscores or an exponent (``5``, ``-12``, ``0.5``, ``5.``): YAML 1.1
#: reads the first form (no leading zero) as an int, the second as a float, as Python does.
_DECIMAL = re.compile(r'[-+]?(?:(0|[1-9][0-9]*)|[0-9]+\.[0-9]*)')
#: The words PyYAML's resolver reads as a bool or null (typed by PyYAML itself, once).
_YAML_WORDS = ('yes', 'Yes', 'YES', 'no', 'No', 'NO', 'true', 'True', 'TRUE', 'false', 'False', 'FALSE',
               'on', 'On', 'ON', 'off', 'Off', 'OFF', 'null', 'Null', 'NULL')


def yaml_value(text: str) -> Any:
    """``yaml.safe_load(text)`` (yaml.YAMLError as it raises), quick for one plain word."""
    if _PLAIN_WORD.fullmatch(text):
        # The usual parameter values first: a plain decimal number, a bool or null word.
        number = _DECIMAL.fullmatch(text)
        if number is not None:
            return int(text) if number.group(1) is not None else float(text)
        resolver, constructor, scalar, words = _plain_scalar_typing()
        if text in words:
            return words[text]
        return _construct(resolver, constructor, scalar, text)
    import yaml

    return yaml.safe_load(text)


def _construct(resolver: Any, constructor: Any, scalar: Any, text: str) -> Any:
    """What safe_load's composer and constructor do for one plain scalar, called directly:
    the resolver's tag, then that tag's constructor (a scalar's has no state to reset)."""
    tag = resolver.resolve(scalar, text, (True, False))
    construct = constructor.yaml_constructors.get(tag)
    if construct is None:  # a tag someone added a resolver for: as safe_load treats it
        return type(constructor)().construct_document(scalar(tag, text))
    return construct(constructor, scalar(tag, text))


@cache  # one entry: PyYAML's stateless helpers, made when first needed
def _plain_scalar_typing() -> tuple[Any, Any, Any, dict[str, Any]]:
    from yaml.constructor import SafeConstructor
    from yaml.nodes import ScalarNode
    from yaml.resolver import Resolver

    resolver, constructor = Resolver(), SafeConstructor()
    return resolver, constructor, ScalarNode, {
        word: _construct(resolver, constructor, ScalarNode, word) for word in _YAML_WORDS}


def _yaml(text: str, can_be_str: bool) -> Any:
    if not text:
        return text
    try:
        out = yaml_value(text)
    except Exception as exc:
        import yaml  # only now: a value read without error needs no import statement

        if not isinstance(exc, yaml.YAMLError):
            raise
        if can_be_str:
            return text
        raise LaunchProblem('NODL518', f'cannot read {text!r} as a YAML value: {exc}'.split('\n')[0]) from None
    valid = isinstance(out, SCALAR_TYPES) or (isinstance(out, list) and _uniform(out, can_be_str))
    if not valid:
        raise LaunchProblem('NODL518', f'the value {text!r} is {type(out).__name__} in YAML; a '
                                       'parameter is a bool, int, float, string or a uniform list '
                                       'of them (quote it to make it a string)')
    return out


def coerce_to_type(text: str, data_type: Any = None, *, can_be_str: bool = False) -> Any:
    """``launch.utilities.type_utils.coerce_to_type``: YAML rules, or the given type."""
    if data_type is None:
        return _yaml(text, can_be_str)
    if isinstance(data_type, tuple):
        item_type = data_type[1]
        out = _yaml(text, can_be_str)
        if not isinstance(out, list) or not all(isinstance(x, (item_type, str) if can_be_str else item_type)
                                                for x in out):
            raise LaunchProblem('NODL518', f'cannot convert {text!r} to a list of {item_type.__name__}')
        return out
    if data_type is str:
        return text
    if data_type in (int, float):
        try:
            return data_type(text)
        except ValueError:
            if can_be_str:
                return text
            raise LaunchProblem('NODL518', f'cannot convert {text!r} to {data_type.__name__}') from None
    value = {'1': 'true', '0': 'false'}.get(text, text)
    out = _yaml(value, can_be_str)
    if isinstance(out, bool) or (can_be_str and isinstance(out, str)):
        return out
    raise LaunchProblem('NODL518', f'cannot convert {text!r} to bool')


def get_typed_value(value: str | list[str], data_type: Any, *, can_be_str: bool = True) -> Any:
    """``get_typed_value``: a frontend attribute (text, or a list split by ``value-sep``)."""
    if isinstance(value, list):
        item_type = data_type[1] if isinstance(data_type, tuple) else None
        if data_type is not None and not isinstance(data_type, tuple):
            raise LaunchProblem('NODL518', f'a list {value!r} cannot be converted to {data_type.__name__}')
        out = [coerce_to_type(v, item_type, can_be_str=can_be_str) for v in value]
        if not _uniform(out, can_be_str):
            raise LaunchProblem('NODL518', f'the list {value!r} mixes types; a parameter list is uniform')
        return out
    return coerce_to_type(value, data_type, can_be_str=can_be_str)


def type_from_identifier(identifier: str) -> Any:
    """The ``type`` attribute of a frontend ``param`` (``str``, ``list_of_int``...)."""
    try:
        return _TYPE_NAMES[identifier]
    except KeyError:
        from nodl.wording import did_you_mean

        raise LaunchProblem('NODL504', f"unknown parameter type '{identifier}'"
                                       f'{did_you_mean(identifier, _TYPE_NAMES)}; expected one of '
                                       f'{", ".join(_TYPE_NAMES)}') from None


class ParameterValue:
    """A value to compute: a scalar, substitutions, or a list of those; with an optional type.

    ``yaml_typed`` values (what ``normalize_parameter_dict`` makes of substitutions) are read
    by YAML after substitution; ``data_type`` values (``ParameterValue(v, value_type=...)``,
    frontend ``param``) are coerced as ``perform_typed_substitution`` does.
    """

    #: Where the value is written, when a frontend knows (an XML or YAML ``param``): findings
    #: about it sit there rather than at the node's entry.
    location: Any = None

    def __init__(self, value: Any, value_type: Any = None, *, dict_rules: bool = False) -> None:
        self.value = value
        self.value_type = value_type
        self.dict_rules = dict_rules


class RuntimeValue:
    """A parameter value only the running launch knows (``$(command ...)``...): the node is
    analysed with this parameter set, its value unchecked.

    It is no value and has no text standing for one (no placeholder string can reach a
    report): the JSON report writes ``null`` for it, the log says it is known at run time."""

    __slots__ = ('name',)

    def __init__(self, name: str = '') -> None:
        #: The parameter it is the value of.
        self.name = name

    def __repr__(self) -> str:
        return f'RuntimeValue({self.name!r})'


def _is_subs(value: Any) -> bool:
    from nodl.launch.substitutions import Substitution

    return isinstance(value, Substitution) or (
        isinstance(value, (list, tuple)) and bool(value)
        and all(isinstance(v, (Substitution, str)) for v in value)
        and any(isinstance(v, Substitution) for v in value))


def evaluate_value(context: Any, spec: Any, name: str = '') -> Any:
    """Compute a parameter value in ``context`` as launch_ros does."""
    if isinstance(spec, ParameterValue):
        value, data_type = spec.value, spec.value_type
        if isinstance(value, SCALAR_TYPES):  # a value as it is, under both rules (the usual case)
            return value
        from nodl.launch.substitutions import perform

        if spec.dict_rules:  # evaluate_parameter_dict: substitutions are read as YAML, '' is ''
            if _is_subs(value):
                text = perform(context, value)
                return _dict_yaml(text or "''", name)
            if isinstance(value, list) and value and all(isinstance(v, list) for v in value):
                items = [_dict_yaml(perform(context, v) or "''", name) for v in value]
                if not _uniform(items) or not items:
                    raise LaunchProblem('NODL518', f"parameter '{name}': a list of items of one "
                                                   'type (bool, int, float or str) was expected')
                return items
            return value
        if _is_subs(value):
            return coerce_to_type(perform(context, value), data_type)
        if isinstance(value, list):
            item_type = data_type[1] if isinstance(data_type, tuple) else None
            out = [coerce_to_type(perform(context, v), item_type) if _is_subs(v) else v for v in value]
            if not _uniform(out):
                raise LaunchProblem('NODL518', f"parameter '{name}': the list is not uniform")
            return out
        return value
    return spec


def _dict_yaml(text: str, name: str) -> Any:
    import yaml

    try:
        out = yaml_value(text)
    except yaml.YAMLError:
        raise LaunchProblem('NODL518', f"parameter '{name}': the value {text!r} is not valid YAML; "
                                       'for a string, wrap it in ParameterValue(value, value_type=str)') from None
    if isinstance(out, SCALAR_TYPES):
        return out
    if isinstance(out, list) and out and _uniform(out):
        return out
    raise LaunchProblem('NODL518', f"parameter '{name}': the value {text!r} is {type(out).__name__} "
                                   'in YAML; allowed are bool, int, float, str and uniform lists')


def normalize_python_dict(parameters: Any, prefix: str = '') -> list[tuple[Any, Any]]:
    """A Python ``parameters=[{...}]`` dict as ``normalize_parameter_dict`` makes it:
    nested dicts flattened with ``.``; strings stay strings; substitutions are read as YAML."""
    from nodl.launch.substitutions import Substitution, normalize

    out: list[tuple[Any, Any]] = []
    for key, value in parameters.items():
        name = normalize(key)
        if prefix:
            from nodl.launch.substitutions import TextSubstitution

            name = [TextSubstitution(prefix), TextSubstitution('.'), *name]
        if isinstance(value, dict):
            from nodl.launch.substitutions import TextSubstitution

            joined = ''.join(s.text for s in name if isinstance(s, TextSubstitution))
            out.extend(normalize_python_dict(value, joined))
        elif isinstance(value, ParameterValue):
            out.append((name, value))
        elif isinstance(value, Substitution):
            out.append((name, ParameterValue(normalize(value), dict_rules=True)))
        elif isinstance(value, (list, tuple)):
            items = list(value)
            kinds = {type(v) for v in items}
            if any(isinstance(v, Substitution) for v in items) and all(
                    isinstance(v, (str, Substitution)) for v in items):
                out.append((name, ParameterValue(normalize(items), dict_rules=True)))
            elif kinds == {int}:
                out.append((name, ParameterValue(items, dict_rules=True)))
            elif kinds <= {int, float} and kinds:
                out.append((name, ParameterValue([float(v) for v in items], dict_rules=True)))
            elif kinds == {bool}:
                out.append((name, ParameterValue(items, dict_rules=True)))
            else:
                import yaml

                parts = [normalize(v) if not isinstance(v, (bool, int, float, str))
                         else normalize(yaml.dump(v)) for v in items]
                out.append((name, ParameterValue(parts, dict_rules=True)))
        else:
            out.append((name, ParameterValue(value, dict_rules=True)))
    return out


# -- parameter files -------------------------------------------------------------------------

class ParameterFileNode(NamedTuple):
    """One node key of a parameter file and its parameters (nested names joined with ``.``)."""

    key: str
    parameters: dict[str, Any]
    #: Parameter name -> (line, column) of its key in the file.
    positions: dict[str, tuple[int, int]]
    line: int
    column: int
    #: The same parameters typed as rcl types them (a node started as a process reads the file
    #: with rcl: ``y`` is a bool, ``1e5`` a double); ``parameters`` is typed by PyYAML, as
    #: launch_ros reads the file for a composable node.
    rcl_parameters: dict[str, Any] = {}


class ParameterFile:
    """A parameter file: its node keys in file order, and the problems found reading it.

    rcl and launch_ros read YAML differently: rcl refuses every alias ("Will not support
    aliasing"), ignores anchors and has no merge keys (``<<`` is a parameter name to it),
    while launch_ros reads a composable node's file with PyYAML, which expands aliases and
    merge keys.  ``nodes`` is the file as written (``rcl_parameters`` typed by rcl), what
    rcl alone objects to is in ``rcl_diagnostics``, and ``composable_nodes`` is PyYAML's
    reading.
    """

    def __init__(self, path: str, nodes: list[ParameterFileNode], diagnostics: list[Diagnostic],
                 rcl_diagnostics: list[Diagnostic] | None = None,
                 composable_nodes: list[ParameterFileNode] | None = None) -> None:
        self.path = path
        self.nodes = nodes
        self.diagnostics = diagnostics
        #: What rcl alone refuses or ignores (aliases NODL710, anchors NODL711, merge keys
        #: NODL712): a problem where the file is given to a node started as a process.
        self.rcl_diagnostics: list[Diagnostic] = rcl_diagnostics or []
        #: The node keys as launch_ros reads the file for a composable node (PyYAML).
        self.composable_nodes = nodes if composable_nodes is None else composable_nodes

    @property
    def rcl_refuses(self) -> bool:
        """True if rcl cannot parse the file (it holds an alias): a node started as a
        process with it fails to start, and gets none of its values."""
        return any(d.code == ALIAS_REFUSED for d in self.rcl_diagnostics)

    @property
    def keys(self) -> list[str]:
        """The node keys, in file order."""
        return [n.key for n in self.nodes]


_CACHE: dict[tuple[str, float, int], ParameterFile] = {}


#: What a parameter file is, said where one is empty or not a mapping.
_PARAMETER_FILE_SHAPE = 'a parameter file is a mapping NODE: {ros__parameters: {NAME: VALUE}}'


def _as_parameter_file_problem(diagnostic: Diagnostic) -> Diagnostic:
    """A reading problem of a parameter file said about parameter files: the YAML reader's
    "document is empty / not a mapping" (NODL011) speaks of NoDL documents."""
    if diagnostic.code != 'NODL011':
        return diagnostic
    empty = 'empty' in diagnostic.message
    what = 'the parameter file is empty' if empty else \
        'the parameter file is ' + diagnostic.message.removeprefix('document is ').split(';')[0]
    return diagnostic.replace(code='NODL517', message=f'{what}; {_PARAMETER_FILE_SHAPE}')


def load_parameter_file(path: str | os.PathLike[str]) -> ParameterFile:
    """Read a ROS parameter file (``node: {ros__parameters: {...}}``), keeping positions."""
    from nodl.files import describe_os_error

    name = os.fspath(path)
    try:
        stat = os.stat(name)
    except OSError as exc:
        return ParameterFile(name, [], [Diagnostic(Severity.ERROR, f'cannot read the parameter file: '
                                                   f'{describe_os_error(exc)}', (), name, code='NODL517')])
    key = (os.path.realpath(name), stat.st_mtime, stat.st_size)
    if key in _CACHE:
        return _CACHE[key]
    text, problem = read_parameter_text(name)  # a directory, no permission: said in words
    if text is None:
        assert problem is not None
        result = ParameterFile(name, [], [problem])
        _CACHE[key] = result
        return result
    result = _parse_parameter_text(name, text)
    if len(_CACHE) > 1024:
        _CACHE.clear()
    _CACHE[key] = result
    return result


def read_parameter_text(path: str) -> tuple[str | None, Diagnostic | None]:
    """The text of the parameter file ``path`` (within the size limit, UTF-8), or None and
    what is wrong (NODL517, the reason in words)."""
    from nodl.frontends.source import decode, read_limited

    try:
        data = read_limited(path)
    except OSError as exc:
        from nodl.files import describe_os_error

        return None, Diagnostic(Severity.ERROR, 'cannot read the parameter file: '
                                f'{describe_os_error(exc)}', (), path, code='NODL517')
    return decode(data, path)


#: Substituted parameter files already read, by (name, text): a file launch_ros evaluates once
#: for many nodes (one ``ParameterFile`` given to them all) is one text they all read.
_TEXTS: dict[tuple[str, str], ParameterFile] = {}


def parse_parameter_text(name: str, text: str) -> ParameterFile:
    """A parameter file's ``text`` (read from ``name``, which findings name) read as
    :func:`load_parameter_file` reads a file: for a file whose text launch substitutes first
    (``allow_substs``).  The same name and text are read once (the result, as
    :func:`load_parameter_file`'s, is shared: not to be changed)."""
    key = (name, text)
    found = _TEXTS.get(key)
    if found is None:
        # The same text under another name (each evaluation of a substitution such as nav2's
        # RewrittenYaml writes a file of its own): its nodes, if reading it found nothing to
        # say (a finding names its file).
        same = _TEXTS.get(('', text))
        if same is not None and not same.diagnostics and not same.rcl_diagnostics:
            found = ParameterFile(name, same.nodes, [], None, same.composable_nodes)
        else:
            found = _parse_parameter_text(name, text)
        if len(_TEXTS) > 64:
            _TEXTS.clear()
        _TEXTS[key] = _TEXTS[('', text)] = found
    return found


def _parse_parameter_text(name: str, text: str) -> ParameterFile:
    from yaml.nodes import MappingNode, ScalarNode

    from nodl.frontends.source import SourceText
    from nodl.frontends.yaml_json import parse_document

    doc = parse_document(SourceText(text, name))
    if doc.diagnostics:
        return ParameterFile(name, [], [_as_parameter_file_problem(d) for d in doc.diagnostics])
    root = doc._node_tree()  # composed once: safe, the data was built within the limits
    nodes: list[ParameterFileNode] = []
    problems: list[Diagnostic] = []

    def params_of(mapping: Any, prefix: str, params: dict[str, Any], positions: dict[str, tuple[int, int]],
                  data: Any, rcl: dict[str, Any]) -> None:
        for key_node, value_node in mapping.value:
            pname = f'{prefix}{key_node.value}'
            value = data.get(key_node.value) if isinstance(data, dict) else None
            if isinstance(value_node, MappingNode):
                params_of(value_node, pname + '.', params, positions, value, rcl)
            else:
                params[pname] = value
                rcl[pname] = rcl_node_value(value_node)
                positions[pname] = (key_node.start_mark.line + 1, key_node.start_mark.column + 1)

    def walk(mapping: Any, path: list[str], data: Any) -> None:
        for key_node, value_node in mapping.value:
            if not isinstance(key_node, ScalarNode):
                continue
            value = data.get(key_node.value) if isinstance(data, dict) else None
            if key_node.value == 'ros__parameters':
                node_key = '/'.join(path)
                params: dict[str, Any] = {}
                positions: dict[str, tuple[int, int]] = {}
                rcl: dict[str, Any] = {}
                if isinstance(value_node, MappingNode):
                    params_of(value_node, '', params, positions, value, rcl)
                nodes.append(ParameterFileNode(node_key, params, positions,
                                               key_node.start_mark.line + 1,
                                               key_node.start_mark.column + 1, rcl))
            elif isinstance(value_node, MappingNode):
                walk(value_node, path + [key_node.value], value)
            else:
                problems.append(Diagnostic(
                    Severity.ERROR, f"'{key_node.value}' is not a node key with ros__parameters "
                    'under it; a parameter file is NODE: {ros__parameters: {NAME: VALUE}}', (), name,
                    key_node.start_mark.line + 1, key_node.start_mark.column + 1, code='NODL517'))

    if isinstance(root, MappingNode):
        walk(root, [], doc.data)
        problems.extend(unsafe_parameter_text(name, text, root))
    if not doc.aliasing:  # (most files: rcl and PyYAML read them alike)
        return ParameterFile(name, nodes, problems)
    return ParameterFile(name, nodes, problems, _rcl_refusals(name, doc.aliasing),
                         _as_pyyaml_reads(doc))


def unsafe_parameter_text(name: str, text: str, root: Any) -> list[Diagnostic]:
    """Every node key, parameter name and string value of a parameter file (``text``, its
    node tree ``root``) that holds a control character (NODL221) or a Trojan Source bidi
    control (NODL222), as an error at that character (raw, or the escape of a double-quoted
    scalar): rcl gives such a value to the node as it is (see
    :mod:`nodl.launch.text_checks`)."""
    from nodl.text_safety import UNSAFE

    if '\\' not in text and UNSAFE.search(text) is None:
        return []  # (almost every file: nothing raw, no escape that could make one)
    from yaml.nodes import MappingNode, ScalarNode, SequenceNode

    from nodl.launch.model import SourceLocation
    from nodl.launch.text_checks import unsafe_diagnostic
    from nodl.text_safety import line_column, locate_unsafe, offset_of, visible

    out: list[Diagnostic] = []

    def check(node: Any, what: str) -> None:
        value = node.value
        if not isinstance(value, str) or UNSAFE.search(value) is None:
            return
        line, column = node.start_mark.line + 1, node.start_mark.column + 1
        at = locate_unsafe(text, offset_of(text, line, column), value)
        if at >= 0:
            line, column = line_column(text, at)
        found = unsafe_diagnostic(value, what, SourceLocation(name, line, column))
        assert found is not None
        out.append(found.replace(file=name, line=line, column=column))

    def shown(value: str) -> str:
        return f"'{visible(value, one_line=True)}'"

    def parameters(mapping: Any, prefix: str) -> None:
        for key_node, value_node in mapping.value:
            pname = f'{prefix}{key_node.value}'
            check(key_node, f'the parameter name {shown(pname)}')
            if isinstance(value_node, MappingNode):
                parameters(value_node, pname + '.')
            elif isinstance(value_node, ScalarNode):
                check(value_node, f'the value of parameter {shown(pname)}')
            elif isinstance(value_node, SequenceNode):
                for item in value_node.value:
                    if isinstance(item, ScalarNode):
                        check(item, f'the value of parameter {shown(pname)}')

    def nodes(mapping: Any) -> None:
        for key_node, value_node in mapping.value:
            if not isinstance(key_node, ScalarNode):
                continue
            if key_node.value == 'ros__parameters':
                if isinstance(value_node, MappingNode):
                    parameters(value_node, '')
                continue
            check(key_node, f'the node key {shown(str(key_node.value))}')
            if isinstance(value_node, MappingNode):
                nodes(value_node)

    nodes(root)
    return out


# Diagnostic codes (see nodl.codes): what rcl's parameter parser refuses or ignores.
ALIAS_REFUSED = 'NODL710'
ANCHOR_IGNORED = 'NODL711'
NO_MERGE_KEYS = 'NODL712'


def _rcl_refusals(name: str, aliasing: list[tuple[str, int, int]]) -> list[Diagnostic]:
    """Every alias, anchor and merge key of a parameter file, as rcl treats it."""
    out: list[Diagnostic] = []
    for kind, line, column in aliasing:
        if kind == 'alias':
            out.append(Diagnostic(
                Severity.ERROR, "YAML alias in a parameter file: rcl refuses aliasing ('Will not "
                "support aliasing'), so a node started with this file fails to start; write the "
                'value out where the alias is', (), name, line, column, code=ALIAS_REFUSED))
        elif kind == 'anchor':
            out.append(Diagnostic(
                Severity.WARNING, 'YAML anchor in a parameter file: rcl refuses aliasing, so no '
                'alias can use it (rcl ignores the anchor); remove it', (), name, line, column,
                code=ANCHOR_IGNORED))
        else:
            out.append(Diagnostic(
                Severity.ERROR, "merge key '<<' in a parameter file: rcl has no merge keys (it "
                "reads '<<' as a parameter name) and refuses aliasing; write the parameters out "
                'under the node', (), name, line, column, code=NO_MERGE_KEYS))
    return out


def _as_pyyaml_reads(doc: Any) -> list[ParameterFileNode]:
    """The node keys of a parameter file as launch_ros reads it for a composable node:
    ``yaml.safe_load`` (aliases and merge keys as the installed PyYAML resolves them: that is
    what the running launch does), nested parameter names joined with ``.``."""
    import yaml

    try:
        data = yaml.safe_load(doc.source.text)
    except yaml.YAMLError:  # (read without error by the strict reader: not expected)
        return []
    nodes: list[ParameterFileNode] = []

    def flatten(values: dict[Any, Any], parts: tuple[Any, ...], where: tuple[Any, ...],
                params: dict[str, Any], positions: dict[str, tuple[int, int]]) -> None:
        for key, value in values.items():
            if isinstance(value, dict):
                flatten(value, (*parts, key), where, params, positions)
                continue
            pname = '.'.join(str(part) for part in (*parts, key))
            params[pname] = value
            positions[pname] = doc.position((*where, *parts, key), 'key')

    def walk(mapping: dict[Any, Any], path: tuple[Any, ...]) -> None:
        for key, value in mapping.items():
            if key == 'ros__parameters':
                line, column = doc.position((*path, key), 'key')
                params: dict[str, Any] = {}
                positions: dict[str, tuple[int, int]] = {}
                if isinstance(value, dict):
                    flatten(value, (), (*path, key), params, positions)
                nodes.append(ParameterFileNode('/'.join(str(part) for part in path), params,
                                               positions, line, column, {}))
            elif isinstance(value, dict):
                walk(value, (*path, key))

    if isinstance(data, dict):
        walk(data, ())
    return nodes


def flatten_parameters(values: dict[str, Any], prefix: str = '') -> dict[str, Any]:
    """Nested parameter dicts with names joined by ``.``."""
    out: dict[str, Any] = {}
    for key, value in values.items():
        name = f'{prefix}{key}'
        if isinstance(value, dict):
            out.update(flatten_parameters(value, name + '.'))
        else:
            out[name] = value
    return out
