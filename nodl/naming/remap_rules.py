"""Remapping rules as rcl parses them (``rcl/src/rcl/arguments.c`` and its lexer).

``[node:]match:=replacement`` (``match`` optionally ``rostopic://`` or
``rosservice://``), ``[node:]__ns:=/namespace`` and ``[node:]__node:=name``
(``__name`` is the same).  Names in rules are plain tokens joined by ``/``,
optionally starting with ``/`` or ``~/``: no substitutions, wildcards or
backreferences (rcl does not implement them).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterable, Sequence

from nodl.naming.validation import ALNUM, DIGITS

__all__ = [
    'RULE_KINDS',
    'InvalidRemapRuleError',
    'RemapArgs',
    'RemapRule',
    'parse_remap_rule',
    'parse_remap_rules',
]


class InvalidRemapRuleError(ValueError):
    """A remapping rule that rcl cannot parse."""

    def __init__(self, rule: str, reason: str) -> None:
        super().__init__(f'invalid remapping {rule!r}: {reason}; expected [NODE:]FROM:=TO, '
                         '[NODE:]__ns:=/NAMESPACE or [NODE:]__node:=NAME')
        self.rule = rule
        self.reason = reason


# -- remapping rules (rcl arguments.c lexer and parser) ----------------------------------------

#: What a rule remaps: ``name`` (topics and services), ``topic`` (``rostopic://``),
#: ``service`` (``rosservice://``), ``namespace`` (``__ns``) or ``node`` (``__node``/``__name``).
RULE_KINDS = ('name', 'topic', 'service', 'namespace', 'node')


class RemapRule:
    """One remapping rule, as rcl parses ``[node:]match:=replacement``.

    Immutable and compared by value (its fields, as a frozen dataclass would be; a plain
    class because ``nodl validate`` loads this package and cannot afford the start-up
    time of :mod:`dataclasses`).
    """

    __slots__ = ('kind', 'match', 'node', 'replacement', 'text')

    #: One of :data:`RULE_KINDS`.
    kind: str
    #: The side to replace; ``None`` for ``__ns`` and ``__node`` rules.
    match: str | None
    #: The replacement: a name, a namespace (``__ns``) or a node name (``__node``).
    replacement: str
    #: The node the rule is limited to (``node:...``), or ``None`` for every node.
    node: str | None
    #: The rule as written.
    text: str

    def __init__(self, kind: str, match: str | None, replacement: str, node: str | None = None,
                 text: str = '') -> None:
        # (object.__setattr__: this class's own refuses every assignment)
        object.__setattr__(self, 'kind', kind)
        object.__setattr__(self, 'match', match)
        object.__setattr__(self, 'replacement', replacement)
        object.__setattr__(self, 'node', node)
        object.__setattr__(self, 'text', text)

    def _fields(self) -> tuple[str, str | None, str, str | None, str]:
        return (self.kind, self.match, self.replacement, self.node, self.text)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, RemapRule) and other.__class__ is self.__class__:
            return self._fields() == other._fields()
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self._fields())

    def __repr__(self) -> str:
        return (f'{type(self).__name__}(kind={self.kind!r}, match={self.match!r}, '
                f'replacement={self.replacement!r}, node={self.node!r}, text={self.text!r})')

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f'cannot assign to field {name!r}: a RemapRule is immutable')

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f'cannot delete field {name!r}: a RemapRule is immutable')

    def __reduce__(self) -> tuple[type[RemapRule], tuple[str, str | None, str, str | None, str]]:
        return (type(self), self._fields())

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
        if char in ALNUM:
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
            for word, word_kind in (('__ns', _NS), ('__node', _NODE), ('__name', _NODE)):
                if rest.startswith(word):
                    kind, end = word_kind, i + len(word)
                    break
            else:
                raise InvalidRemapRuleError(rule, f"'{rest[:3]}' at index {i} starts no name "
                                            "(only __ns, __node and __name start with '__')")
        elif rest[0] == '*':
            kind, end = _WILD, i + (2 if rest.startswith('**') else 1)
        elif rest[0] == '\\' and rest[1:2] in DIGITS and rest[1:2] != '0':
            kind, end = _BACKREF, i + 2
        elif rest[0] in ALNUM and rest[0] not in DIGITS or rest[0] == '_':
            kind, end = _TOKEN, _token_end(rule, i)
        else:
            raise InvalidRemapRuleError(rule, f'unexpected {rest[0]!r} at index {i}')
        out.append((kind, rule[i:end], i))
        i = end
    out.append((_EOF, '', len(rule)))
    return out


class _RemapRuleParser:
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
    return _RemapRuleParser(rule).parse()


#: What the functions taking remapping rules accept: :class:`RemapRule` objects,
#: ``from:=to`` strings, or a command line with ``--ros-args``.
RemapArgs = Sequence[RemapRule] | Sequence[str] | Iterable[str | RemapRule] | None

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
    if not items:
        return []
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
            with contextlib.suppress(InvalidRemapRuleError):  # else an argument of the program, not a rule
                rules.append(parse_remap_rule(item))
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
