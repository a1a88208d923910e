"""Frontend entities (XML elements, YAML mappings) to launch actions: one table of tags.

:data:`TAGS` lists, for every launch tag the toolkit reads, its attributes (``*`` marks a
required one) and its nested entity lists; anything else is an error with "did you mean".
Both markup frontends build :class:`FrontendEntity` objects and call :func:`build_description`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, TypeVar

from nodl.diagnostics import Diagnostic, Severity
from nodl.launch import actions as A
from nodl.launch import conditions as C
from nodl.launch import ros_actions as R
from nodl.launch.errors import LaunchProblem
from nodl.launch.model import SourceLocation
from nodl.launch.params import ParameterValue, get_typed_value, type_from_identifier
from nodl.launch.substitution_grammar import parse_if_substitutions, parse_substitution
from nodl.launch.substitutions import TextSubstitution

if TYPE_CHECKING:  # pragma: no cover - for type checkers only
    from nodl.frontends.xml_reader import XmlElement

__all__ = ['FrontendEntity', 'TAGS', 'build_description']

_PROCESS = ('cwd', 'shell', 'emulate_tty', 'additional_env', 'launch-prefix', 'output', 'respawn',
            'respawn_delay', 'respawn_max_retries', 'on_exit', 'sigterm_timeout', 'sigkill_timeout',
            'exec_name', 'log_cmd')
_NODE = ('pkg', 'exec*', 'name', 'namespace', 'args', 'ros_args', 'node-name', *_PROCESS)
_NODE_LISTS = ('param', 'remap', 'env')
_CONDITION = ('if', 'unless')

#: tag -> (attributes, nested entity lists, has child actions).
TAGS: dict[str, tuple[tuple[str, ...], tuple[str, ...], bool]] = {
    'arg': (('name*', 'default', 'description', *_CONDITION), ('choice',), False),
    'let': (('name*', 'value*', *_CONDITION), (), False),
    'include': (('file*', *_CONDITION), ('arg',), False),
    'group': (('scoped', 'forwarding', *_CONDITION), ('keep',), True),
    'push-ros-namespace': (('namespace*', *_CONDITION), (), False),
    'push_ros_namespace': (('namespace*', *_CONDITION), (), False),
    'set_remap': (('from*', 'to*', *_CONDITION), (), False),
    'set_parameter': (('name*', 'value*', *_CONDITION), (), False),
    'set_parameters_from_file': (('filename*', *_CONDITION), (), False),
    'set_env': (('name*', 'value*', *_CONDITION), (), False),
    'unset_env': (('name*', *_CONDITION), (), False),
    'append_env': (('name*', 'value*', 'prepend', 'separator', *_CONDITION), (), False),
    'node': ((*_NODE, *_CONDITION), _NODE_LISTS, False),
    'node_container': ((*_NODE, *_CONDITION), (*_NODE_LISTS, 'composable_node'), False),
    'load_composable_node': (('target*', *_CONDITION), ('composable_node',), False),
    'executable': (('cmd*', 'name', *_PROCESS, *_CONDITION), ('env',), False),
    'log': (('message*', 'level', *_CONDITION), (), False),
    'timer': (('period*', *_CONDITION), (), True),
    'ros_timer': (('period*', *_CONDITION), (), True),
    'shutdown': (('reason', *_CONDITION), (), False),
    'set_use_sim_time': (('value*', *_CONDITION), (), False),
    'set_ros_log_dir': (('new_log_dir*', *_CONDITION), (), False),
}
#: Nested entities: tag -> (attributes, nested lists).
NESTED: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    'choice': (('value*',), ()),
    'keep': (('name*', 'value*'), ()),
    'env': (('name*', 'value*'), ()),
    'remap': (('from*', 'to*'), ()),
    'extra_arg': (('name*', 'value*'), ()),
    'param': (('name', 'value', 'type', 'value-sep', 'from', 'allow_substs'), ('param',)),
    'composable_node': (('pkg*', 'plugin*', 'name*', 'namespace', *_CONDITION),
                        ('param', 'remap', 'extra_arg')),
}
#: Attributes only launch_xml reads (it splits ``NAME`` by ``NAME-sep``); launch_yaml reads
#: no separator (a list is a YAML list) and rejects any key it did not read.
XML_ONLY = frozenset({'value-sep'})


class FrontendEntity:
    """A frontend entity: its tag, attributes, nested entity lists and child actions."""

    __slots__ = ('tag', 'yaml', 'location', 'values', 'positions', 'element', 'nested', 'children', 'stray')

    def __init__(self, tag: str, file: str, line: int, column: int, *, yaml: bool = False) -> None:
        self.tag = tag
        #: True for an entity of a YAML launch file (launch_yaml's rules: no ``NAME-sep``,
        #: values are checked against ``type``, not coerced).
        self.yaml = yaml
        self.location = SourceLocation(file, line, column)
        #: Attribute name -> value as written (text in XML; any YAML scalar or list).
        self.values: dict[str, Any] = {}
        #: Attribute name -> (line, column) where it is written (the YAML frontend's).
        self.positions: dict[str, tuple[int, int]] = {}
        #: The XML element an XML entity is read from: it places an attribute when asked (see
        #: :meth:`position`), which is only when something is wrong or a place is recorded.
        self.element: XmlElement | None = None
        self.nested: dict[str, list[FrontendEntity]] = {}
        self.children: list[FrontendEntity] = []
        #: Where unexpected content is (a YAML child list for a tag without children...).
        self.stray: list[tuple[str, int, int]] = []

    def position(self, name: str) -> tuple[int, int]:
        """Where attribute ``name`` is written (line, column); the entity's place if unknown."""
        if self.element is not None:
            attribute = self.element.get(name)
            if attribute is not None:
                return attribute.line, attribute.column
        return self.positions.get(name, (self.location.line, self.location.column))

    def text(self, name: str) -> str | None:
        """An attribute as text (YAML scalars other than text are written as YAML writes them)."""
        value = self.values.get(name)
        if type(value) is str:  # every XML attribute: no further checks
            return value
        if value is None:  # absent, or YAML's null
            return None
        if isinstance(value, bool):
            return str(value).lower()
        if isinstance(value, (list, dict)):
            raise LaunchProblem('NODL504', f"attribute '{name}' of <{self.tag}> must be text, not a "
                                           f'{type(value).__name__}', self.location.file,
                                *self.position(name))
        return str(value)

    def subs(self, name: str) -> Any:
        """An attribute parsed for substitutions (None when absent)."""
        value = self.values.get(name)
        if value is None:  # absent (most optional attributes), or YAML's null
            return None
        text = value if type(value) is str else self.text(name)  # called for each attribute read
        assert text is not None
        try:
            return parse_substitution(text)
        except LaunchProblem as problem:
            raise LaunchProblem(problem.code, problem.message, self.location.file, *self.position(name)) from None

    def boolean(self, name: str) -> bool | None:
        """A boolean attribute (``true``/``false``/``1``/``0``)."""
        if name not in self.values:
            return None
        value = self.values[name]
        if isinstance(value, bool):
            return value
        text = str(value).strip().lower()
        if text in ('true', '1'):
            return True
        if text in ('false', '0'):
            return False
        raise LaunchProblem('NODL504', f"attribute '{name}' of <{self.tag}> must be true or false, not "
                                       f"'{value}'", self.location.file, *self.position(name))


