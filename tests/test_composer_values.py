"""nodl.composer.values: each format spells a value so that launch reads it back the same."""

from __future__ import annotations

import ast

import pytest
import yaml

from nodl.composer.values import (
    python_value,
    same_value,
    typed_value,
    xml_value,
    yaml_needs_type,
    yaml_value_text,
)
from nodl.launch.params import get_typed_value, type_from_identifier

VALUES = [0.4, 3, -7, True, False, 'hello', '3', 'true', '', 'a b: c', 1e-05, 1e20,
          [1, 2], [0.5, 1.5], ['a', 'b'], ['1', '2'], [True, False], 'x"<&>\'y', 'two\nlines: {a}']


def test_typed_as_launch_types_a_value() -> None:
    assert typed_value('0.4') == 0.4 and typed_value('3') == 3 and typed_value('true') is True
    assert typed_value('[1, 2]') == [1, 2] and typed_value('rover') == 'rover'
    with pytest.raises(ValueError):
        typed_value('{a: 1}')   # a mapping is no parameter value


@pytest.mark.parametrize('value', VALUES, ids=repr)
def test_xml_spelling_reads_back(value) -> None:  # type: ignore[no-untyped-def]
    text, type_ = xml_value(value)
    back = get_typed_value(text, type_from_identifier(type_) if type_ else None)
    assert same_value(back, value), (text, type_, back)


@pytest.mark.parametrize('value', VALUES, ids=repr)
def test_yaml_spelling_reads_back(value) -> None:  # type: ignore[no-untyped-def]
    raw = yaml.safe_load(yaml_value_text(value))
    type_ = yaml_needs_type(value)
    data_type = type_from_identifier(type_) if type_ else None
    if isinstance(raw, str):   # launch_yaml types a string value again
        raw = get_typed_value(raw, data_type)
    elif isinstance(raw, list) and data_type is not None:
        raw = [get_typed_value(x, data_type[1]) if isinstance(x, str) else x for x in raw]
    assert same_value(raw, value), (yaml_value_text(value), type_, raw)


def test_yaml_spelling_is_one_line() -> None:
    assert yaml_value_text('two\nlines') == '"two\\nlines"'


@pytest.mark.parametrize('value', VALUES, ids=repr)
def test_python_spelling_is_the_literal(value) -> None:  # type: ignore[no-untyped-def]
    assert same_value(ast.literal_eval(python_value(value)), value)


def test_same_value_is_strict_about_types() -> None:
    assert not same_value(1, 1.0) and not same_value(True, 1) and same_value([1], [1])
