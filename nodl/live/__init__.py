"""Live ROS: observing running nodes (describe, check).

This is the only part of the toolkit that imports rclpy, and only when a
live feature is used; install the ``ros`` extra for it.
"""
