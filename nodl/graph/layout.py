"""Laying the DOT text out as SVG with ``graphviz-pure`` (the ``graph`` extra)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys

from nodl.files import describe_os_error
from nodl.graph.dot import format_dot
from nodl.graph.model import Graph, GraphError

__all__ = [
    'LAYOUT_PROGRAM',
    'VIEW',
    'find_layout_program',
    'fit_scale',
    'layout_graph',
    'layout_svg',
]

#: The picture's part of the page in a 1280x800 window (CSS pixels): what the layout is
#: chosen to fit.
VIEW = (900.0, 700.0)

#: The program that lays graphs out (it reads DOT like Graphviz's ``dot``).
LAYOUT_PROGRAM = 'graphviz-pure'
#: At most this long for one layout.
TIMEOUT = 120.0


def find_layout_program() -> str | None:
    """The layout program: next to this Python (a virtual environment), else on PATH."""
    beside = os.path.join(os.path.dirname(sys.executable), LAYOUT_PROGRAM)
    if os.path.isfile(beside) and os.access(beside, os.X_OK):
        return beside
    return shutil.which(LAYOUT_PROGRAM)


def layout_svg(dot: str) -> str:
    """The SVG of ``dot`` (GraphError if the layout program is missing or fails)."""
    program = find_layout_program()
    if program is None:
        raise GraphError(f"SVG and HTML pictures need the '{LAYOUT_PROGRAM}' program: "
                         "pip install 'nodl-toolkit[graph]' (or write a .dot file, and lay it "
                         'out with Graphviz)')
    try:
        done = subprocess.run([program, '-Tsvg'], input=dot.encode('utf-8'), capture_output=True,
                              timeout=TIMEOUT, check=False)
    except subprocess.TimeoutExpired:
        raise GraphError(f'{LAYOUT_PROGRAM} took longer than {TIMEOUT:.0f} s') from None
    except OSError as exc:
        raise GraphError(f'cannot run {program}: {describe_os_error(exc)}') from None
    if done.returncode != 0:
        message = done.stderr.decode('utf-8', 'replace').strip().splitlines()
        raise GraphError(f'{LAYOUT_PROGRAM} failed ({done.returncode}): '
                         f'{message[-1] if message else "no message"}')
    return done.stdout.decode('utf-8')


def fit_scale(svg: str, view: tuple[float, float] = VIEW) -> float:
    """How much ``svg`` (its ``viewBox``, in points) is scaled to fit ``view`` (CSS pixels)."""
    found = re.search(r'viewBox="[-\d.]+ [-\d.]+ ([\d.]+) ([\d.]+)"', svg)
    if found is None:
        return 1.0
    width, height = (float(n) * 4 / 3 for n in found.groups())   # pt -> px
    return min(view[0] / max(width, 1.0), view[1] / max(height, 1.0))


def layout_graph(graph: Graph, view: tuple[float, float] = VIEW) -> str:
    """The SVG of ``graph``: left to right as rqt_graph draws it, or top to bottom when that
    fits ``view`` at a larger scale (a long pipeline is far wider than a window, and fitted
    to it its labels would be dots)."""
    svg = layout_svg(format_dot(graph))
    scale = fit_scale(svg, view)
    if scale >= 1.0:   # shown at its natural size already
        return svg
    down = layout_svg(format_dot(graph, 'TB'))
    return down if fit_scale(down, view) > scale * 1.1 else svg