class _Spec:
    """What a tag allows, as sets made once: :func:`_check` decides the usual entity (nothing
    wrong) by set comparisons, and builds messages only when something is wrong."""

    __slots__ = ('lists', 'children', 'allowed', 'allowed_yaml', 'required', 'required_set', 'lists_set')

    def __init__(self, attributes: tuple[str, ...], lists: tuple[str, ...], children: bool) -> None:
        self.lists = lists
        self.children = children
        self.allowed = frozenset(a.rstrip('*') for a in attributes)
        self.allowed_yaml = self.allowed - XML_ONLY
        self.required = tuple(a[:-1] for a in attributes if a.endswith('*'))
        self.required_set = frozenset(self.required)
        self.lists_set = frozenset(lists)


_SPECS = {tag: _Spec(*spec) for tag, spec in TAGS.items()}
_NESTED_SPECS = {tag: _Spec(attributes, lists, False) for tag, (attributes, lists) in NESTED.items()}
_ROOT_SPEC = _Spec(('deprecated', 'version'), (), True)


def _check(entity: FrontendEntity, spec: _Spec, problems: list[Diagnostic]) -> bool:
    allowed = spec.allowed_yaml if entity.yaml else spec.allowed
    present = entity.values
    if (spec.children or not entity.children) and not ('if' in present and 'unless' in present) and \
            allowed.issuperset(present) and present.keys() >= spec.required_set and \
            spec.lists_set.issuperset(entity.nested):
        return True  # the usual case, decided without building any message
    return _check_slow(entity, set(allowed), spec.required, spec.lists, spec.children, problems)


