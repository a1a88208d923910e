"""nodl.composer.change: what an operation answers."""

from __future__ import annotations

import json

from nodl.composer import Change, ComposerError
from nodl.diagnostics import Diagnostic, Severity


def test_a_change_is_ok_unless_an_error_says_otherwise() -> None:
    warned = Change([Diagnostic(Severity.WARNING, 'unchecked', file='a.launch.xml',
                                code='NODL985')], 'n1',
                    remaps=[{'node': 'n1', 'from': 'a', 'to': 'b'}])
    assert warned.ok and Change().ok
    refused = Change([Diagnostic(Severity.ERROR, 'no', file='a.launch.xml', code='NODL982')])
    assert not refused.ok
    data = json.loads(json.dumps(warned.to_dict()))
    assert data['ok'] and data['node'] == 'n1' and data['removed'] == []
    assert data['remaps'] == [{'node': 'n1', 'from': 'a', 'to': 'b'}]
    assert data['diagnostics'][0]['code'] == 'NODL985'


def test_a_composer_error_carries_its_diagnostic() -> None:
    problem = Diagnostic(Severity.ERROR, 'the file exists already', file='a.launch.xml',
                         code='NODL981')
    error = ComposerError(problem)
    assert error.diagnostic is problem and str(error) == 'the file exists already'
