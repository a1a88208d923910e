"""``ros2 nodl ...``: the ros2cli command extension.

Registered in the ``ros2cli.command`` entry point group.  It exposes the
same verbs as ``nodl`` (the ``nodl.verbs`` group), so both commands always
agree.  ros2cli itself is optional: without it the class still follows the
ros2cli ``CommandExtension`` protocol (``add_arguments(parser, cli_name)``
and ``main(*, parser, args)``).
"""

from __future__ import annotations

import argparse
from typing import Any

from nodl.cli.runner import add_verbs, run_verb

try:  # pragma: no cover - depends on whether ros2cli is installed
    from ros2cli.command import CommandExtension as _CommandBase
except ImportError:  # ros2cli is not on the Python registry; keep the protocol
    class _CommandBase:  # type: ignore[no-redef]
        """Stand-in with the attributes ros2cli reads."""

        NAME: str | None = None
        EXTENSION_POINT_VERSION = '0.1'

__all__ = ['NodlCommand']


class NodlCommand(_CommandBase):  # type: ignore[misc]
    """Validate, compose and inspect NoDL node definitions."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the verbs of ``nodl`` under ``ros2 nodl``."""
        self._parser = parser
        add_verbs(parser, dest='_nodl_verb')

    def main(self, *, parser: argparse.ArgumentParser, args: Any) -> int:
        """Run the chosen verb."""
        return run_verb(parser, args, dest='_nodl_verb')
