"""``pip install`` with progress a person can follow (used by the Makefile).

The first ``make demo`` on a fresh machine downloads and installs about a
hundred packages (ROS 2 from the Python registry); pip's own output is either
silent (``--quiet``) or hundreds of lines. This runs pip and prints one line
per package as it is resolved and fetched, then counts the installation
(which pip does silently) by watching the environment's ``*.dist-info``
folders appear, and ends with a one-line summary. When pip fails, the end of
its output is shown.

Usage: python tools/pip_install.py PIP-INSTALL-ARGUMENTS...
(run it with the interpreter of the environment to install into).
"""

from __future__ import annotations

import collections
import os
import re
import subprocess
import sys
import sysconfig
import threading
import time

# a requirement from an index, or a local file or folder (the project itself)
_COLLECTING = re.compile(r'^(?:Collecting|Processing) (\S+)')
_FETCHING = re.compile(r'^\s*(Downloading|Using cached) (\S+?)(?:\s+\((.*)\))?$')
_INSTALLING = re.compile(r'^Installing collected packages: (.*)$')
_DONE = re.compile(r'^Successfully installed (.*)$')


def _site_packages() -> str:
    return sysconfig.get_paths()['purelib']


def _installed() -> set[str]:
    try:
        return {n for n in os.listdir(_site_packages()) if n.endswith('.dist-info')}
    except OSError:
        return set()


def _watch_installation(total: int, before: set[str], stop: threading.Event) -> None:
    """Print how many of ``total`` packages pip has installed, every few seconds."""
    shown = -1
    while not stop.wait(3.0):
        done = min(len(_installed() - before), total)
        if done != shown:
            shown = done
            print(f'  installed {done}/{total}', flush=True)


def main(argv: list[str]) -> int:
    cmd = [sys.executable, '-m', 'pip', 'install', '--progress-bar', 'off',
           '--disable-pip-version-check', *argv]
    tail: collections.deque[str] = collections.deque(maxlen=40)
    collected = 0
    fetched = 0
    summary = False
    started = time.monotonic()
    stop = threading.Event()
    watcher: threading.Thread | None = None
    env = dict(os.environ, PYTHONUNBUFFERED='1')
    with subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=env, bufsize=1) as pip:
        assert pip.stdout is not None
        for line in pip.stdout:
            line = line.rstrip('\n')
            tail.append(line)
            if m := _COLLECTING.match(line):
                collected += 1
                print(f'  resolving [{collected}] {os.path.basename(m.group(1)) or m.group(1)}',
                      flush=True)
            elif m := _FETCHING.match(line):
                fetched += 1
                what = os.path.basename(m.group(2))
                size = f' ({m.group(3)})' if m.group(3) else ''
                verb = 'downloading' if m.group(1) == 'Downloading' else 'cached'
                print(f'  {verb} [{fetched}/{collected}] {what}{size}', flush=True)
            elif m := _INSTALLING.match(line):
                names = [n.strip() for n in m.group(1).split(',') if n.strip()]
                print(f'  installing {len(names)} packages (this takes a while the first time)',
                      flush=True)
                watcher = threading.Thread(target=_watch_installation,
                                           args=(len(names), _installed(), stop), daemon=True)
                watcher.start()
            elif m := _DONE.match(line):
                count = len(m.group(1).split())
                summary = True
                print(f'  installed {count} packages in {time.monotonic() - started:.0f} s',
                      flush=True)
            elif line.startswith(('ERROR', 'error:')):
                print(line, flush=True)
        code = pip.wait()
    stop.set()
    if watcher is not None:
        watcher.join(timeout=5)
    if code:
        print('pip failed; the end of its output:', file=sys.stderr)
        print('\n'.join(tail), file=sys.stderr)
    elif not summary:
        print('  nothing to install', flush=True)
    return code


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
