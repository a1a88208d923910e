"""Where the studio draws each node: a side file next to the launch file.

``rover.launch.xml`` -> ``rover.launch.xml.studio.json``: ``{"version": 1, "positions":
{"/rover/lidar": {"x": 120, "y": 40}, ...}}``, keyed by the node's final name (what
stays when the file is edited elsewhere and read again).  Written atomically
(:func:`nodl.writing.write_file`); a missing or unreadable side file is an empty layout
(the page places such nodes itself).
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from typing import Any

from nodl.writing import write_file

__all__ = ['SUFFIX', 'layout_file', 'read_layout', 'write_layout']

#: What the side file's name adds to the launch file's.
SUFFIX = '.studio.json'


def layout_file(launch_file: str) -> str:
    """The side file of ``launch_file``."""
    return launch_file + SUFFIX


def read_layout(launch_file: str) -> dict[str, dict[str, float]]:
    """The positions kept for ``launch_file`` (empty when none can be read)."""
    try:
        with open(layout_file(launch_file), encoding='utf-8') as stream:
            data = json.load(stream)
    except (OSError, ValueError):
        return {}
    positions = data.get('positions') if isinstance(data, dict) else None
    out: dict[str, dict[str, float]] = {}
    for key, value in (positions or {}).items():
        if isinstance(key, str) and isinstance(value, dict):
            x, y = value.get('x'), value.get('y')
            if isinstance(x, (int, float)) and isinstance(y, (int, float)) \
                    and not isinstance(x, bool) and not isinstance(y, bool):
                out[key] = {'x': float(x), 'y': float(y)}
    return out


def write_layout(launch_file: str, positions: Mapping[str, Mapping[str, Any]]) -> str:
    """Write the positions (final name -> ``{x, y}``) next to ``launch_file``; the side file's
    path.  :class:`nodl.writing.WriteError` when it cannot be written."""
    kept = {name: {'x': round(float(p['x']), 1), 'y': round(float(p['y']), 1)}
            for name, p in sorted(positions.items())}
    path = layout_file(launch_file)
    write_file(path, json.dumps({'version': 1, 'positions': kept}, indent=1) + '\n')
    return os.fspath(path)
