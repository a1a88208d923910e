"""ROS names exactly as rcl computes them: validation, expansion, remapping.

This module is the one place where the toolkit turns a name written in a
definition (``scan``, ``~/scan``, ``{node}/scan``, ``/scan``) into the name a
real node uses.  It follows rcl (``rcl/expand_topic_name.c``, ``remap.c``,
``arguments.c``, ``node.c``) and the rmw validators, and its tests compare it
with real rclpy nodes.

* :func:`expand_name` -- ``~``, ``~/x``, ``{node}``, ``{ns}``/``{namespace}``,
  relative and absolute names, as ``rclpy.expand_topic_name`` does.
* :func:`parse_remap_rules` -- ``from:=to``, ``node:from:=to``,
  ``rostopic://``/``rosservice://`` rules, ``__ns:=``, ``__node:=`` and
  ``__name:=``, from a list of rules or a whole ``--ros-args`` command line.
* :func:`node_name_after_remaps`, :func:`node_fqn` -- the node's own final
  name.  The ``__node`` rule is looked up with the node's name as created;
  the ``__ns`` rule with the name after ``__node``.
* :func:`resolve_name` -- expansion, then the first matching rule (a
  node-scoped rule applies only to the node of that final name; the match
  side is expanded against the final name and namespace), then the check
  rmw makes of a fully qualified name.

Invalid names raise :class:`InvalidNameError` (a ``ValueError``) with rcl's
reason; malformed rules raise :class:`InvalidRemapRuleError`.

The older, tolerant helpers :func:`expand`, :func:`fully_qualified` and
:func:`relativize` stay for code that works on names read from a running
graph (already valid): they accept namespaces written without the leading
``/`` or with a trailing one, and do not validate.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Sequence, Union

__all__ = [
    'InvalidNameError', 'InvalidRemapRuleError', 'RemapRule', 'RemapArgs',
    'topic_name_error', 'full_name_error', 'namespace_error', 'node_name_error',
    'normalize_namespace', 'expand_name', 'parse_remap_rule', 'parse_remap_rules',
    'node_name_after_remaps', 'node_namespace_after_remaps', 'node_fqn', 'resolve_name',
    'join_name', 'split_name', 'expand', 'relativize', 'fully_qualified',
]

#: rmw's limits (``RMW_TOPIC_MAX_NAME_LENGTH`` and friends).
TOPIC_MAX_LENGTH = 255 - 8
NAMESPACE_MAX_LENGTH = TOPIC_MAX_LENGTH - 2
NODE_NAME_MAX_LENGTH = 255

_ALNUM = frozenset('abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789')
_DIGITS = frozenset('0123456789')


class InvalidNameError(ValueError):
    """A topic, service, node name or namespace that rcl would reject."""

    def __init__(self, what: str, name: str, reason: str) -> None:
        super().__init__(f"{what} '{name}' is invalid: {reason}")
        #: ``topic name``, ``node name``, ``node namespace`` or ``resolved name``.
        self.what = what
        self.name = name
        #: rcl's (or rmw's) wording of the rule the name breaks.
        self.reason = reason


class InvalidRemapRuleError(ValueError):
    """A remapping rule that rcl cannot parse."""

    def __init__(self, rule: str, reason: str) -> None:
        super().__init__(f'invalid remapping rule {rule!r}: {reason}; expected [NODE:]FROM:=TO, '
                         '[NODE:]__ns:=/NAMESPACE or [NODE:]__node:=NAME')
        self.rule = rule
        self.reason = reason


# -- validation (rcl_validate_topic_name, rmw_validate_*) --------------------------------------


def topic_name_error(name: str) -> str | None:
    """Why rcl rejects ``name`` as a topic/service name before expansion, or ``None``."""
    if not name:
        return 'topic name must not be empty string'
    if name[0] in _DIGITS:
        return 'topic name token must not start with a number'
    if name[-1] == '/':
        return 'topic name must not end with a forward slash'
    in_brace = False
    opening = 0
    for i, char in enumerate(name):
        if char in _ALNUM:
            if char in _DIGITS and in_brace and i == opening + 1:
                return 'substitution name must not start with a number'
        elif char == '_':
            continue
        elif char == '/':
            if in_brace:
                return "substitution name must not contain characters other than alphanumerics or '_'"
        elif char == '~':
            if i != 0:
                return "topic name must not have tilde '~' unless it is the first character"
        elif char == '{':
            if in_brace:
                return "substitution name must not contain characters other than alphanumerics or '_'"
            in_brace, opening = True, i
        elif char == '}':
            if not in_brace:
                return "topic name must not have unmatched (unbalanced) curly braces '{}'"
            in_brace = False
        elif in_brace:
            return "substitution name must not contain characters other than alphanumerics or '_'"
        else:
            return ("topic name must not contain characters other than alphanumerics, '_', '~', "
                    "'{', or '}'")
    if in_brace:
        return "topic name must not have unmatched (unbalanced) curly braces '{}'"
    # rcl looks at every character but the last one here (so '~x' passes, '~xy' does not)
    for i in range(len(name) - 1):
        if name[i] == '/':
            if name[i + 1] in _DIGITS:
                return 'topic name token must not start with a number'
        elif i == 1 and name[0] == '~':
            return "topic name must not have a tilde '~' that is not followed by a forward slash '/'"
    return None


def full_name_error(name: str) -> str | None:
    """Why rmw rejects ``name`` as a fully qualified topic/service name, or ``None``."""
    if not name:
        return 'topic name must not be empty'
    if name[0] != '/':
        return "topic name must be absolute, it must lead with a '/'"
    if name[-1] == '/':
        return "topic name must not end with a '/'"
    for char in name:
        if char not in _ALNUM and char not in '_/':
            return "topic name must not contain characters other than alphanumerics, '_', or '/'"
    for i in range(len(name) - 1):
        if name[i] == '/':
            if name[i + 1] == '/':
                return "topic name must not contain repeated '/'"
            if name[i + 1] in _DIGITS:
                return 'topic name must not have a token that starts with a number'
    if len(name) > TOPIC_MAX_LENGTH:
        return f"topic length should not exceed '{TOPIC_MAX_LENGTH}'"
    return None


def namespace_error(namespace: str) -> str | None:
    """Why rmw rejects ``namespace`` (absolute, as a node holds it), or ``None``."""
    if namespace == '/':
        return None
    problem = full_name_error(namespace)
    if problem is not None and not problem.startswith('topic length'):
        problem = problem.replace('topic name', 'namespace')
        if problem.endswith("end with a '/'"):
            problem += ", unless only a '/'"
        return problem
    if len(namespace) > NAMESPACE_MAX_LENGTH:
        return f"namespace should not exceed '{NAMESPACE_MAX_LENGTH}'"
    return None


def node_name_error(name: str) -> str | None:
    """Why rmw rejects ``name`` as a node name, or ``None``."""
    if not name:
        return 'node name must not be empty'
    if any(c not in _ALNUM and c != '_' for c in name):
        return "node name must not contain characters other than alphanumerics or '_'"
    if name[0] in _DIGITS:
        return 'node name must not start with a number'
    if len(name) > NODE_NAME_MAX_LENGTH:
        return f"node name length should not exceed '{NODE_NAME_MAX_LENGTH}'"
    return None


def normalize_namespace(namespace: str) -> str:
    """The namespace as ``rcl_node_init`` takes it: ``''`` is ``/``, ``a`` is ``/a``."""
    if not namespace:
        return '/'
    return namespace if namespace.startswith('/') else '/' + namespace


def _check_node(node_name: str, namespace: str) -> str:
    problem = node_name_error(node_name)
    if problem:
        raise InvalidNameError('node name', node_name, problem)
    namespace = normalize_namespace(namespace)
    problem = namespace_error(namespace)
    if problem:
        raise InvalidNameError('node namespace', namespace, problem)
    return namespace


# -- expansion (rcl_expand_topic_name) ---------------------------------------------------------

_SUBSTITUTIONS = ('{node}', '{ns}', '{namespace}')


def _expand(name: str, node_name: str, namespace: str) -> str:
    """rcl's expansion of a valid ``name`` for a node in the absolute ``namespace``."""
    root = namespace == '/'
    has_substitution = '{' in name
    if name.startswith('/') and not has_substitution:
        return name
    if name.startswith('~'):
        name = (namespace if root else namespace + '/') + node_name + name[1:]
    if has_substitution:
        while '{' in name:
            start = name.index('{')
            key = name[start:name.index('}', start) + 1]
            if key not in _SUBSTITUTIONS:
                raise InvalidNameError('topic name', name, f'unknown substitution: {key}')
            name = name.replace(key, node_name if key == '{node}' else namespace)
    if not name.startswith('/'):
        name = (namespace if root else namespace + '/') + name
    return name