def _check_slow(entity: FrontendEntity, allowed: set[str], required: tuple[str, ...], lists: tuple[str, ...],
                children: bool, problems: list[Diagnostic]) -> bool:
    from nodl.wording import did_you_mean

    ok = True
    for name in entity.values:
        if name not in allowed and not (name.startswith(('xmlns', 'xsi:')) and not entity.yaml):
            hint = did_you_mean(name, allowed | set(lists)) or next(  # 'sep' -> 'value-sep'
                (f"; did you mean '{a}'?" for a in sorted(allowed) if a.endswith('-' + name)), '')
            if entity.yaml and name in XML_ONLY:
                hint += (f" ('{name}' is launch_xml's: in a YAML launch file a list value is a "
                         'YAML list, [a, b])')
            problems.append(Diagnostic(Severity.ERROR, f"unknown attribute '{name}' of <{entity.tag}>"
                                       f'{hint}; expected '
                                       f'{", ".join(sorted(allowed))}', (), entity.location.file,
                                       *entity.position(name), code='NODL502'))
            ok = False
    for name in required:
        if name not in entity.values:
            problems.append(Diagnostic(Severity.ERROR, f"<{entity.tag}> needs the attribute '{name}'",
                                       (), *entity.location, code='NODL503'))
            ok = False
    for name, items in entity.nested.items():
        if name not in lists:
            known = set(lists) | (set(TAGS) if children else set())
            for item in items:
                problems.append(Diagnostic(Severity.ERROR, f"unexpected <{name}> in <{entity.tag}>"
                                           f'{did_you_mean(name, known)}', (), *item.location,
                                           code='NODL501'))
            ok = False
    if entity.children and not children:
        for child in entity.children:
            problems.append(Diagnostic(Severity.ERROR, f"unexpected <{child.tag}> in <{entity.tag}>"
                                       f'{did_you_mean(child.tag, lists)}; it holds no actions', (),
                                       *child.location, code='NODL501'))
        ok = False
    if 'if' in entity.values and 'unless' in entity.values:
        problems.append(Diagnostic(Severity.ERROR, f"<{entity.tag}> has both 'if' and 'unless'; use one",
                                   (), *entity.location, code='NODL504'))
        ok = False
    return ok


def _nested_ok(entity: FrontendEntity, problems: list[Diagnostic]) -> bool:
    ok = True
    for name, items in entity.nested.items():
        spec = _NESTED_SPECS.get(name)
        if spec is None:
            continue
        for item in items:
            ok = _check(item, spec, problems) and ok
            if item.nested:  # most nested entities (a param, a remap) hold none
                ok = _nested_ok(item, problems) and ok
    return ok


def _condition(entity: FrontendEntity) -> C.Condition | None:
    if_ = entity.subs('if')
    if if_ is not None:
        return C.IfCondition(if_)
    unless = entity.subs('unless')
    return C.UnlessCondition(unless) if unless is not None else None


def _parameters(entity: FrontendEntity) -> list[Any]:
    out: list[Any] = []
    for param in entity.nested.get('param', []):
        source = param.subs('from')
        if source is not None:
            if param.text('name') is not None:
                raise LaunchProblem('NODL504', "<param> takes 'from' or 'name', not both", *param.location)
            entry = R.ParameterFileEntry(source, param.boolean('allow_substs') or False)
            entry.location = param.location  # its findings sit at the <param from=...>
            out.append(entry)
        elif param.text('name') is not None:
            out.append(_named(param, []))
        else:
            raise LaunchProblem('NODL503', "<param> needs 'name' (with 'value' or nested <param>) or 'from'",
                                *param.location)
    return out


