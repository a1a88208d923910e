"""``assert_conforms``: the check of ``nodl check`` as one assertion."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Iterable

if TYPE_CHECKING:
    from nodl_schema.live.check import CheckResult

__all__ = ['NodeDrift', 'assert_conforms']


class NodeDrift(AssertionError):
    """A running node does not conform to its definition; the message lists every difference."""


def assert_conforms(node: str, definition: str | os.PathLike[str] | tuple[str, str], *,
                    timeout: float = 10.0, remaps: Iterable[str] = (),
                    parameters: bool = True) -> CheckResult:
    """Check the running ``node`` against ``definition`` and fail with every difference.

    ``definition`` is a file or ``(package, executable)`` registered in the
    ament index.  Returns the :class:`~nodl_schema.live.check.CheckResult`
    when the node conforms (unverifiable fields never fail).
    """
    from nodl_schema.live.check import check_node
    from nodl_schema.live.report import format_check_text

    result = check_node(node, definition, timeout=timeout, remaps=remaps, parameters=parameters)
    if not result.conforms:
        raise NodeDrift(format_check_text(result))
    return result