def expand_name(name: str, node_name: str, namespace: str) -> str:
    """The fully qualified form of ``name`` for the node ``node_name`` in ``namespace``.

    The same result as ``rclpy.expand_topic_name`` (which may still be an
    invalid full name, e.g. ``{ns}/x`` in ``/`` gives ``//x``; :func:`resolve_name`
    checks that).  ``namespace`` is taken as a node takes it: ``''`` means
    ``/`` and a missing leading ``/`` is added.  Raises
    :class:`InvalidNameError` for an invalid name, node name or namespace.
    """
    problem = topic_name_error(name)
    if problem:
        raise InvalidNameError('topic name', name, problem)
    namespace = _check_node(node_name, namespace)
    return _expand(name, node_name, namespace)


# -- remapping rules (rcl arguments.c lexer and parser) ----------------------------------------

#: What a rule remaps: ``name`` (topics and services), ``topic`` (``rostopic://``),
#: ``service`` (``rosservice://``), ``namespace`` (``__ns``) or ``node`` (``__node``/``__name``).
RULE_KINDS = ('name', 'topic', 'service', 'namespace', 'node')


@dataclass(frozen=True)
class RemapRule:
    """One remapping rule, as rcl parses ``[node:]match:=replacement``."""

    #: One of :data:`RULE_KINDS`.
    kind: str
    #: The side to replace; ``None`` for ``__ns`` and ``__node`` rules.
    match: str | None
    #: The replacement: a name, a namespace (``__ns``) or a node name (``__node``).
    replacement: str
    #: The node the rule is limited to (``node:...``), or ``None`` for every node.
    node: str | None = None
    #: The rule as written.
    text: str = ''

    def applies_to(self, node_name: str) -> bool:
        """True if the rule is for every node or for ``node_name``."""
        return self.node is None or self.node == node_name

    def __str__(self) -> str:
        return self.text or _format_rule(self)