def _named(param: FrontendEntity, prefix: list[Any]) -> list[tuple[Any, Any]]:
    name = [*prefix, *([TextSubstitution('.')] if prefix else []), *param.subs('name')]
    nested = param.nested.get('param', [])
    has_value = 'value' in param.values
    identifier = param.text('type')
    if has_value and nested:
        raise LaunchProblem('NODL504', "<param> takes a 'value' or nested <param>, not both", *param.location)
    if nested:
        if identifier is not None:
            raise LaunchProblem('NODL504', "<param> with nested <param> takes no 'type'", *param.location)
        out: list[tuple[Any, Any]] = []
        for child in nested:
            out.extend(_named(child, name))
        return out
    if not has_value:
        raise LaunchProblem('NODL503', f"<param name=\"{param.text('name')}\"> needs a 'value' or nested "
                                       '<param>', *param.location)
    data_type = type_from_identifier(identifier) if identifier is not None else None
    raw = param.values['value']
    if param.yaml:
        if raw is None:  # launch_yaml reads 'value: ~' as no value
            raise LaunchProblem('NODL503', f"<param name=\"{param.text('name')}\"> needs a 'value' or "
                                           'nested <param>', param.location.file, *param.position('value'))
        problem = _yaml_value_problem(raw, data_type, identifier)
        if problem:
            raise LaunchProblem('NODL518', f"parameter '{param.text('name')}': {problem}",
                                param.location.file, *param.position('value'))
    separator = param.text('value-sep')
    try:
        typed = raw
        if isinstance(raw, str):
            typed = get_typed_value(raw.split(separator) if separator else raw, data_type)
        value = ParameterValue(parse_if_substitutions(typed), data_type)
        value.location = param.location  # findings about the value sit at its <param>
        return [(name, value)]
    except LaunchProblem as problem:
        raise LaunchProblem(problem.code, problem.message, param.location.file, *param.position('value')) from None


def _yaml_value_problem(raw: Any, data_type: Any, identifier: str | None) -> str | None:
    """launch_yaml's check of a YAML ``value`` (it converts nothing: text may still hold
    substitutions, any other YAML value must already be of the ``type``), or None."""
    from nodl.launch.params import SCALAR_TYPES, _uniform

    shown = f'{raw!r} ({type(raw).__name__})'
    if data_type is None:
        if isinstance(raw, list):
            if _uniform(raw, True):
                return None
            return f'the list {raw!r} mixes types; a parameter list is uniform'
        if isinstance(raw, SCALAR_TYPES):
            return None
        return (f'the value {shown} is not a parameter value; expected a bool, int, float, '
                'string or a uniform list of them')
    if isinstance(data_type, tuple):
        if isinstance(raw, list) and all(isinstance(x, (str, data_type[1])) for x in raw):
            return None
    elif isinstance(raw, (str, data_type)):
        return None
    return (f"the value {shown} is not of type '{identifier}': launch_yaml checks a YAML value "
            'against the type, it does not convert it (quote it to have it converted)')


def _remaps(entity: FrontendEntity) -> list[tuple[Any, Any]]:
    return [(r.subs('from'), r.subs('to')) for r in entity.nested.get('remap', [])]


_Placed = TypeVar('_Placed', 'R.Node', 'R.ComposableNode')


def _placed(node: _Placed, entity: FrontendEntity) -> _Placed:
    """``node`` (a node action or composable node) told where its ``remap`` entries and its
    ``args``/``ros_args`` are written: findings about a rule point there."""
    node.remap_sources = [r.location for r in entity.nested.get('remap', [])]
    node.place_of = entity.position  # where name= and namespace= are (asked only for a finding)
    if isinstance(node, R.Node) and ('args' in entity.values or 'ros_args' in entity.values):
        node.word_sources = {name: SourceLocation(entity.location.file, *entity.position(name))
                             for name in entity.values if name in ('args', 'ros_args')}
    return node


def _composable(entity: FrontendEntity) -> R.ComposableNode:
    node = R.ComposableNode(package=entity.subs('pkg'), plugin=entity.subs('plugin'), name=entity.subs('name'),
                            namespace=entity.subs('namespace'), parameters=_parameters(entity),
                            remappings=_remaps(entity), condition=_condition(entity),
                            extra_arguments=[{a.text('name') or '': ParameterValue(a.subs('value'), dict_rules=True)}
                                             for a in entity.nested.get('extra_arg', [])])
    node.location = entity.location
    return _placed(node, entity)


def _cmdline(entity: FrontendEntity, name: str) -> list[Any] | None:
    """``args``/``ros_args`` split into words as launch_ros splits them (None when absent)."""
    parts = entity.subs(name)
    if parts is None:
        return None
    import shlex

    words: list[Any] = []
    current: list[Any] = []
    for part in parts:
        if isinstance(part, TextSubstitution):
            text = part.text
            tokens = shlex.split(text)
            if text[:1].isspace() and current:
                words.append(current)
                current = []
            for index, token in enumerate(tokens):
                if index:
                    words.append(current)
                    current = []
                current.append(TextSubstitution(token))
            if text[-1:].isspace() and current:
                words.append(current)
                current = []
        else:
            current.append(part)
    if current:
        words.append(current)
    return words


