"""Run every benchmark; each prints its figures and the ratio to its baseline.

`make bench`.  Exit status 1 if any ratio misses its target.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

import bench_analyse  # noqa: E402
import bench_cli_start  # noqa: E402
import bench_describe  # noqa: E402
import bench_describe_launch  # noqa: E402
import bench_doc  # noqa: E402
import bench_extract_cpp  # noqa: E402
import bench_extract_python  # noqa: E402
import bench_generate  # noqa: E402
import bench_hostile  # noqa: E402
import bench_load  # noqa: E402
import bench_monitor  # noqa: E402
import bench_nav2_bringup  # noqa: E402
import bench_policy  # noqa: E402
import bench_studio  # noqa: E402
import bench_system  # noqa: E402
import bench_validate_types  # noqa: E402

BENCHMARKS = [bench_load, bench_cli_start, bench_describe, bench_describe_launch, bench_monitor, bench_analyse,
              bench_generate, bench_policy, bench_hostile, bench_extract_python, bench_extract_cpp,
              bench_validate_types, bench_doc, bench_nav2_bringup, bench_system, bench_studio]


def main() -> int:
    ok = True
    for bench in BENCHMARKS:
        ok = bench.main() and ok
        print()
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
