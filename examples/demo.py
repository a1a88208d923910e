"""`make demo`: the toolkit's main jobs on the bundled examples, narrated.

Every step runs the real `nodl` command, as a user would.
"""

from __future__ import annotations

import os
import shlex
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
NODL = [sys.executable, '-m', 'nodl_schema']


def step(title: str, args: list[str], expect: int = 0) -> None:
    """Run one `nodl` command and show what it printed."""
    print(f'\n=== {title}')
    print('$ nodl ' + ' '.join(shlex.quote(a) for a in args))
    result = subprocess.run(NODL + args, cwd=REPO, text=True, capture_output=True, timeout=120)
    sys.stdout.write(result.stdout)
    sys.stdout.write(result.stderr)
    print(f'(exit code {result.returncode})')
    if result.returncode != expect:
        sys.exit(f'demo: expected exit code {expect}, got {result.returncode}')


def main() -> None:
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    step('Validate every bundled example (node, lifecycle node, interface, parameter)',
         ['validate', 'examples/'])
    step('A file full of typical mistakes: every problem at once, with FILE:LINE:COL',
         ['validate', 'examples/mistakes/typos.yaml'], expect=1)
    step('The same diagnostics as JSON, for tools',
         ['validate', '--format', 'json', '-q', 'examples/mistakes/typos.yaml'], expect=1)
    step('Warnings fail only under --strict', ['validate', '--strict', 'examples/'])
    print('\n=== The JSON Schema for editors (first lines of `nodl schema interface`)')
    schema = subprocess.run(NODL + ['schema', 'interface'], cwd=REPO, text=True,
                            capture_output=True, timeout=60, check=True).stdout
    print('\n'.join(schema.splitlines()[:8]) + '\n  ...')
    print('\nDemo finished.')


if __name__ == '__main__':
    main()