def _node_kwargs(entity: FrontendEntity) -> dict[str, Any]:
    return dict(executable=entity.subs('exec'), package=entity.subs('pkg'), name=entity.subs('name'),
                namespace=entity.subs('namespace'), parameters=_parameters(entity),
                remappings=_remaps(entity), arguments=_cmdline(entity, 'args'),
                ros_arguments=_cmdline(entity, 'ros_args'))


def build_action(entity: FrontendEntity, problems: list[Diagnostic]) -> A.Action | None:
    """One entity to its action (None, reported, when it is not valid)."""
    spec = _SPECS.get(entity.tag)
    if spec is None:
        from nodl.wording import did_you_mean

        problems.append(Diagnostic(Severity.ERROR, f'unknown launch tag <{entity.tag}>'
                                   f'{did_you_mean(entity.tag, TAGS)}', (), *entity.location, code='NODL501'))
        return None
    if not (_check(entity, spec, problems) and _nested_ok(entity, problems)):
        return None
    tag = entity.tag
    try:
        action = _make(entity, tag, problems)
        action.condition = _condition(entity)
    except LaunchProblem as problem:
        problems.append(problem.diagnostic(*entity.location))
        return None
    action.location = entity.location
    return action


def _children(entity: FrontendEntity, problems: list[Diagnostic]) -> list[A.Action]:
    out = []
    for child in entity.children:
        action = build_action(child, problems)
        if action is not None:
            out.append(action)
    return out


def _make(entity: FrontendEntity, tag: str, problems: list[Diagnostic]) -> A.Action:
    s = entity.subs
    if tag == 'node':  # the usual entity first
        return _placed(R.Node(**_node_kwargs(entity)), entity)
    if tag == 'arg':
        choices = [c.text('value') for c in entity.nested.get('choice', [])]
        return A.DeclareLaunchArgument(entity.text('name') or '', default_value=s('default'),
                                       description=entity.text('description') or '',
                                       choices=choices or None)
    if tag == 'let':
        return A.SetLaunchConfiguration(s('name'), s('value'))
    if tag == 'include':
        return A.IncludeLaunchDescription(s('file'), launch_arguments=[
            (a.subs('name'), a.subs('value')) for a in entity.nested.get('arg', [])])
    if tag == 'group':
        keep = {tuple(k.subs('name')): k.subs('value') for k in entity.nested.get('keep', [])}
        scoped, forwarding = entity.boolean('scoped'), entity.boolean('forwarding')
        return A.GroupAction(_children(entity, problems), scoped=True if scoped is None else scoped,
                             forwarding=True if forwarding is None else forwarding,
                             launch_configurations={k: v for k, v in keep.items()})
    if tag in ('push-ros-namespace', 'push_ros_namespace'):
        return R.PushRosNamespace(s('namespace'))
    if tag == 'set_remap':
        return R.SetRemap(s('from'), s('to'))
    if tag == 'set_parameter':
        return R.SetParameter(s('name'), s('value'))
    if tag == 'set_parameters_from_file':
        return R.SetParametersFromFile(s('filename'))
    if tag == 'set_env':
        return A.SetEnvironmentVariable(s('name'), s('value'))
    if tag == 'unset_env':
        return A.UnsetEnvironmentVariable(s('name'))
    if tag == 'append_env':
        return A.AppendEnvironmentVariable(s('name'), s('value'), prepend=bool(entity.boolean('prepend')),
                                           separator=entity.text('separator') or ':')
    if tag == 'node_container':
        return _placed(R.ComposableNodeContainer(
            composable_node_descriptions=[_composable(c) for c in entity.nested.get('composable_node', [])],
            **_node_kwargs(entity)), entity)
    if tag == 'load_composable_node':
        return R.LoadComposableNodes(
            composable_node_descriptions=[_composable(c) for c in entity.nested.get('composable_node', [])],
            target_container=s('target'))
    if tag in ('timer', 'ros_timer'):
        return A.Ignored(actions=_children(entity, problems))
    if tag == 'executable':
        return A.ExecuteProcess(cmd=s('cmd'))
    return A.Ignored()


def build_description(root: FrontendEntity, problems: list[Diagnostic]) -> A.LaunchDescription | None:
    """The root ``launch`` entity to a :class:`LaunchDescription`."""
    if root.tag != 'launch':
        problems.append(Diagnostic(Severity.ERROR, f"the root is <{root.tag}>; a launch file's root is "
                                   '<launch>', (), *root.location, code='NODL501'))
        return None
    _check(root, _ROOT_SPEC, problems)
    description = A.LaunchDescription(_children(root, problems))
    description.location = root.location
    return description
