"""nodl.composer.setting: a parameter of a node's entry, checked against its declaration at once.

The value is typed as launch types it and checked with the shared parameter plan; where it is
written (in place, or after a kept parameter file that would set it again) is compared with an
expected file.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from composer_helpers import FIXTURES, copy_launch, definitions
from nodl.composer import Composition
from nodl.composer.setting import check_value, parameter_plans, set_parameter

EXPECTED = FIXTURES / 'expected'


@pytest.fixture
def params(tmp_path: Path) -> Composition:
    return Composition.open(str(copy_launch(tmp_path) / 'params.launch.xml'),
                            definitions=definitions())


def test_plans_and_checks_of_a_definition(params: Composition) -> None:
    talker = params.node('talker')
    assert talker is not None
    plans = parameter_plans(params.definition_of(talker))
    assert {'prefix', 'rate', 'use_sim_time'} <= {p.name for p in plans.parameters}
    rate = plans.get('rate')
    assert check_value(rate, 5.0) == []
    assert check_value(rate, 500.0) == ['must be between 0.1 and 100.0']
    assert check_value(rate, 'fast') and check_value(plans.get('prefix'), 'hi') == []


def test_values_are_written_where_they_win(params: Composition) -> None:
    # rate is also in a parameter file after it: it moves last, where it wins
    assert set_parameter(params, 'talker', 'rate', '7.5').ok
    # in place when nothing later sets it again; a string parameter takes the text as it is
    assert set_parameter(params, 'second', 'rate', '9.0').ok
    assert set_parameter(params, 'second', 'prefix', '3').ok
    second = params.node('second')
    assert second is not None and second.param_values() == {'rate': 9.0, 'prefix': '3'}
    assert params.render() == (EXPECTED / 'params.set.launch.xml').read_text(encoding='utf-8')


def test_refusals_say_what_the_parameter_accepts(params: Composition) -> None:
    typed = set_parameter(params, 'talker', 'rate', '3')
    assert [d.code for d in typed.diagnostics] == ['NODL977']
    assert 'write 3.0 for a double' in typed.diagnostics[0].message
    assert (typed.diagnostics[0].line, typed.diagnostics[0].column) == (2, 3)
    unknown = set_parameter(params, 'talker', 'rates', '3.0')
    assert [d.code for d in unknown.diagnostics] == ['NODL978']
    assert "did you mean 'rate'" in unknown.diagnostics[0].message
    mapping = set_parameter(params, 'talker', 'rate', '{a: 1}')
    assert [d.code for d in mapping.diagnostics] == ['NODL977']
    assert [d.code for d in set_parameter(params, 'nobody', 'rate', '1.0').diagnostics] == \
        ['NODL970']
    assert not params.dirty


def test_a_node_without_definition_is_written_unchecked(params: Composition) -> None:
    assert params.add('demo_pkg', 'unknown', 'mystery').ok
    change = set_parameter(params, 'mystery', 'anything', '1')
    assert change.ok and [d.code for d in change.diagnostics] == ['NODL985']
    assert '<param name="anything" value="1"/>' in params.render()
