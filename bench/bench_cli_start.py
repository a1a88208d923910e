"""Cold start of `nodl validate FILE` against `python -I -c "import yaml"`.

Target (issue 7, section 8): at most 1.5x.  Baseline: the virtual
environment's own interpreter running ``python -I -c "import yaml"``.  Both
commands start as a shell would start them: in a fresh environment, without
what the ROS 2 wheels' bootstrapper (``ros_wheels_bootstrapper.pth``) put
into this benchmark's own environment when it re-executed the interpreter
(its marker variable and its ``LD_LIBRARY_PATH`` entries), so both pay that
re-execution, as they do for a user.  They run interleaved, many times; the
median of each is compared.
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from corpus import document

TARGET = 1.5
#: What ros_wheels_bootstrapper sets before it re-executes the interpreter.
BOOTSTRAP_MARKER = '_ROS_WHEELS_BOOTSTRAP_COMPLETE'


def shell_environment() -> dict[str, str]:
    """This process's environment as the shell had it, before the bootstrapper's re-exec."""
    env = dict(os.environ)
    if env.pop(BOOTSTRAP_MARKER, None) is None:
        return env  # no bootstrapper ran: nothing to undo
    prefix = os.path.realpath(sys.prefix)
    added = [part for part in env.get('LD_LIBRARY_PATH', '').split(os.pathsep)
             if part and not os.path.realpath(part).startswith(prefix + os.sep)
             and os.path.realpath(part) != prefix]
    if added:
        env['LD_LIBRARY_PATH'] = os.pathsep.join(added)
    else:
        env.pop('LD_LIBRARY_PATH', None)
    return env


def _time(cmd: list[str], env: dict[str, str]) -> float:
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    return time.perf_counter() - start


def _compile_package() -> None:
    """Byte-compile the toolkit, as pip does for a regular (non-editable) install."""
    import compileall

    import nodl

    compileall.compile_dir(str(Path(nodl.__file__).parent), quiet=1)


def run(repeats: int = 15) -> dict[str, float]:
    _compile_package()
    nodl = shutil.which('nodl', path=str(Path(sys.executable).parent)) or 'nodl'
    with tempfile.TemporaryDirectory() as tmp:
        file = Path(tmp) / 'driver.nodl.yaml'
        file.write_text(document(0), encoding='utf-8')
        baseline_cmd = [sys.executable, '-I', '-c', 'import yaml']
        nodl_cmd = [nodl, 'validate', '-q', str(file)]
        env = shell_environment()
        _time(baseline_cmd, env), _time(nodl_cmd, env)  # warm the file cache
        base, tool = [], []
        for _ in range(repeats):
            base.append(_time(baseline_cmd, env))
            tool.append(_time(nodl_cmd, env))
    b, t = statistics.median(base), statistics.median(tool)
    return {'baseline_s': b, 'nodl_s': t, 'ratio': t / b}


def main() -> bool:
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    r = run()
    print('nodl validate FILE cold start vs python -I -c "import yaml" (the venv\'s python; '
          'both started in a fresh shell environment, each re-executed once by the ROS 2 '
          'wheels\' bootstrapper)')
    print(f'  python -I -c "import yaml": {r["baseline_s"] * 1000:7.1f} ms (median)')
    print(f'  nodl validate FILE:          {r["nodl_s"] * 1000:7.1f} ms (median)')
    print(f'  ratio:                        {r["ratio"]:.2f}x  (target <= {TARGET}x)  '
          f'{"OK" if r["ratio"] <= TARGET else "ABOVE TARGET"}')
    return r['ratio'] <= TARGET


if __name__ == '__main__':
    raise SystemExit(0 if main() else 1)
