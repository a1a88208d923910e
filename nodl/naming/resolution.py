"""Expansion and remapping of names for a node (``rcl_expand_topic_name``, ``remap.c``,
``rcl_node_init``, ``rcl_node_resolve_name``), and joining/splitting full names."""

from __future__ import annotations

from functools import lru_cache

from nodl.naming.remap_rules import RemapArgs, RemapRule, parse_remap_rules
from nodl.naming.validation import (
    _VALID_FULL_NAME,
    TOPIC_MAX_LENGTH,
    InvalidNameError,
    checked_namespace,
    full_name_error,
    namespace_error,
    normalize_namespace,
    topic_name_error,
)
from nodl.vocabulary import NAME_SUBSTITUTIONS

__all__ = [
    'NodeNames',
    'declared_name_error',
    'declared_names',
    'expand',
    'expand_name',
    'fully_qualified',
    'join_name',
    'node_fqn',
    'node_name_after_remaps',
    'node_namespace_after_remaps',
    'relativize',
    'resolve_name',
    'split_name',
]


# -- expansion (rcl_expand_topic_name) ---------------------------------------------------------

_SUBSTITUTIONS = tuple('{' + word + '}' for word in NAME_SUBSTITUTIONS)


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
    namespace = checked_namespace(node_name, namespace)
    return _expand(name, node_name, namespace)


@lru_cache(maxsize=4096)  # definitions declare the same few names again and again
def declared_name_error(name: str) -> str | None:
    """Why rcl refuses ``name`` as a topic, service or action name a node declares, or ``None``.

    The one check of a name written in a definition: rcl's check before expansion
    (:func:`topic_name_error`), its expansion (only ``{node}``, ``{ns}`` and
    ``{namespace}`` are known), then rmw's check of the fully qualified result (no
    repeated ``/``), for a node ``n`` in ``/ns``.  The reason is rcl's (or rmw's)
    wording.  A name valid there is valid for every node, except a substitution that
    expands to the root namespace (``{ns}//x``), which only an instance can tell.
    """
    problem = topic_name_error(name)
    if problem is not None:
        return problem
    try:
        expanded = _expand(name, 'n', '/ns')
    except InvalidNameError as exc:
        return exc.reason
    return full_name_error(expanded)


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


