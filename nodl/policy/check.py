"""``--check``: an existing policy against what the system needs.

Every grant the system needs that the policy lacks (NODL604; a whole
profile missing: NODL607) would make the node fail at runtime; every grant
the policy gives that the system does not need (NODL605; a profile of a node
the system does not have: NODL608) is over-privilege.  Names in the file are
resolved as SROS 2 resolves them (:func:`~nodl.policy.names.resolve_policy_name`),
so ``chatter``, ``/chatter`` and ``~/x`` compare by their final names.  A
name DDS reads as a pattern (``*``) satisfies what it matches but is reported
as widening access (NODL603); a ``DENY`` rule that matches a needed grant
takes it away (DDS applies deny rules first).  Permissions belong to
enclaves, not nodes: a node's profile in another enclave than the one the
node runs in (as ``--enclave-per``/``--enclave-map`` say the system is
started) is NODL609, since the node lacks those grants and whoever holds
that enclave has them.  Each finding is placed in the policy file; missing
grants at the profile that should hold them.
"""

from __future__ import annotations

import fnmatch
import os
from pathlib import Path
from typing import NamedTuple

from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.xml_reader import XmlElement
from nodl.naming import join_name
from nodl.policy.model import PERMISSIONS, Policy
from nodl.policy.names import has_wildcard, resolve_policy_name, written_name
from nodl.policy.schema_check import ParsedPolicy, check_policy_structure, read_policy

__all__ = ['GrantedName', 'granted_names', 'check_policy_file', 'check_parsed_policy']

_LISTS = {p.element: p for p in PERMISSIONS}


class GrantedName(NamedTuple):
    """One name of a policy file, resolved, with its place."""

    #: The profile's node, fully qualified.
    node: str
    communication: str
    access: str
    #: ``ALLOW`` or ``DENY``.
    qualifier: str
    #: As written.
    written: str
    #: As SROS 2 resolves it.
    name: str
    line: int
    column: int
    enclave: str
    #: The file it is written in, if not the policy file itself (an included file).
    file: str = ''


def _fqn(namespace: str, node: str) -> str:
    return join_name(namespace, node)


def granted_names(parsed: ParsedPolicy) -> tuple[list[GrantedName], dict[str, XmlElement]]:
    """Every name a (structurally valid) policy grants or denies, and each node's first profile."""
    out: list[GrantedName] = []
    profiles: dict[str, XmlElement] = {}
    root = parsed.root
    if root is None:
        return out, profiles
    for enclaves in root.children:
        for enclave in enclaves.children:
            path = enclave.get('path')
            for group in enclave.children:
                for profile in group.children:
                    if profile.tag != 'profile':
                        continue
                    ns, node = profile.get('ns'), profile.get('node')
                    if ns is None or node is None:
                        continue
                    fqn = _fqn(ns.value, node.value)
                    profiles.setdefault(fqn, profile)
                    for permissions in profile.children:
                        kind = _LISTS.get(permissions.tag)
                        if kind is None:
                            continue
                        for access in kind.accesses:
                            qualifier = permissions.get(access)
                            if qualifier is None:
                                continue
                            for item in permissions.children:
                                # as SROS 2 reads it: the text as written, white space included
                                written = parsed.text_of(item, strip=False)
                                line, column = item.line, item.column
                                out.append(GrantedName(
                                    fqn, kind.communication, access, qualifier.value, written,
                                    resolve_policy_name(written, ns.value, node.value), line, column,
                                    path.value if path is not None else '', parsed.file_of(item)))
    return out, profiles


def _shown(g: GrantedName) -> str:
    """The name as SROS 2 resolves it, quoted when white space around it is part of it."""
    return repr(g.name) if g.written != g.written.strip() else g.name


def _enclaves_of(root: XmlElement, fqn: str) -> list[tuple[str, XmlElement]]:
    """``(enclave path, profile element)`` of every profile of ``fqn`` in the policy."""
    out = []
    for enclaves in root.children:
        for enclave in enclaves.children:
            path = enclave.get('path')
            for group in enclave.children:
                for profile in group.children:
                    ns, node = profile.get('ns'), profile.get('node')
                    if profile.tag == 'profile' and ns is not None and node is not None and \
                            _fqn(ns.value, node.value) == fqn:
                        out.append((path.value if path is not None else '', profile))
    return out


def _spaced(written: str) -> str:
    """A hint when ``written`` has white space around it, which SROS 2 keeps in the name."""
    if written == written.strip():
        return ''
    return (f'; SROS 2 takes the text between the tags as it is, white space included: write '
            f'<...>{written.strip()}</...> with nothing around the name')


