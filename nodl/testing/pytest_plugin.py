"""The pytest plugin (entry point ``pytest11``): a ``nodl_conformance`` fixture.

In a package's test::

    def test_talker_conforms(nodl_conformance):
        # start the node under test first (launch_testing, subprocess, ...)
        nodl_conformance('/talker', ('my_pkg', 'talker'))

Loading the plugin imports nothing of ROS; rclpy is imported when the
fixture is used.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest


@pytest.fixture
def nodl_conformance() -> Callable[..., Any]:
    """``nodl_conformance(node, definition, timeout=10, remaps=(), ignore=(), error=())`` asserts
    that ``node`` conforms (see :func:`nodl.testing.assert_conforms`)."""
    from nodl.testing.conformance import assert_conforms

    return assert_conforms