class NodeNames:
    """A node's final name and namespace with its rules: resolves names as the node does.

    Build it with :meth:`create` from the name and namespace a node is
    created with (``__node``/``__ns`` rules are applied), or directly from the
    final name and namespace of a running node (as the graph reports them).
    Immutable and compared by value (name, namespace, rules), as a frozen dataclass
    would be (a plain class: ``nodl validate`` cannot afford loading :mod:`dataclasses`).
    """

    __slots__ = ('_prefixes_', '_tables', 'fqn', 'name', 'namespace', 'rules')

    #: The node's final name.
    name: str
    #: The node's final, absolute namespace.
    namespace: str
    #: Every rule the node was given (``__node``/``__ns`` rules are already reflected above).
    rules: tuple[RemapRule, ...]
    #: ``/namespace/name``.
    fqn: str
    # What follows is asked for every entity of every launched node: what depends on the
    # node only (its checked namespace, the prefixes names expand to, its rules' expanded
    # match sides) is computed once, when first asked, and kept beside the fields (not
    # compared, not shown).
    _prefixes_: tuple[str, str, str] | None
    _tables: tuple[tuple[dict[str, RemapRule], str | None], ...] | None

    def __init__(self, name: str, namespace: str, rules: tuple[RemapRule, ...] = ()) -> None:
        # (object.__setattr__: this class's own refuses every assignment)
        object.__setattr__(self, 'name', name)
        object.__setattr__(self, 'namespace', namespace)
        object.__setattr__(self, 'rules', rules)
        object.__setattr__(self, 'fqn', join_name(namespace, name))
        object.__setattr__(self, '_prefixes_', None)
        object.__setattr__(self, '_tables', None)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, NodeNames) and other.__class__ is self.__class__:
            return (self.name, self.namespace, self.rules) == (other.name, other.namespace, other.rules)
        return NotImplemented

    def __hash__(self) -> int:
        return hash((self.name, self.namespace, self.rules))

    def __repr__(self) -> str:
        return (f'{type(self).__name__}(name={self.name!r}, namespace={self.namespace!r}, '
                f'rules={self.rules!r})')

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f'cannot assign to field {name!r}: NodeNames are immutable')

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f'cannot delete field {name!r}: NodeNames are immutable')

    def __reduce__(self) -> tuple[type[NodeNames], tuple[str, str, tuple[RemapRule, ...]]]:
        return (type(self), (self.name, self.namespace, self.rules))

    @classmethod
    def create(cls, node_name: str, namespace: str, remap_args: RemapArgs = None) -> NodeNames:
        """The node ``Node(node_name, namespace=namespace)`` given ``remap_args`` becomes.

        Raises :class:`InvalidNameError` when rcl would refuse to create it.
        """
        rules = parse_remap_rules(remap_args) if remap_args else []  # (most nodes: none)
        namespace = checked_namespace(node_name, namespace)
        if not rules:  # most launched nodes: nothing renames them, and both names are checked
            names = cls(node_name, namespace, ())
            under = namespace if namespace == '/' else namespace + '/'
            object.__setattr__(names, '_prefixes_', (namespace, names.fqn, under))
            return names
        final_name = node_name_after_remaps(node_name, rules)
        # rcl_node_init: the __ns rule's node scope is compared with the name after __node
        for rule in rules:
            if rule.kind == 'namespace' and rule.applies_to(final_name):
                problem = namespace_error(rule.replacement)
                if problem:
                    raise InvalidNameError('node namespace', rule.replacement, problem)
                return cls(final_name, rule.replacement, tuple(rules))
        return cls(final_name, namespace, tuple(rules))

    def _checked_namespace(self) -> str:
        """The node's namespace, its name and namespace checked once (:func:`expand_name`
        checks them for every name; a node expands many)."""
        return self._prefixes()[0]

    def _prefixes(self) -> tuple[str, str, str]:
        """``(checked namespace, what '~' stands for, what a relative name is put under)``;
        raises :class:`InvalidNameError` if the node's name or namespace is invalid."""
        prefixes = self._prefixes_
        if prefixes is None:
            namespace = checked_namespace(self.name, self.namespace)
            under = namespace if namespace == '/' else namespace + '/'
            prefixes = (namespace, under + self.name, under)  # (as create() without rules)
            object.__setattr__(self, '_prefixes_', prefixes)
        return prefixes

    def _expanded(self, name: str) -> str:
        """:func:`_expand` of a ``name`` :func:`topic_name_error` accepts, for this node."""
        prefixes = self._prefixes_ or self._prefixes()
        if '{' in name:
            return _expand(name, self.name, prefixes[0])
        first = name[0]
        if first == '/':
            return name
        if first == '~':
            return prefixes[1] + name[1:]
        return prefixes[2] + name

    def expand(self, name: str) -> str:
        """``name`` expanded for this node (no remapping); see :func:`expand_name`."""
        problem = topic_name_error(name)
        if problem:
            raise InvalidNameError('topic name', name, problem)
        return self._expanded(name)

    def rule_for(self, name: str, *, service: bool = False) -> RemapRule | None:
        """The rule that remaps ``name`` (a topic, or a service) for this node, if one does."""
        return self._rule_for_expanded(self.expand(name), service)

    def _rule_for_expanded(self, expanded: str, service: bool) -> RemapRule | None:
        if not self.rules:
            return None
        tables = self._tables or self._rule_tables()
        found, failing = tables[1 if service else 0]
        rule = found.get(expanded)
        if rule is None and failing is not None:
            _expand(failing, self.name, self.namespace)  # raises, as the rule-by-rule search did
        return rule

    def _rule_tables(self) -> tuple[tuple[dict[str, RemapRule], str | None], ...]:
        """For topics, then services: expanded match side -> the first rule that applies to
        this node with it, and the match side of the first such rule that does not expand
        (the rules after it are never reached)."""
        tables = []
        for wanted in ('topic', 'service'):
            found: dict[str, RemapRule] = {}
            failing = None
            for rule in self.rules:
                if rule.kind in ('name', wanted) and rule.applies_to(self.name):
                    assert rule.match is not None
                    try:
                        found.setdefault(_expand(rule.match, self.name, self.namespace), rule)
                    except ValueError:
                        failing = rule.match
                        break
            tables.append((found, failing))
        out = tuple(tables)
        object.__setattr__(self, '_tables', out)
        return out

    def topic_remaps(self) -> dict[str, str]:
        """The topic rules that apply to this node, as expanded FROM -> TO (first rule wins).

        Rules for services only (``rosservice://``) and ``__node``/``__ns`` rules have no entry.
        """
        out: dict[str, str] = {}
        for rule in self.rules:
            if rule.kind in ('name', 'topic') and rule.applies_to(self.name) and rule.match:
                out.setdefault(_expand(rule.match, self.name, self.namespace),
                               _expand(rule.replacement, self.name, self.namespace))
        return out

    def resolve(self, name: str, *, service: bool = False) -> str:
        """The final name of the topic (or service) ``name``; see :func:`resolve_name`.

        An action's name resolves as a topic name (as ``rcl_action`` does).
        """
        # Every entity of every launched node comes here, and the regular expression of a full
        # name was most of the cost: what depends on the written name alone (is it valid, which
        # of the node's prefixes it goes under, is what it adds valid) is asked once per name.
        problem, under, tail, tail_valid = _name_shape(name)
        if problem:
            raise InvalidNameError('topic name', name, problem)
        # (the prefixes asked even for an absolute name: they check the node's own names)
        prefixes = self._prefixes_ or self._prefixes()
        if under > 0:
            resolved = prefixes[under] + tail
        elif under:
            resolved = self._expanded(name)  # with substitutions
        else:
            resolved = name
        if self.rules:
            rule = self._rule_for_expanded(resolved, service)
            if rule is not None:
                resolved = _expand(rule.replacement, self.name, self.namespace)
                tail_valid = False
        if tail_valid and len(resolved) <= TOPIC_MAX_LENGTH:
            return resolved
        # full_name_error's own first test, inline
        if len(resolved) > TOPIC_MAX_LENGTH or _VALID_FULL_NAME.fullmatch(resolved) is None:
            problem = full_name_error(resolved)
            if problem:
                raise InvalidNameError('resolved name', resolved, problem)
        return resolved


