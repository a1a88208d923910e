"""The grants of one node instance: what its composed definition declares, under its final names.

Every endpoint of a :class:`~nodl.system.NodeInstance` becomes one
grant (publisher -> topic publish, subscription -> topic subscribe, service
server -> service reply, client -> request, action server -> action execute,
client -> call) on its final name.  The base's entities are granted as the
client library creates them on the chosen distribution
(:mod:`nodl.policy.distros`): ``~/get_type_description`` only where
it exists and while ``start_type_description_service`` is not false, and
``/clock`` (subscribe) only when ``use_sim_time`` can be true when the node
starts (its launched value, else its default, is true or not known to be
false).  That the parameter is writable (as in every node) grants nothing:
a switch to simulation time at runtime is denied ``/clock`` (fails closed).
"""

from __future__ import annotations

import functools
import os

from nodl.composition.entities import Location, Provider
from nodl.composition.instance import NodeInstance
from nodl.diagnostics import Diagnostic, Severity
from nodl.policy.distros import DEFAULT_DISTRO, check_distro, exists_in
from nodl.policy.model import ACCESS_OF_KIND, Profile, Source
from nodl.policy.names import written_name_error

__all__ = ['profile_for_instance', 'display_path', 'CLOCK_TOPIC', 'CLOCK_TYPE', 'use_sim_time_can_be_true']

#: The topic a node's time source subscribes to while ``use_sim_time`` is true.
CLOCK_TOPIC = '/clock'
CLOCK_TYPE = 'rosgraph_msgs/msg/Clock'


def display_path(path: str) -> str:
    """``path`` relative to the current directory when it is below it (stable comments)."""
    if not path or path.startswith('<') or not os.path.isabs(path):
        return path
    return _relative(path, os.getcwd())


@functools.lru_cache(maxsize=4096)
def _relative(path: str, cwd: str) -> str:
    try:
        relative = os.path.relpath(path, cwd)
    except ValueError:
        return path
    return path if relative.startswith('..') else relative


def _where(location: Location | None) -> str:
    if location is None or not location.file:
        return ''
    file = display_path(location.file)
    return f'{file}:{location.line}:{location.column}' if location.line else file


def use_sim_time_can_be_true(value: object) -> bool:
    """True unless ``use_sim_time`` is surely false (False, unset, or the text ``false``)."""
    if value is None or value is False:
        return False
    return not (isinstance(value, str) and value.strip().lower() == 'false')


def profile_for_instance(instance: NodeInstance, *, distro: str = DEFAULT_DISTRO
                         ) -> tuple[Profile, list[Diagnostic]]:
    """The profile of ``instance`` and the problems found (names that cannot be granted)."""
    check_distro(distro)
    resolved = instance.resolved
    launch = _where(instance.location)
    profile = Profile(instance.namespace, instance.name, definition=display_path(resolved.file),
                      base=f'{resolved.client_library} on {distro}', launch=launch)
    diagnostics: list[Diagnostic] = []
    values = instance.parameter_values()
    start_type_description = values.get('start_type_description_service', True)
    for bound in instance.entities:
        entity = bound.entity
        if entity.is_parameter:
            continue
        base = entity.provider is Provider.CLIENT_LIBRARY
        if base and not exists_in(entity.kind.value, entity.name, distro):
            continue
        if base and entity.name == '~/get_type_description' and start_type_description is False:
            continue
        communication, access = ACCESS_OF_KIND[entity.kind.value]
        if base:
            source = Source(f'client library {resolved.client_library} ({entity.layer})', '', launch)
        else:
            source = Source(f'{entity.kind.word} {entity.name!r} ({entity.layer})',
                            _where(entity.location), launch)
        problem = written_name_error(bound.name)
        if problem is not None:
            diagnostics.append(Diagnostic(
                Severity.ERROR, f'{instance.fqn}: the {entity.kind.word} {entity.name!r} resolves to '
                f'{bound.name!r}, which cannot be granted in a policy: {problem}; fix the name or '
                'its remapping', (), entity.location.file, entity.location.line,
                entity.location.column, code='NODL602'))
            profile.notes.append(f'not granted: {entity.kind.word} {bound.name} ({problem})')
            continue
        profile.grant(communication, access, bound.name, source)
    use_sim_time = instance.parameter_overrides.get('use_sim_time', values.get('use_sim_time'))
    if use_sim_time_can_be_true(use_sim_time):
        why = 'use_sim_time is true' if use_sim_time is True else \
            f'use_sim_time may be true ({use_sim_time!r})'
        profile.grant('topic', 'subscribe', CLOCK_TOPIC,
                      Source(f'client library {resolved.client_library} (time source: {why})', '',
                             launch))
    return profile, diagnostics
