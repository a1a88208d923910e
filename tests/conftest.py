"""Test configuration shared by every test module.

Network rule: anything that starts ROS stays on loopback, in a domain of its
own.  Both variables are set here, once, before any test imports rclpy.
"""

from __future__ import annotations

import os

os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'

#: How many domains a run takes: one per parallel worker (``make test`` runs one per core).
DOMAINS_PER_RUN = 8


def _domain_in_use(domain: int) -> bool:
    """Whether a DDS participant on this machine is in ``domain``.

    The first participant of a domain binds the domain's first unicast discovery port
    (RTPS well-known ports: 7400 + 250 * domain + 10); if this process cannot bind it,
    someone (another test run, a demo, a user's system) is there.
    """
    import socket

    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        try:
            probe.bind(('127.0.0.1', 7400 + 250 * domain + 10))
        except OSError:
            return True
    return False


def _free_domain_base(start: int, count: int = DOMAINS_PER_RUN) -> int:
    """The first domain from ``start`` on (1-101, wrapping) such that ``count`` domains
    from it are all free, or ``start`` when none is (the run then shares, as before)."""
    span = 101 - count + 1
    for step in range(span):
        base = 1 + (start - 1 + step) % span
        if not any(_domain_in_use(base + i) for i in range(count)):
            return base
    return start


# A run's domains are chosen once, by the process that starts the workers, and inherited
# by them: free ones, so that two runs at once (two clones, a demo, a user's ROS system
# in ROS_DOMAIN_ID) never see each other's nodes. NODL_TEST_ROS_DOMAIN_BASE set by hand
# picks them instead.
if 'NODL_TEST_ROS_DOMAIN_BASE' not in os.environ:
    os.environ['NODL_TEST_ROS_DOMAIN_BASE'] = str(_free_domain_base(1 + os.getpid() % 94))
os.environ['ROS_DOMAIN_ID'] = os.environ['NODL_TEST_ROS_DOMAIN_BASE']


def _worker_domain(base: str, worker: str | None) -> str:
    """The domain of one pytest-xdist worker: the run's domain plus the worker's index.

    Workers run live tests at the same time; each must see only its own nodes (tests
    assert on what the graph holds), so each gets a domain of its own.  The controller
    sets the base above before it starts the workers, which inherit it.
    """
    if not worker or not worker.startswith('gw'):
        return base
    return str((int(base) + int(worker[2:])) % 102)  # 0-101: valid with localhost discovery


# The worker's domain is computed from the run's base, however often this runs (and
# whatever a child process inherits).
os.environ['ROS_DOMAIN_ID'] = _worker_domain(os.environ['NODL_TEST_ROS_DOMAIN_BASE'],
                                             os.environ.get('PYTEST_XDIST_WORKER'))

from pathlib import Path  # noqa: E402

import pytest  # noqa: E402

FIXTURES = Path(__file__).parent / 'fixtures'
REPO = Path(__file__).resolve().parent.parent


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption('--update-golden', action='store_true', default=False,
                     help='rewrite the expected-output files instead of comparing with them')
    parser.addoption('--record-durations', action='store_true', default=False,
                     help=f'write the seconds each test module took to {DURATIONS.name} '
                          '(the order in which parallel workers are given the modules)')


# --- Parallel runs (pytest-xdist, as `make test` runs the suite) -------------------------

#: Seconds each test module took when last recorded (``pytest --record-durations``).
DURATIONS = Path(__file__).parent / 'durations.json'


def module_costs() -> dict[str, float]:
    """The recorded seconds per test module file name ({} if none were recorded)."""
    import json

    try:
        costs = json.loads(DURATIONS.read_text(encoding='utf-8'))
    except (OSError, ValueError):
        return {}
    return {str(k): float(v) for k, v in costs.items()} if isinstance(costs, dict) else {}


def costliest_first(modules: list[str], costs: dict[str, float]) -> list[str]:
    """The modules, the most expensive first; one with no recorded cost (a new module)
    counts as the most expensive, and equal costs keep the given order."""
    return sorted(modules, key=lambda m: -costs.get(m, float('inf')))


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """On an xdist worker, order the modules by their recorded cost, the costliest first.

    With ``--dist loadfile --no-loadscope-reorder`` (the Makefile), workers are handed
    whole modules in this order, so the long builds and live-node modules start at once
    and the many quick modules fill the gaps; otherwise the run ends waiting for a
    colcon build that started last.  A run without xdist keeps the plain file order.
    Only the order changes (each module's tests stay together and in their order).
    """
    if not hasattr(config, 'workerinput'):
        return
    by_module: dict[str, list[pytest.Item]] = {}
    for item in items:
        by_module.setdefault(item.path.name, []).append(item)
    items[:] = [item for module in costliest_first(list(by_module), module_costs())
                for item in by_module[module]]