def _diagnostic(file: str, severity: Severity, message: str, line: int, column: int,
                code: str) -> Diagnostic:
    return Diagnostic(severity, message, (), file, line, column, code=code)


def check_parsed_policy(parsed: ParsedPolicy, expected: Policy) -> list[Diagnostic]:
    """What ``parsed`` lacks and grants beyond ``expected`` (structure problems first, alone)."""
    structure = check_policy_structure(parsed)
    if any(d.severity is Severity.ERROR for d in structure):
        return structure
    file = parsed.file
    names, profiles = granted_names(parsed)
    root = parsed.root
    assert root is not None
    by_node: dict[str, list[GrantedName]] = {}
    for name in names:
        by_node.setdefault(name.node, []).append(name)
    out = list(structure)
    needed_nodes = set()
    for enclave, profile in expected.profiles():
        fqn = profile.fqn
        needed_nodes.add(fqn)
        element = profiles.get(fqn)
        for place, where in _enclaves_of(root, fqn):
            if place != enclave.path:
                out.append(_diagnostic(
                    file, Severity.ERROR, f'misplaced: the profile of {fqn} is in enclave {place!r}, '
                    f'but the node runs in enclave {enclave.path!r} (as the enclave options given '
                    'place it: say how the processes are started with --enclave-per or '
                    f'--enclave-map): {fqn} would lack these grants, and whoever holds {place!r} '
                    'has them', where.line, where.column, 'NODL609'))
        if element is None:
            if profile.grants:
                out.append(_diagnostic(
                    file, Severity.ERROR, f'missing: no profile for {fqn} (ns="{profile.namespace}" '
                    f'node="{profile.node}"), which needs {len(profile.grants)} grants: the node would '
                    'fail at runtime', root.line, root.column, 'NODL607'))
            continue
        in_profile = by_node.get(fqn, [])
        allowed = [g for g in in_profile if g.qualifier == 'ALLOW']
        denied = [g for g in in_profile if g.qualifier == 'DENY']

        def covers(g: GrantedName, communication: str, access: str, name: str) -> bool:
            return g.communication == communication and g.access == access and \
                (g.name == name or (has_wildcard(g.name) and fnmatch.fnmatchcase(name, g.name)))

        for grant in profile.sorted_grants():
            key = (grant.communication, grant.access, grant.name)
            deny = next((g for g in denied if covers(g, *key)), None)
            if deny is not None:
                out.append(_diagnostic(
                    deny.file or file, Severity.ERROR, f'missing: {fqn} needs {grant.communication} '
                    f'{grant.access} on {grant.name}, which this DENY rule takes away',
                    deny.line, deny.column, 'NODL604'))
                continue
            if not any(covers(g, *key) for g in allowed):
                write = written_name(grant.name, profile.namespace, profile.node)
                out.append(_diagnostic(
                    file, Severity.ERROR, f'missing: the profile of {fqn} does not grant '
                    f'{grant.communication} {grant.access} on {grant.name} (write <{grant.communication}>'
                    f'{write}</{grant.communication}> in a <{grant.communication}s {grant.access}="ALLOW">): '
                    'the node would fail at runtime', element.line, element.column, 'NODL604'))
        needed = profile.names()
        for g in allowed:
            if has_wildcard(g.written):
                out.append(_diagnostic(
                    g.file or file, Severity.WARNING, f'{fqn}: the {g.communication} pattern {g.written!r} '
                    f'grants {g.access} on every matching name; list the names the node needs '
                    'instead', g.line, g.column, 'NODL603'))
            elif (g.communication, g.access, g.name) not in needed:
                out.append(_diagnostic(
                    g.file or file, Severity.ERROR, f'extra: {fqn} is granted {g.communication} {g.access} on '
                    f'{_shown(g)}, which it does not need (over-privilege)' + _spaced(g.written),
                    g.line, g.column, 'NODL605'))
    for fqn, element in profiles.items():
        if fqn not in needed_nodes:
            out.append(_diagnostic(
                file, Severity.ERROR, f'extra: a profile for {fqn}, which the system does not have '
                '(over-privilege for whoever holds its enclave)', element.line, element.column, 'NODL608'))
    out.sort(key=lambda d: (d.file != file, d.file, d.line, d.column, d.code, d.message))
    return out


def check_policy_file(path: str | os.PathLike[str], expected: Policy) -> list[Diagnostic]:
    """Compare the policy file at ``path`` with ``expected``.  OSError if it cannot be read."""
    return check_parsed_policy(read_policy(Path(path)), expected)