def _format_rule(rule: RemapRule) -> str:
    scope = f'{rule.node}:' if rule.node else ''
    if rule.kind == 'node':
        return f'{scope}__node:={rule.replacement}'
    if rule.kind == 'namespace':
        return f'{scope}__ns:={rule.replacement}'
    url = {'topic': 'rostopic://', 'service': 'rosservice://'}.get(rule.kind, '')
    return f'{scope}{url}{rule.match}:={rule.replacement}'


# lexemes
_TOKEN, _SLASH, _TILDE_SLASH, _SEP, _COLON, _NS, _NODE, _URL_TOPIC, _URL_SERVICE, _EOF = (
    'token', "'/'", "'~/'", "':='", "':'", "'__ns'", "'__node'", "'rostopic://'",
    "'rosservice://'", 'end of rule')
_WILD, _BACKREF = "'*'", 'backreference'


def _token_end(text: str, i: int) -> int:
    """End of rcl's name token starting at ``text[i]`` (a letter or a single ``_``)."""
    after_underscore = text[i] == '_'
    i += 1
    while i < len(text):
        char = text[i]
        if char in _ALNUM:
            after_underscore = False
        elif char == '_' and not after_underscore:
            after_underscore = True
        else:
            break
        i += 1
    return i


def _lex(rule: str) -> list[tuple[str, str, int]]:
    """rcl's lexemes of a rule: ``(kind, text, position)``; raises on a character it rejects."""
    out: list[tuple[str, str, int]] = []
    i = 0
    while i < len(rule):
        rest = rule[i:]
        if rest.startswith(':='):
            kind, end = _SEP, i + 2
        elif rest[0] == ':':
            kind, end = _COLON, i + 1
        elif rest[0] == '/':
            kind, end = _SLASH, i + 1
        elif rest.startswith('~/'):
            kind, end = _TILDE_SLASH, i + 2
        elif rest.startswith('rostopic://'):
            kind, end = _URL_TOPIC, i + len('rostopic://')
        elif rest.startswith('rosservice://'):
            kind, end = _URL_SERVICE, i + len('rosservice://')
        elif rest.startswith('__'):
            for word, kind in (('__ns', _NS), ('__node', _NODE), ('__name', _NODE)):
                if rest.startswith(word):
                    end = i + len(word)
                    break
            else:
                raise InvalidRemapRuleError(rule, f"'{rest[:3]}' at index {i} starts no name "
                                            "(only __ns, __node and __name start with '__')")
        elif rest[0] == '*':
            kind, end = _WILD, i + (2 if rest.startswith('**') else 1)
        elif rest[0] == '\\' and rest[1:2] in _DIGITS and rest[1:2] != '0':
            kind, end = _BACKREF, i + 2
        elif rest[0] in _ALNUM and rest[0] not in _DIGITS or rest[0] == '_':
            kind, end = _TOKEN, _token_end(rule, i)
        else:
            raise InvalidRemapRuleError(rule, f'unexpected {rest[0]!r} at index {i}')
        out.append((kind, rule[i:end], i))
        i = end
    out.append((_EOF, '', len(rule)))
    return out


