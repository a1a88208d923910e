"""The cold start of ``nodl validate FILE``: what it must not load.

bench/bench_cli_start.py measures the start-up against ``python -I -c "import yaml"``
(at most 1.5x); this test keeps out the modules that cost it most and that validating a
file does not need, so that a change putting one back on the path fails here, at once.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

#: A valid node definition with parameters, validators and every kind of endpoint.
FIXTURE = Path(__file__).parent / 'fixtures' / 'valid' / 'node_laser_driver.nodl.yaml'

#: Modules ``nodl validate`` must not load, with what each costs the start-up.
NOT_LOADED = {
    'dataclasses': 'with inspect, ast, dis and tokenize: ~8 ms',
    'inspect': '~5 ms',
    'tempfile': 'with shutil, random, bz2 and lzma: ~4 ms (nodl.writing makes its own temporary files)',
    'hashlib': '~2.5 ms (the content marker of written files only)',
    'shutil': '~2 ms',
    'importlib.metadata': '~10 ms (the plugin scan reads entry_points.txt itself)',
    'nodl.writing': 'what writing files needs (nodl.write_error holds the error the command catches)',
    'nodl.reporting.junit': '~0.8 ms: the JUnit reporter, for --format junit only',
}

_PROGRAM = '''
import json, sys
from nodl.cli.main import main
code = main(['validate', '-q', sys.argv[1]])
print(json.dumps([code, sorted(sys.modules)]))
'''


def _loaded(path: Path) -> tuple[int, set[str]]:
    done = subprocess.run([sys.executable, '-c', _PROGRAM, str(path)], capture_output=True, text=True,
                          timeout=60, cwd=Path(__file__).resolve().parent.parent)
    assert done.returncode == 0, done.stderr
    code, modules = json.loads(done.stdout.splitlines()[-1])
    return code, set(modules)


def test_validate_loads_none_of_the_costly_modules_it_does_not_need() -> None:
    code, modules = _loaded(FIXTURE)
    assert code == 0 and 'nodl.validation' in modules  # (it did validate the file)
    unwanted = {name: why for name, why in NOT_LOADED.items() if name in modules}
    assert not unwanted, f'nodl validate now loads {unwanted}'


def test_the_error_the_command_catches_is_the_one_writing_raises() -> None:
    from nodl.write_error import WriteError as Caught
    from nodl.writing import WriteError

    assert WriteError is Caught
