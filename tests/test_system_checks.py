"""The nodl.checks extension point (nodl.system.checks): the NODL55x checks are registered
extensions; a check that raises or yields something else is reported (NODL567) and skipped,
and every other check still runs."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from nodl.system.checks import CheckExtension, load_checks
from nodl.system.context import AnalysisContext
from nodl.system.findings import Finding
from nodl.system.run import analyse_launch

FIXTURES = Path(__file__).parent / 'fixtures' / 'analysis'
PREFIX = [str(FIXTURES / 'prefix')]


class Raising(CheckExtension):
    kinds = ()

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        raise RuntimeError('boom')


class WrongYield(CheckExtension):
    kinds = ()

    def check(self, context: AnalysisContext) -> Iterator[Finding]:
        yield 'not a finding'  # type: ignore[misc]


def test_the_builtin_checks_load_from_the_shared_layer() -> None:
    checks, broken = load_checks()
    assert not broken
    assert {type(c).__module__ for c in checks.values()} >= {
        'nodl.system.checks.names', 'nodl.system.checks.connections',
        'nodl.system.checks.parameters', 'nodl.system.checks.orphans'}


def test_a_broken_check_is_reported_and_skipped() -> None:
    checks, _ = load_checks()
    alone = analyse_launch(FIXTURES / 'launch' / 'checks.launch.xml', prefixes=PREFIX,
                           checks=checks)
    mixed = analyse_launch(FIXTURES / 'launch' / 'checks.launch.xml', prefixes=PREFIX,
                           checks={'raising': Raising(), **checks, 'wrong': WrongYield()})
    broken = [f for f in mixed.findings if f.kind == 'broken-check']
    assert [(f.code, f.diagnostic.file) for f in broken] == [('NODL567', '<nodl.checks>')] * 2
    assert "check 'raising' skipped: it raised RuntimeError: boom" in broken[0].message
    assert "check 'wrong' skipped" in broken[1].message and 'other than Finding' in broken[1].message
    assert [f.to_dict() for f in mixed.findings if f.kind != 'broken-check'] == \
        [f.to_dict() for f in alone.findings]


def test_the_former_path_of_the_extension_point_still_works_and_says_where_it_went() -> None:
    import importlib
    import sys
    import warnings

    sys.modules.pop('nodl.analysis.checks', None)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always')
        former = importlib.import_module('nodl.analysis.checks')
    assert former.CheckExtension is CheckExtension and former.load_checks is load_checks
    assert [str(w.message) for w in caught if w.category is DeprecationWarning] == [
        'nodl.analysis.checks moved to nodl.system.checks; import it from there']
