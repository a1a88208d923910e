"""``assert_conforms``: the check of ``nodl check`` as one assertion."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from nodl.diagnostics import Diagnostic
    from nodl.live.check import CheckResult

__all__ = ['NodeDrift', 'assert_conforms']


class NodeDrift(AssertionError):
    """A running node does not conform to its definition; the message lists every difference.

    :attr:`result` is the check's :class:`~nodl.live.check.CheckResult` and
    :attr:`diagnostics` its differences, each a coded diagnostic placed at the
    declaration it concerns (for a test's own assertions or report)."""

    def __init__(self, message: str, result: CheckResult | None = None) -> None:
        super().__init__(message)
        self.result = result
        self.diagnostics: list[Diagnostic] = list(result.differences) if result is not None else []


def assert_conforms(node: str, definition: str | os.PathLike[str] | tuple[str, str], *,
                    timeout: float = 10.0, remaps: Iterable[str] = (),
                    parameters: bool = True, client_library: str | None = None,
                    ignore: Iterable[str] = (), error: Iterable[str] = (),
                    use_config: bool = True) -> CheckResult:
    """Check the running ``node`` against ``definition`` and fail with every difference.

    ``definition`` is a file or ``(package, executable)`` registered in the
    ament index.  As ``nodl check`` does, the codes of the ``nodl.toml`` or
    ``[tool.nodl]`` found upward from the definition file apply (unless
    ``use_config`` is false), then ``ignore`` and ``error`` (codes such as
    ``NODL402``), which win; conformance is decided after them.  Returns the
    :class:`~nodl.live.check.CheckResult` when the node conforms
    (unverifiable fields never fail unless promoted).  ValueError for an
    unknown code or a bad configuration file.
    """
    from nodl.live.check import check_node
    from nodl.live.report import format_check_text
    from nodl.overrides import Overrides, parse_code_list

    codes: dict[str, list[str]] = {}
    for option, values in (('ignore', ignore), ('error', error)):
        found, unknown = parse_code_list([values] if isinstance(values, str) else values)
        if unknown:
            raise ValueError(f'unknown code {unknown[0]!r} in {option} (see docs/diagnostics.md)')
        codes[option] = found
    result = check_node(node, definition, timeout=timeout, remaps=remaps, parameters=parameters,
                        client_library=client_library)
    overrides = Overrides(codes['ignore'], codes['error'])
    if use_config and os.path.exists(result.definition):
        from nodl.config import overrides_for

        overrides = overrides_for(result.definition).then(overrides)
    result = result.with_overrides(overrides)
    if not result.conforms:
        raise NodeDrift(format_check_text(result), result)
    return result