class _Parser:
    def __init__(self, rule: str) -> None:
        self.rule = rule
        self.lexemes = _lex(rule)
        self.pos = 0

    def peek(self, ahead: int = 0) -> str:
        return self.lexemes[min(self.pos + ahead, len(self.lexemes) - 1)][0]

    def take(self, *kinds: str) -> str:
        kind, text, index = self.lexemes[self.pos]
        if kind not in kinds:
            if kind == _WILD:
                raise InvalidRemapRuleError(self.rule, 'wildcards are not implemented by rcl')
            if kind == _BACKREF:
                raise InvalidRemapRuleError(self.rule, 'backreferences are not implemented by rcl')
            found = f'{text!r}' if text else 'the end'
            raise InvalidRemapRuleError(self.rule, f"expected {' or '.join(kinds)} at index "
                                        f'{index}, found {found}')
        self.pos += 1
        return text

    def name(self, end: str) -> str:
        """``['~/' | '/'] token ('/' token)*`` up to ``end``."""
        start = self.lexemes[self.pos][2]
        if self.peek() in (_TILDE_SLASH, _SLASH):
            self.pos += 1
        self.take(_TOKEN)
        while self.peek() != end:
            self.take(_SLASH, end)
            self.take(_TOKEN)
        return self.rule[start:self.lexemes[self.pos][2]]

    def parse(self) -> RemapRule:
        node = None
        if self.peek() == _TOKEN and self.peek(1) == _COLON:
            node = self.take(_TOKEN)
            self.pos += 1
        if self.peek() == _NODE:
            self.pos += 1
            self.take(_SEP)
            if self.peek() != _TOKEN:
                raise InvalidRemapRuleError(self.rule, 'a node name is a single token of letters, '
                                            "digits and '_' (not starting with a digit)")
            rule = RemapRule('node', None, self.take(_TOKEN), node, self.rule)
        elif self.peek() == _NS:
            self.pos += 1
            self.take(_SEP)
            start = self.lexemes[self.pos][2]
            if self.peek() != _SLASH:
                raise InvalidRemapRuleError(self.rule, "the namespace must be fully qualified "
                                            "(start with '/')")
            self.pos += 1
            while self.peek() == _TOKEN:
                self.pos += 1
                if self.peek() != _SLASH:
                    break
                self.pos += 1
            rule = RemapRule('namespace', None, self.rule[start:self.lexemes[self.pos][2]], node,
                             self.rule)
        else:
            kind = 'name'
            if self.peek() in (_URL_TOPIC, _URL_SERVICE):
                kind = 'topic' if self.take(_URL_TOPIC, _URL_SERVICE).startswith('rostopic') \
                    else 'service'
            match = self.name(_SEP)
            self.take(_SEP)
            rule = RemapRule(kind, match, self.name(_EOF), node, self.rule)
        self.take(_EOF)
        return rule


