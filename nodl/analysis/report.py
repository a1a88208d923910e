"""An analysis as JSON, text, SARIF and JUnit.

The JSON shape (``--format json``)::

    {"nodes": [{"name": "/robot/camera", "package": "...", "executable": "...",
                "definition": "/path/camera.nodl.yaml" | null,
                "definition_source": "index" | "overlay" | "file" | null,
                "definition_folder": "my_defs" | null,    # the definitions folder (overlay)
                "definition_provenance": "extracted" | "described" | null,
                "source": {"file": "robot.launch.xml", "line": 12},
                "remaps": [["from", "to"], ...],          # in the order rcl applies them
                "remaps_complete": true,                  # false: more rules come at run time
                "parameters": {"fps": 30.0, ...},         # the final values it receives
                "parameters_complete": true,              # false: more values come at run time
                "run_time": [{"part": "parameter", "parameter": "robot_description",
                              "file": "...", "line": 7, "column": 5}],   # what only it knows
                "endpoints": {"publishers": [["~/image", "/robot/camera/image"], ...], ...}}],
     "findings": [{"code": "NODL553", "kind": "qos-incompatible", "severity": "error",
                   "message": "...", "file": "...", "line": 12, "column": 5,
                   "nodes": ["/lidar", "/planner"], "endpoint": "/scan"}]}

``definition_source`` says which served the definition: the ament index, a definitions
folder (``definition_folder``; ``--definitions``, ``NODL_PATH``, ``nodl.toml``), or a
file given by path (``nodl analyse DEFINITION...``); ``definition_provenance`` whether
``nodl extract`` or ``nodl describe`` wrote that file (its header says so).  The text
report says, before its summary line, how many nodes each source served
(:func:`coverage`).

A composable node's ``executable`` is its plugin class.  ``parameters_complete`` /
``remaps_complete`` are false when the launch gives the node parameters or remapping
rules only the running launch knows (a parameter file whose path is a run-time value,
``remappings=``/``arguments=`` computed by a module not installed here: a NODL513
warning): ``parameters`` and ``remaps`` are then the known ones.  A parameter whose value
only the running launch knows is ``null`` in ``parameters`` (and ``parameters_complete`` is
false).  ``run_time`` lists each such part, with where it is written: ``parameter`` (one
value, named), ``parameters`` (a source of values), ``remaps`` or ``arguments``.
"""

from __future__ import annotations

import json
from typing import Any

from nodl.diagnostics import Severity
from nodl.reporting.junit import JUnitCase, JUnitFailure
from nodl.reporting.reporters import JUnitReporter, Report, SarifReporter
from nodl.system.findings import KINDS
from nodl.system.launched import SystemNode, node_provenance
from nodl.system.run import LAUNCH_KIND, Analysis
from nodl.targets.resolve import coverage_line
from nodl.text_safety import visible

__all__ = [
    'analysis_report',
    'analysis_to_dict',
    'coverage',
    'format_json',
    'format_junit',
    'format_sarif',
    'format_text',
    'junit_cases',
    'node_provenance',
    'node_to_dict',
    'summary',
]


def coverage(analysis: Analysis) -> str:
    """``16 nodes: 9 registered, 6 overlay (2 extracted), 1 without definition``."""
    return coverage_line(node_provenance(node) for node in analysis.nodes)


def node_to_dict(node: SystemNode) -> dict[str, Any]:
    """One node of the JSON report (:meth:`~nodl.system.launched.SystemNode.to_dict`)."""
    return node.to_dict()


def analysis_to_dict(analysis: Analysis) -> dict[str, Any]:
    """``{"nodes": [...], "findings": [...]}``."""
    return {'nodes': [node_to_dict(n) for n in analysis.nodes],
            'findings': [f.to_dict() for f in analysis.findings]}


def format_json(analysis: Analysis) -> str:
    """The JSON report (one object)."""
    return json.dumps(analysis_to_dict(analysis), indent=2, default=str) + '\n'


def summary(analysis: Analysis) -> str:
    """``N nodes, N errors, N warnings`` (and infos when there are some)."""
    return analysis.summary()


def format_text(analysis: Analysis, verbose: bool = False) -> str:
    """One ``FILE:LINE:COL: severity: message [CODE]`` line per finding (info with
    ``verbose``), then the summary line."""
    lines = [visible(str(f), one_line=True) for f in analysis.findings
             if verbose or f.severity is not Severity.INFO]
    if verbose:  # which file served each node, and from where
        for node in analysis.nodes:
            if node.match.file is not None:
                lines.append(visible(f'{node.fqn}: {node.match.file} ({node_provenance(node)})',
                                     one_line=True))
    lines.append(coverage(analysis))
    lines.append(summary(analysis))
    return '\n'.join(lines) + '\n'


def format_sarif(analysis: Analysis) -> str:
    """SARIF 2.1.0 (one result per finding)."""
    return SarifReporter().report(analysis_report(analysis))


def junit_cases(analysis: Analysis) -> list[JUnitCase]:
    """One JUnit test case per kind of finding (failed when it has errors), the errors as
    its failure and the other findings as its output."""
    by_kind: dict[str, list[Any]] = {kind: [] for kind in (LAUNCH_KIND, *KINDS)}
    for finding in analysis.findings:
        by_kind.setdefault(finding.kind, []).append(finding)
    classname = 'nodl.analyse.' + (analysis.launch_file or 'launch')
    cases = []
    for kind, found in by_kind.items():
        errors = [f for f in found if f.severity is Severity.ERROR]
        failures = [JUnitFailure(kind, f'{len(errors)} error(s)', '\n'.join(str(f) for f in errors))
                    ] if errors else []
        cases.append(JUnitCase(kind, [f.diagnostic for f in found], bool(errors), classname=classname,
                               failures=failures,
                               output=[str(f) for f in found if f.severity is not Severity.ERROR]))
    return cases


def format_junit(analysis: Analysis) -> str:
    """JUnit XML: one test case per kind of finding (:func:`junit_cases`)."""
    return JUnitReporter().report(analysis_report(analysis))


def analysis_report(analysis: Analysis, verbose: bool = False) -> Report:
    """The analysis as every reporter reads it: its findings, the nodes as the JSON payload,
    a test case per kind of finding, the text report, and the coverage and summary lines."""
    return Report(f'nodl analyse {analysis.launch_file or "launch"}',
                  [f.diagnostic for f in analysis.findings],
                  summary=f'{coverage(analysis)}\n{summary(analysis)}',
                  text=lambda: format_text(analysis, verbose), payload=lambda: analysis_to_dict(analysis),
                  cases=lambda: junit_cases(analysis))
