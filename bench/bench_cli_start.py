"""Cold start of `nodl validate FILE` against `python -I -c "import yaml"`.

Target (issue 2): at most 2x.  Both commands run in the same environment,
interleaved, many times; the median of each is compared.
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

TARGET = 2.0


def _time(cmd: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def _compile_package() -> None:
    """Byte-compile the toolkit, as pip does for a regular (non-editable) install."""
    import compileall

    import nodl_schema

    compileall.compile_dir(str(Path(nodl_schema.__file__).parent), quiet=1)


def run(repeats: int = 15) -> dict[str, float]:
    _compile_package()
    nodl = shutil.which('nodl', path=str(Path(sys.executable).parent)) or 'nodl'
    with tempfile.TemporaryDirectory() as tmp:
        file = Path(tmp) / 'driver.nodl.yaml'
        file.write_text(document(0), encoding='utf-8')
        baseline_cmd = [sys.executable, '-I', '-c', 'import yaml']
        nodl_cmd = [nodl, 'validate', '-q', str(file)]
        _time(baseline_cmd), _time(nodl_cmd)  # warm the file cache
        base, tool = [], []
        for _ in range(repeats):
            base.append(_time(baseline_cmd))
            tool.append(_time(nodl_cmd))
    b, t = statistics.median(base), statistics.median(tool)
    return {'baseline_s': b, 'nodl_s': t, 'ratio': t / b}


def main() -> bool:
    os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
    r = run()
    print('nodl validate FILE cold start vs python -I -c "import yaml"')
    print(f'  python -I -c "import yaml": {r["baseline_s"] * 1000:7.1f} ms (median)')
    print(f'  nodl validate FILE:          {r["nodl_s"] * 1000:7.1f} ms (median)')
    print(f'  ratio:                        {r["ratio"]:.2f}x  (target <= {TARGET}x)  '
          f'{"OK" if r["ratio"] <= TARGET else "ABOVE TARGET"}')
    return r['ratio'] <= TARGET


if __name__ == '__main__':
    raise SystemExit(0 if main() else 1)
