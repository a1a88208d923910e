"""Run a launch file with the real upstream ``launch``/``launch_ros``, starting nothing.

Benchmark baseline only (bench_nav2_bringup.py runs it in its own virtual environment,
never the toolkit's): the toolkit neither imports nor needs upstream launch.

    python upstream_launch_run.py UPSTREAM LAUNCH_FILE [ROS_SITE_PACKAGES]

``UPSTREAM`` holds the sources: ``launch/launch`` (ros2/launch), ``launch_ros/launch_ros``
(ros2/launch_ros) and ``nav2_common`` (navigation2); ``ROS_SITE_PACKAGES`` is where rclpy and
the message packages are installed (appended to the path).  What is stubbed out is what
would leave this process: a process's execution (its completion is signalled at once) and
the service calls that load composable nodes into their container (the ROS node that would
make them, and the calls themselves).  Everything else runs as ``ros2 launch`` runs it: the
launch file is read, every action executed, every substitution performed, every node's
parameters (parameter files included) evaluated into the request or command line it would
get.  Prints one JSON line: the seconds ``LaunchService.run()`` took (the run of the launch
description, from including it to the service going idle; wall-clock and processor time),
the processes and composable nodes it would have started, and the exit code of the run.
"""

from __future__ import annotations

import json
import os
import sys
import time
import types


def _stub_composition_interfaces() -> None:
    """``composition_interfaces`` is not published on PyPI: a request type with its fields."""
    class Request:
        def __init__(self) -> None:
            self.package_name = ''
            self.plugin_name = ''
            self.node_name = ''
            self.node_namespace = ''
            self.log_level = 0
            self.remap_rules: list[str] = []
            self.parameters: list[object] = []
            self.extra_arguments: list[object] = []

    package = types.ModuleType('composition_interfaces')
    srv = types.ModuleType('composition_interfaces.srv')
    srv.LoadNode = types.SimpleNamespace(Request=Request)  # type: ignore[attr-defined]
    package.srv = srv  # type: ignore[attr-defined]
    sys.modules['composition_interfaces'] = package
    sys.modules['composition_interfaces.srv'] = srv


def main() -> int:
    upstream, launch_file = sys.argv[1], sys.argv[2]
    sys.path[:0] = [os.path.join(upstream, 'launch', 'launch'),
                    os.path.join(upstream, 'launch_ros', 'launch_ros'),
                    os.path.join(upstream, 'nav2_common')]
    if len(sys.argv) > 3:
        sys.path.append(sys.argv[3])
    _stub_composition_interfaces()

    import launch
    from launch.actions.execute_local import ExecuteLocal
    from launch.launch_description_sources import get_launch_description_from_python_launch_file
    from launch_ros.actions import load_composable_nodes

    started: list[str] = []
    loaded: list[str] = []

    async def no_process(self: ExecuteLocal, context: object) -> None:
        started.append(self.process_description.final_name)
        future = self._ExecuteLocal__completed_future  # type: ignore[attr-defined]
        if not future.done():
            future.set_result(None)

    def no_service_calls(self: object, requests: list[object], context: object) -> None:
        loaded.extend(f'{r.node_namespace}/{r.node_name}' for r in requests)  # type: ignore

    class _NoNode:
        def create_client(self, *args: object, **kwargs: object) -> None:
            return None

    ExecuteLocal._ExecuteLocal__execute_process = no_process  # type: ignore[attr-defined]
    load_composable_nodes.LoadComposableNodes._load_in_sequence = no_service_calls  # type: ignore
    load_composable_nodes.get_ros_node = lambda context: _NoNode()  # type: ignore

    description = get_launch_description_from_python_launch_file(launch_file)
    service = launch.LaunchService(argv=[], noninteractive=True)
    start, cpu = time.perf_counter(), time.process_time()
    service.include_launch_description(description)
    code = service.run()
    seconds, cpu_seconds = time.perf_counter() - start, time.process_time() - cpu
    print(json.dumps({'seconds': seconds, 'cpu_seconds': cpu_seconds, 'processes': started,
                      'composable_nodes': loaded, 'exit_code': code}))
    return 0


if __name__ == '__main__':
    sys.exit(main())
