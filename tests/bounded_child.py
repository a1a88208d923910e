"""Run one hostile case in a child process of its own, under an address-space limit.

``run_bounded(setup, body)`` starts ``python -c`` with ``RLIMIT_AS`` set (``resource.setrlimit``
in the child before it runs anything), runs ``setup`` (imports: not measured), then ``body``,
which assigns ``out`` (anything JSON can write), and returns ``out`` with the seconds ``body``
took and the child's peak resident memory in MB (its VmHWM).  A case that needs more memory than the
limit fails there (MemoryError, exit status not 0) instead of exhausting the machine; one
that hangs is killed after ``timeout`` seconds.  The helper of the hostile-input tests of
the launch substitutions, the policy XInclude expansion and the big-input tests.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent

_TEMPLATE = '''
import json, resource, time
{setup}
start = time.perf_counter()
{body}
seconds = time.perf_counter() - start
# VmHWM, not ru_maxrss: Linux keeps ru_maxrss across exec, so a child of a big pytest worker
# would report the worker's size (the pages fork copied) as its own
peak = next(int(line.split()[1]) for line in open('/proc/self/status')
            if line.startswith('VmHWM:')) / 1024
print(json.dumps({{'out': out, 'seconds': seconds, 'peak_mb': peak}}))
'''


def run_bounded(setup: str, body: str, *, megabytes: int = 1024, timeout: float = 60.0) -> dict[str, Any]:
    """``{'out': ..., 'seconds': ..., 'peak_mb': ...}`` of ``body`` run in a child limited to
    ``megabytes`` of address space (AssertionError with the child's stderr if it failed)."""
    limit = megabytes * 1024 * 1024

    def limit_memory() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    code = _TEMPLATE.format(setup=textwrap.dedent(setup), body=textwrap.dedent(body))
    env = dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    done = subprocess.run([sys.executable, '-c', code], cwd=REPO, env=env, capture_output=True,
                          text=True, timeout=timeout, preexec_fn=limit_memory)
    assert done.returncode == 0, f'the child failed (exit {done.returncode}):\n{done.stderr[-3000:]}'
    result: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
    return result
