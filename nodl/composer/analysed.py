"""The real analysis (``nodl analyse``) of a composition, and its nodes found again.

The composition is analysed as written: the text it would save is analysed by the launch
reader and the checks exactly as ``nodl analyse`` analyses a file.  An unsaved text is
written first to a hidden file next to the launch file (so that ``$(dirname)``, relative
includes and the configuration found upward mean what they mean for the saved file) and
removed at once; findings name the launch file itself.  Each launched node the analysis
reports in the launch file is found again among the composition's nodes by the lines the
node's entry occupies in the written text.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from dataclasses import dataclass, field
from typing import Any

from nodl.composer.rendering import Rendered
from nodl.diagnostics import Diagnostic
from nodl.system.run import analyse_launch
from nodl.system.settings import load_settings

__all__ = ['ComposedAnalysis', 'analyse_text']


@dataclass
class ComposedAnalysis:
    """An analysis of the composition's text, with its nodes by the composition's ids."""

    #: The analysis (:class:`nodl.system.run.Analysis`).
    analysis: Any
    #: The findings, each naming the launch file (not the hidden copy analysed).
    findings: list[Any]
    #: composition node id -> the launched node (:class:`nodl.system.launched.SystemNode`).
    by_id: dict[str, Any] = field(default_factory=dict)
    #: The launched nodes that are not the composition's (from includes, kept code).
    others: list[Any] = field(default_factory=list)

    def node(self, node_id: str) -> Any:
        """The launched node of a composition node, or None (not launched, e.g. a condition)."""
        return self.by_id.get(node_id)


def _renamed(finding: Any, hidden: str, path: str) -> Any:
    d: Diagnostic = finding.diagnostic
    related = tuple((path if f == hidden else f, line, column, message)
                    for f, line, column, message in d.related)
    if d.file != hidden and related == d.related:
        return finding
    return finding.with_diagnostic(d.replace(file=path if d.file == hidden else d.file,
                                             related=related))


def analyse_text(path: str, rendered: Rendered, *, on_disk: bool,
                 definitions: Any = None, limits: Any = None,
                 arguments: dict[str, str] | None = None,
                 prefixes: list[str] | None = None) -> ComposedAnalysis:
    """Analyse ``rendered`` as the launch file ``path`` (``on_disk``: the file holds that text
    already).  OSError when the hidden copy cannot be written."""
    target = os.path.abspath(path)
    hidden = target
    if not on_disk:
        folder, base = os.path.split(target)
        suffix = next((s for s in ('.launch.xml', '.launch.yaml', '.launch.yml', '.launch.py')
                       if base.lower().endswith(s)), os.path.splitext(base)[1])
        fd, hidden = tempfile.mkstemp(prefix='.nodl-system-', suffix=suffix, dir=folder)
        with os.fdopen(fd, 'w', encoding='utf-8') as stream:
            stream.write(rendered.text)
    try:
        try:
            settings = load_settings(target)
        except Exception:  # noqa: BLE001 - a broken configuration is nodl analyse's to report
            settings = None
        analysis = analyse_launch(hidden, arguments or {}, settings=settings, limits=limits,
                                  definitions=definitions, prefixes=prefixes)
    finally:
        if hidden != target:
            with contextlib.suppress(OSError):
                os.unlink(hidden)
    findings = [_renamed(f, hidden, target) for f in analysis.findings]
    out = ComposedAnalysis(analysis, findings)
    real = os.path.realpath(hidden)
    spans = sorted(rendered.spans.items(), key=lambda item: item[1][1] - item[1][0])
    for launched in analysis.nodes:
        where = launched.location
        if where.file != hidden and os.path.realpath(str(where.file)) != real:
            out.others.append(launched)
            continue
        found = next((node_id for node_id, (first, last) in spans
                      if first <= where.line <= last and node_id not in out.by_id), None)
        if found is None:
            out.others.append(launched)
        else:
            out.by_id[found] = launched
    return out