class _DurationRecorder:
    """Adds up setup, call and teardown seconds per module (on the controller)."""

    def __init__(self) -> None:
        self.seconds: dict[str, float] = {}

    def pytest_runtest_logreport(self, report: pytest.TestReport) -> None:
        module = Path(report.nodeid.split('::', 1)[0]).name
        self.seconds[module] = self.seconds.get(module, 0.0) + report.duration

    def pytest_sessionfinish(self) -> None:
        import json

        costs = module_costs()
        costs.update({m: round(s, 1) for m, s in self.seconds.items()})
        DURATIONS.write_text(json.dumps(dict(sorted(costs.items())), indent=1) + '\n',
                             encoding='utf-8')


def pytest_configure(config: pytest.Config) -> None:
    if config.getoption('--record-durations') and not hasattr(config, 'workerinput'):
        config.pluginmanager.register(_DurationRecorder(), 'nodl-durations')


class Golden:
    """Compares generated text with a checked-in expected file."""

    def __init__(self, update: bool) -> None:
        self.update = update

    def check(self, actual: str, expected_file: Path) -> None:
        if self.update:
            expected_file.parent.mkdir(parents=True, exist_ok=True)
            expected_file.write_text(actual, encoding='utf-8')
            return
        assert expected_file.exists(), (
            f'{expected_file} is missing; run pytest --update-golden to create it')
        assert actual == expected_file.read_text(encoding='utf-8'), (
            f'output differs from {expected_file}; if the change is intended, '
            'run pytest --update-golden and review the diff')


@pytest.fixture
def golden(request: pytest.FixtureRequest) -> Golden:
    """Golden-file comparison; ``pytest --update-golden`` regenerates the files."""
    return Golden(request.config.getoption('--update-golden'))


NODES = Path(__file__).parent / 'nodes'


#: Runs before a node's script, in the node's process (it ends by exec-ing the script, so
#: the process is the node's): asks Linux to end it (SIGKILL) when the test process that
#: started it dies, so that a run stopped half-way (a timeout, Ctrl-C, a crashed xdist
#: worker) leaves no node behind in the domain for the next run to see.  SIGKILL, not
#: SIGTERM: an orphan has nobody to shut down for, and rclpy's graceful shutdown could
#: take longer than the next run waits on a loaded machine.  A separate step, not Popen's
#: preexec_fn, which is unsafe in a process with threads (rclpy's).
_ENDS_WITH_ITS_PARENT = (
    'import ctypes, os, signal, sys\n'
    'ctypes.CDLL(None).prctl(1, int(signal.SIGKILL), 0, 0, 0)  # PR_SET_PDEATHSIG\n'
    'if os.getppid() != int(sys.argv[1]):  # the parent died before that\n'
    '    os._exit(1)\n'
    'os.execv(sys.argv[2], sys.argv[2:])\n')


class NodeProcess:
    """A real ROS node in a process of its own (see tests/nodes/)."""

    def __init__(self, script: str, name: str, namespace: str = '/', *args: str,
                 timeout: float = 20.0) -> None:
        import subprocess
        import sys

        self.name = name
        self.namespace = namespace
        self.process = subprocess.Popen(
            [sys.executable, '-S', '-c', _ENDS_WITH_ITS_PARENT, str(os.getpid()),
             sys.executable, str(NODES / script), '--name', name, '--namespace', namespace, *args],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=NODES)
        self._wait_ready(timeout)

    @property
    def fqn(self) -> str:
        return (self.namespace.rstrip('/') + '/' + self.name) if self.namespace != '/' else '/' + self.name

    def _wait_ready(self, timeout: float) -> None:
        import selectors
        import time

        assert self.process.stdout is not None
        selector = selectors.DefaultSelector()
        selector.register(self.process.stdout, selectors.EVENT_READ)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if selector.select(timeout=max(0.0, deadline - time.monotonic())):
                line = self.process.stdout.readline()
                if line.strip() == 'ready':
                    return
                if not line:
                    break
        self.stop()
        raise RuntimeError(f'{self.name} did not start: {self.process.stderr.read() if self.process.stderr else ""}')

    def stop(self) -> None:
        import signal
        import subprocess

        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait(timeout=5)
        for stream in (self.process.stdout, self.process.stderr):
            if stream is not None:
                stream.close()


@pytest.fixture
def ros_node():
    """Start real node processes; every one is stopped after the test."""
    started: list[NodeProcess] = []

    def start(script: str, name: str, namespace: str = '/', *args: str) -> NodeProcess:
        node = NodeProcess(script, name, namespace, *args)
        started.append(node)
        return node

    yield start
    for node in started:
        node.stop()


@pytest.fixture
def fixtures() -> Path:
    """The fixture file folder."""
    return FIXTURES
