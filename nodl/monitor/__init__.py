"""``nodl monitor``: runtime health monitoring of a running system on ``/diagnostics``.

* :mod:`~nodl.monitor.expected`: the expected system, from the analysis of a
  launch file or from definitions placed by name (as ``nodl analyse`` computes it);
* :mod:`~nodl.monitor.graph`: full scans of the live graph (every endpoint with
  QoS, type hash and GID), taken when the live layer's graph follower
  (:mod:`~nodl.live.graph_events`, polling at 10 Hz in a thread of its own) saw a
  change, and periodically;
* :mod:`~nodl.monitor.checks`: what is checked (nodes, endpoints as ``nodl
  check`` decides them, connections, parameters, rates) as coded findings;
* :mod:`~nodl.monitor.status`: ``diagnostic_msgs/DiagnosticStatus`` building and
  the reports (text, JSON, JUnit, SARIF, JSON lines);
* :mod:`~nodl.monitor.node`: the hidden rclpy node and its event loop;
* :mod:`~nodl.monitor.aggregator`: a diagnostic_aggregator analyzer configuration.

Nothing here prints or exits.  Importing this package does not import rclpy.
"""

from __future__ import annotations

__all__: list[str] = []