def parse_remap_rule(rule: str) -> RemapRule:
    """Parse one rule as rcl does; raises :class:`InvalidRemapRuleError`."""
    return _Parser(rule).parse()


#: What the functions taking remapping rules accept: :class:`RemapRule` objects,
#: ``from:=to`` strings, or a command line with ``--ros-args``.
RemapArgs = Union[Sequence[RemapRule], Sequence[str], Iterable[Union[str, RemapRule]], None]

_REMAP_FLAGS = ('-r', '--remap')
# ROS arguments that take a value (skipped with it); the others are single flags.
_VALUE_FLAGS = ('-p', '--param', '--params-file', '--log-level', '--log-config-file', '-e',
                '--enclave')


def parse_remap_rules(args: RemapArgs) -> list[RemapRule]:
    """The remapping rules in ``args``, in order (the first matching rule wins).

    ``args`` is either a list of rules (``['a:=b', 'node:c:=d', '__ns:=/x']``),
    or a command line holding ``--ros-args`` (``['--ros-args', '-r', 'a:=b',
    '--remap', 'c:=d', '-p', 'x:=1', '--', ...]``): there, rules follow
    ``-r``/``--remap``, other ROS arguments are skipped, ``--`` ends the ROS
    arguments (until another ``--ros-args``), and outside them an argument
    that is a rule counts, as rcl still accepts that older form.
    :class:`RemapRule` objects are passed through.  Raises
    :class:`InvalidRemapRuleError` for a malformed rule.
    """
    if args is None:
        return []
    items = list(args)
    if not any(item == '--ros-args' for item in items):
        return [item if isinstance(item, RemapRule) else parse_remap_rule(item) for item in items]
    rules: list[RemapRule] = []
    in_ros_args = False
    i = 0
    while i < len(items):
        item = items[i]
        if isinstance(item, RemapRule):
            rules.append(item)
        elif item == '--ros-args':
            in_ros_args = True
        elif not in_ros_args:
            try:
                rules.append(parse_remap_rule(item))
            except InvalidRemapRuleError:
                pass  # an argument of the program, not a rule
        elif item == '--':
            in_ros_args = False
        elif item in _REMAP_FLAGS:
            if i + 1 >= len(items):
                raise InvalidRemapRuleError('', f'{item} at the end of the arguments has no rule')
            i += 1
            rules.append(parse_remap_rule(str(items[i])))
        elif item in _VALUE_FLAGS:
            i += 1
        i += 1
    return rules


# -- applying rules (rcl remap.c, node.c, node_resolve_name.c) ---------------------------------


def node_name_after_remaps(node_name: str, remap_args: RemapArgs = None) -> str:
    """The node's name after the first ``__node`` rule for it (matched on ``node_name``)."""
    for rule in parse_remap_rules(remap_args):
        if rule.kind == 'node' and rule.applies_to(node_name):
            return rule.replacement
    return node_name


def node_namespace_after_remaps(node_name: str, namespace: str,
                                remap_args: RemapArgs = None) -> str:
    """The node's namespace after the first ``__ns`` rule for it.

    As in ``rcl_node_init``, the ``__ns`` rule's node scope is compared with
    the node's name after its ``__node`` rule.
    """
    rules = parse_remap_rules(remap_args)
    final_name = node_name_after_remaps(node_name, rules)
    for rule in rules:
        if rule.kind == 'namespace' and rule.applies_to(final_name):
            return rule.replacement
    return normalize_namespace(namespace)


