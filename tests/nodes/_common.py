"""Shared start-up for the test node processes."""

from __future__ import annotations

import argparse
import os
import sys

# The network rule, even if a test forgets: loopback only.
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'


def arguments(description: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument('--name', required=True)
    parser.add_argument('--namespace', default='/')
    parser.add_argument('--ros-args', nargs=argparse.REMAINDER, default=[])
    return parser.parse_args()


def ready() -> None:
    print('ready', flush=True)


def spin(node, seconds: float | None = None) -> None:  # type: ignore[no-untyped-def]
    import rclpy

    try:
        if seconds is None:
            rclpy.spin(node)
        else:
            import time
            end = time.monotonic() + seconds
            while time.monotonic() < end:
                rclpy.spin_once(node, timeout_sec=0.05)
    except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()
        sys.stdout.flush()
