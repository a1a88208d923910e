"""ROS 2 distributions and what their client libraries create in every node, where it differs.

The built-in bases describe the current distribution (:data:`DEFAULT_DISTRO`).
Older distributions lack some of the base's entities; this table says which,
with the facts it rests on:

* ``~/get_type_description`` (REP 2011): rcl's node type description service
  and rclpy's ``TypeDescriptionService`` were added in 2023 and backported to
  Iron (rcl "[Iron] Add ``~/get_type_description`` service (backport #1052)",
  rclpy "get_type_description service (#1139) (#1140)", July 2023); Humble
  has neither the service nor its ``start_type_description_service``
  parameter.
"""

from __future__ import annotations

__all__ = ['DISTROS', 'DEFAULT_DISTRO', 'SINCE', 'exists_in', 'check_distro']

#: Known distributions, oldest first.
DISTROS: tuple[str, ...] = ('humble', 'iron', 'jazzy', 'kilted', 'rolling')

#: The distribution the built-in bases describe.
DEFAULT_DISTRO = 'kilted'

#: (entity kind value, name as declared in the base) -> the first distribution that has it.
SINCE: dict[tuple[str, str], str] = {
    ('service_server', '~/get_type_description'): 'iron',
    ('parameter', 'start_type_description_service'): 'iron',
}


def check_distro(distro: str) -> str:
    """``distro`` if it is known; ValueError saying what is expected otherwise."""
    if distro not in DISTROS:
        raise ValueError(f'unknown distribution {distro!r}; expected one of: {", ".join(DISTROS)}')
    return distro


def exists_in(kind: str, name: str, distro: str) -> bool:
    """True if the base entity ``(kind, name)`` exists on ``distro``."""
    since = SINCE.get((kind, name))
    return since is None or DISTROS.index(check_distro(distro)) >= DISTROS.index(since)