def _final_node(node_name: str, namespace: str,
                rules: list[RemapRule]) -> tuple[str, str]:
    _check_node(node_name, namespace)
    final_name = node_name_after_remaps(node_name, rules)
    final_namespace = node_namespace_after_remaps(node_name, namespace, rules)
    problem = namespace_error(final_namespace)
    if problem:
        raise InvalidNameError('node namespace', final_namespace, problem)
    return final_name, final_namespace


def node_fqn(node_name: str, namespace: str, remap_args: RemapArgs = None) -> str:
    """The fully qualified name of a node created as ``Node(node_name, namespace=...)``
    with ``remap_args`` (``__node``, ``__name`` and ``__ns`` rules change it)."""
    final_name, final_namespace = _final_node(node_name, namespace, parse_remap_rules(remap_args))
    return join_name(final_namespace, final_name)


def resolve_name(name: str, node_name: str, namespace: str, remap_args: RemapArgs = None, *,
                 service: bool = False) -> str:
    """The name a real node (``Node(node_name, namespace=...)`` with ``remap_args``) uses for
    the topic (or, with ``service=True``, the service) ``name``.

    As ``Node.resolve_topic_name`` / ``resolve_service_name``: the name is
    expanded against the node's final name and namespace, the first rule that
    applies to the node (and to topics, or services) and whose expanded match
    side equals it replaces it with its expanded replacement, and the result
    must be a valid fully qualified name (else :class:`InvalidNameError`).
    """
    rules = parse_remap_rules(remap_args)
    final_name, final_namespace = _final_node(node_name, namespace, rules)
    problem = topic_name_error(name)
    if problem:
        raise InvalidNameError('topic name', name, problem)
    resolved = _expand(name, final_name, final_namespace)
    wanted = 'service' if service else 'topic'
    for rule in rules:
        if rule.kind not in ('name', wanted) or not rule.applies_to(final_name):
            continue
        assert rule.match is not None
        if _expand(rule.match, final_name, final_namespace) == resolved:
            resolved = _expand(rule.replacement, final_name, final_namespace)
            break
    problem = full_name_error(resolved)
    if problem:
        raise InvalidNameError('resolved name', resolved, problem)
    return resolved


# -- joining and splitting fully qualified names -----------------------------------------------


def join_name(namespace: str, name: str) -> str:
    """``namespace`` + ``/`` + ``name``, without doubling the root's ``/``."""
    namespace = '/' + namespace.strip('/') if namespace.strip('/') else ''
    return f'{namespace}/{name}'


def split_name(fqn: str) -> tuple[str, str]:
    """``/ns/sub/name`` -> ``('/ns/sub', 'name')``; a bare name is in ``/``."""
    fqn = fqn.strip()
    if not fqn.startswith('/'):
        fqn = '/' + fqn
    namespace, _, base = fqn.rpartition('/')
    return namespace or '/', base


# -- tolerant helpers for names read from a running graph --------------------------------------


def fully_qualified(namespace: str, name: str) -> str:
    """``/namespace/name`` for a node (the namespace may lack its ``/`` or have extra ones)."""
    return join_name(namespace, name)


def expand(name: str, node_name: str, namespace: str) -> str:
    """The fully qualified form of topic/service/action ``name`` for the given node.

    Like :func:`expand_name` without validation, and with a namespace that
    may be written without its leading ``/`` or with a trailing one.
    """
    ns = '/' + namespace.strip('/') if namespace.strip('/') else '/'
    return _expand(name, node_name, ns)


def relativize(name: str, node_name: str, namespace: str) -> str:
    """The shortest faithful form of an absolute ``name`` for this node.

    Under the node: ``~/x``.  Under its namespace (not at the root): ``x``.
    Otherwise the absolute name.
    """
    own = fully_qualified(namespace, node_name)
    if name == own:
        return '~'
    if name.startswith(own + '/'):
        return '~' + name[len(own):]
    ns = '/' + namespace.strip('/') if namespace.strip('/') else ''
    if ns and name.startswith(ns + '/'):
        return name[len(ns) + 1:]
    return name