@lru_cache(maxsize=4096)  # the same few names are declared by many nodes (every base's)
def _name_shape(name: str) -> tuple[str | None, int, str, bool]:
    """``(problem, under, tail, tail_valid)`` of a written topic or service ``name``.

    ``problem``: :func:`topic_name_error`.  A name without substitutions expands to the
    node's prefix ``under`` (1: what ``~`` stands for, 2: what a relative name goes under,
    see :meth:`NodeNames._prefixes`; 0: none, the name is absolute) followed by ``tail``;
    ``under`` is -1 for a name with substitutions.  ``tail_valid``: that expansion is a
    valid full name (the prefixes are: a checked namespace and node name) short of its
    length, so the full name need not be matched again for every node.
    """
    problem = topic_name_error(name)
    if problem or '{' in name:
        return problem, -1, name, False
    first = name[0]
    if first == '/':
        return None, 0, name, _VALID_FULL_NAME.fullmatch(name) is not None
    if first == '~':
        tail = name[1:]
        return None, 1, tail, not tail or _VALID_FULL_NAME.fullmatch(tail) is not None
    return None, 2, name, _VALID_FULL_NAME.fullmatch('/' + name) is not None


def node_fqn(node_name: str, namespace: str, remap_args: RemapArgs = None) -> str:
    """The fully qualified name of a node created as ``Node(node_name, namespace=...)``
    with ``remap_args`` (``__node``, ``__name`` and ``__ns`` rules change it)."""
    return NodeNames.create(node_name, namespace, remap_args).fqn


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
    return NodeNames.create(node_name, namespace, remap_args).resolve(name, service=service)


def declared_names(final: str, names: NodeNames, *, service: bool = False) -> list[str]:
    """Every name the node ``names`` could declare that resolves to the final name ``final``
    (a topic, or with ``service=True`` a service): the inverse of :meth:`NodeNames.resolve`.

    Candidates are the match side of each of the node's rules whose replacement expands to
    ``final``, then ``final`` itself; each is offered as ``~/x`` (under the node), relative
    (under its namespace, the root included) and absolute, in that order, and kept only if
    the node really resolves it to ``final`` (a rule may take it elsewhere).  Empty when no
    name the node could declare becomes ``final`` (then it came from elsewhere: a
    parameter, a remapping only the running launch knows...).
    """
    namespace, own, under = names._prefixes()
    expanded: list[str] = []
    if names.rules:
        wanted = 'service' if service else 'topic'
        for rule in names.rules:
            if rule.kind not in ('name', wanted) or not rule.applies_to(names.name) or not rule.match:
                continue
            try:
                if _expand(rule.replacement, names.name, namespace) == final:
                    expanded.append(_expand(rule.match, names.name, namespace))
            except ValueError:
                continue
    expanded.append(final)
    out: list[str] = []
    for full in expanded:
        forms = []
        if full == own:
            forms.append('~')
        elif full.startswith(own + '/'):
            forms.append('~' + full[len(own):])
        if full.startswith(under) and len(full) > len(under):
            forms.append(full[len(under):])
        forms.append(full)
        for form in forms:
            if form in out:
                continue
            try:
                if names.resolve(form, service=service) == final:
                    out.append(form)
            except ValueError:
                continue
    return out


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
    return relative_to_namespace(name, namespace)


def relative_to_namespace(name: str, namespace: str) -> str:
    """An absolute ``name`` written relative to ``namespace`` when it lies under it (not at the
    root): ``/ns/x`` in ``/ns`` is ``x``; otherwise the absolute name."""
    ns = '/' + namespace.strip('/') if namespace.strip('/') else ''
    if ns and name.startswith(ns + '/'):
        return name[len(ns) + 1:]
    return name
