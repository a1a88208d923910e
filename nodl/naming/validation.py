"""rcl's and rmw's checks of names: topic/service names, full names, namespaces, node names.

Each ``*_error`` function returns rcl's (or rmw's) wording of the rule a
name breaks, or ``None``; :class:`InvalidNameError` carries that wording.
"""

from __future__ import annotations

import re
from functools import lru_cache

__all__ = [
    'InvalidNameError',
    'checked_namespace',
    'full_name_error',
    'namespace_error',
    'node_name_error',
    'normalize_namespace',
    'topic_name_error',
]

#: rmw's limits (``RMW_TOPIC_MAX_NAME_LENGTH`` and friends).
TOPIC_MAX_LENGTH = 255 - 8
NAMESPACE_MAX_LENGTH = TOPIC_MAX_LENGTH - 2
NODE_NAME_MAX_LENGTH = 255

#: A valid fully qualified name, as :func:`full_name_error` accepts it: tokens of
#: alphanumerics and ``_``, none starting with a digit, each after one ``/``.
_VALID_FULL_NAME = re.compile(r'(?:/[A-Za-z_][A-Za-z0-9_]*)+')

#: What a node name is made of (ASCII alphanumerics and ``_``), as :func:`node_name_error` checks.
_NODE_NAME_CHARACTERS = re.compile(r'[A-Za-z0-9_]+')

ALNUM = frozenset('abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789')
DIGITS = frozenset('0123456789')


class InvalidNameError(ValueError):
    """A topic, service, node name or namespace that rcl would reject."""

    def __init__(self, what: str, name: str, reason: str) -> None:
        super().__init__(f"{what} '{name}' is invalid: {reason}")
        #: ``topic name``, ``node name``, ``node namespace`` or ``resolved name``.
        self.what = what
        self.name = name
        #: rcl's (or rmw's) wording of the rule the name breaks.
        self.reason = reason


# -- validation (rcl_validate_topic_name, rmw_validate_*) --------------------------------------


@lru_cache(maxsize=4096)  # the same few names are declared by many nodes (every base's)
def topic_name_error(name: str) -> str | None:
    """Why rcl rejects ``name`` as a topic/service name before expansion, or ``None``."""
    if not name:
        return 'topic name must not be empty string'
    if name[0] in DIGITS:
        return 'topic name token must not start with a number'
    if name[-1] == '/':
        return 'topic name must not end with a forward slash'
    in_brace = False
    opening = 0
    for i, char in enumerate(name):
        if char in ALNUM:
            if char in DIGITS and in_brace and i == opening + 1:
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
            if name[i + 1] in DIGITS:
                return 'topic name token must not start with a number'
        elif i == 1 and name[0] == '~':
            return "topic name must not have a tilde '~' that is not followed by a forward slash '/'"
    return None


def full_name_error(name: str) -> str | None:
    """Why rmw rejects ``name`` as a fully qualified topic/service name, or ``None``."""
    if len(name) <= TOPIC_MAX_LENGTH and _VALID_FULL_NAME.fullmatch(name):
        return None  # what the checks below accept, at once
    if not name:
        return 'topic name must not be empty'
    if name[0] != '/':
        return "topic name must be absolute, it must lead with a '/'"
    if name[-1] == '/':
        return "topic name must not end with a '/'"
    for char in name:
        if char not in ALNUM and char not in '_/':
            return "topic name must not contain characters other than alphanumerics, '_', or '/'"
    for i in range(len(name) - 1):
        if name[i] == '/':
            if name[i + 1] == '/':
                return "topic name must not contain repeated '/'"
            if name[i + 1] in DIGITS:
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
    # What the checks below accept (ASCII letters, digits and '_', not starting with a
    # digit), at once: asked for every launched node.
    if name.isascii() and name.isidentifier() and len(name) <= NODE_NAME_MAX_LENGTH:
        return None
    if not name:
        return 'node name must not be empty'
    if _NODE_NAME_CHARACTERS.fullmatch(name) is None:
        return "node name must not contain characters other than alphanumerics or '_'"
    if name[0] in DIGITS:
        return 'node name must not start with a number'
    if len(name) > NODE_NAME_MAX_LENGTH:
        return f"node name length should not exceed '{NODE_NAME_MAX_LENGTH}'"
    return None


def normalize_namespace(namespace: str) -> str:
    """The namespace as ``rcl_node_init`` takes it: ``''`` is ``/``, ``a`` is ``/a``."""
    if not namespace:
        return '/'
    return namespace if namespace.startswith('/') else '/' + namespace


def checked_namespace(node_name: str, namespace: str) -> str:
    """The node's absolute namespace; raises :class:`InvalidNameError` if rcl refuses the node."""
    problem = node_name_error(node_name)
    if problem:
        raise InvalidNameError('node name', node_name, problem)
    namespace = normalize_namespace(namespace)
    problem = _namespace_error(namespace)
    if problem:
        raise InvalidNameError('node namespace', namespace, problem)
    return namespace


#: :func:`namespace_error`, asked once per namespace (the nodes of a launch share a few).
_namespace_error = lru_cache(maxsize=1024)(namespace_error)
