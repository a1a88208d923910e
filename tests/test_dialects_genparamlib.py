"""generate_parameter_library files: recognised, converted to NoDL, and written back."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from conftest import FIXTURES
from nodl.dialects import GENPARAMLIB, recognise
from nodl.dialects.convert import convert_dialect
from nodl.dialects.genparamlib import export_genparamlib
from nodl.frontends.genparamlib import read_genparamlib
from nodl.loading import check_source, load_interface
from nodl.model import ParameterDefinition

GPL = FIXTURES / 'dialects' / 'genparamlib'


def test_validate_says_what_the_file_is() -> None:
    report = check_source(GPL / 'gripper_controller.yaml', file='gripper_controller.yaml')
    [error] = report.diagnostics
    assert error.code == 'NODL861'
    assert 'generate_parameter_library file' in error.message
    assert 'nodl convert --from genparamlib' in error.message
    assert (error.line, error.column) == (2, 1)
    assert "missing required key 'type'" not in error.message


def test_recognise() -> None:
    assert recognise({'ctrl': {'gain': {'type': 'double'}}}) == GENPARAMLIB
    assert recognise({'ctrl': {'ns': {'deeper': {'gain': {'type': 'int'}}}}}) == GENPARAMLIB
    # A parameter definition, an interface that forgot nodl_version: not this dialect.
    assert recognise({'type': 'double'}) is None
    assert recognise({'parameters': {'gain': {'type': 'double'}}}) is None
    assert recognise({'ctrl': {'gain': 3}}) is None


def test_leaves_become_dotted_parameters_with_everything_kept() -> None:
    data = yaml.safe_load((GPL / 'gripper_controller.yaml').read_text())
    reading = read_genparamlib(data)
    assert reading.namespace == 'gripper_controller'
    params = reading.data['parameters']
    assert list(params) == ['joint_name', 'mode', 'max_effort', 'gains.position.p',
                            'gains.position.limits', 'sensors']
    assert params['max_effort']['additional_constraints'].startswith('Must not exceed')
    assert params['max_effort']['validation']['gripper_checks::below_rated_effort'] == [100.0]
    assert params['gains.position.limits']['type'] == 'double_array_fixed_2'
    assert params['joint_name']['read_only'] is True
    assert reading.skipped == ['__map_sensors.threshold', '__map_sensors.filter.window']


def test_map_parameters_are_listed_in_one_warning() -> None:
    conversion = convert_dialect(str(GPL / 'gripper_controller.yaml'))
    assert conversion.data is not None
    [warning] = conversion.diagnostics
    assert warning.code == 'NODL862' and warning.line == 46
    assert '__map_sensors.threshold' in warning.message
    assert '__map_sensors.filter.window' in warning.message


def test_errors_are_placed_in_the_original_file() -> None:
    conversion = convert_dialect(str(GPL / 'bad_default.yaml'))
    assert conversion.data is None
    errors = {(d.line, d.path_text, d.code) for d in conversion.diagnostics
              if d.severity == 'error'}
    assert (5, 'wheel_controller.wheel.radius.default_value', 'NODL210') in errors
    assert (12, 'wheel_controller.wheel.count.descriptoin', 'NODL101') in errors


def test_one_namespace_only() -> None:
    conversion = convert_dialect(str(GPL / 'two_roots.yaml'))
    assert conversion.data is None
    [error] = [d for d in conversion.diagnostics if d.severity == 'error']
    assert error.code == 'NODL863' and error.line == 3


def _without_defaults(tree: dict[str, Any]) -> dict[str, Any]:
    """generate_parameter_library's own defaults (read_only false) written or not mean the same."""
    out: dict[str, Any] = {}
    for key, value in tree.items():
        if isinstance(value, dict):
            value = _without_defaults(value)
        if key == 'read_only' and value is False:
            continue
        out[key] = value
    return out


def _without_maps(tree: dict[str, Any]) -> dict[str, Any]:
    return {k: _without_maps(v) if isinstance(v, dict) else v
            for k, v in tree.items() if not str(k).startswith('__map_')}


def test_round_trip_keeps_what_nodl_can_express(tmp_path: Path) -> None:
    original = yaml.safe_load((GPL / 'gripper_controller.yaml').read_text())
    conversion = convert_dialect(str(GPL / 'gripper_controller.yaml'))
    written = tmp_path / conversion.file_name
    written.write_text(conversion.text())
    interface = load_interface(written)
    exported = export_genparamlib(interface.parameters, 'gripper_controller')
    assert exported.diagnostics == []
    back = yaml.safe_load(exported.text())
    assert _without_defaults(back) == _without_defaults(_without_maps(original))


def test_export_writes_builtin_validators_with_angle_brackets_and_skips_none() -> None:
    params = {
        'rate': ParameterDefinition('int', 10, validation={'bounds': [1, 100]}),
        'nothing': ParameterDefinition('none'),
        'a.b': ParameterDefinition('int', 1),
        'a': ParameterDefinition('int', 1),
        'bad-name': ParameterDefinition('int', 1),
    }
    exported = export_genparamlib(params, 'ctrl')
    assert exported.data['ctrl']['rate']['validation'] == {'bounds<>': [1, 100]}
    assert exported.data['ctrl']['a'] == {'b': {'type': 'int', 'default_value': 1}}
    skipped = sorted(d.path[1] for d in exported.diagnostics)
    assert skipped == ['a', 'bad-name', 'nothing']
    assert all(d.code == 'NODL864' for d in exported.diagnostics)


def test_export_escapes_descriptions() -> None:
    text = "colon: here, quote ' and \"double\"\nnew line # not a comment"
    exported = export_genparamlib({'p': ParameterDefinition('string', 'x', description=text)}, 'ns')
    assert yaml.safe_load(exported.text())['ns']['p']['description'] == text
