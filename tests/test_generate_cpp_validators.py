"""Each built-in validator's C++ translation agrees with the validator table's own predicate.

Every case is compiled into one small C++17 program (standard library only) with
the system's compiler and run; its verdicts must equal
``ValidatorRule.predicate`` on the same value and arguments.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path
from typing import Any

from nodl.generate.cpp.parameter_code import CPP_PREDICATES, helper_lines
from nodl.generate.cpp.text import cpp_type, cpp_value
from nodl.validation.validators import BUILTIN_NAMES, VALIDATORS

#: (validator, raw arguments as written, parameter type, values)
CASES: list[tuple[str, Any, str, list[Any]]] = [
    ('bounds', [0, 10], 'int', [-1, 0, 5, 10, 11]),
    ('bounds', [0.5, 1.5], 'double', [0.4, 0.5, 1.5, 1.6]),
    ('bounds', [0, 1], 'double', [-0.1, 0.0, 1.0, 1.01]),
    ('lt', [10], 'int', [9, 10, 11]),
    ('gt', 10, 'int', [9, 10, 11]),
    ('lt_eq', [2.5], 'double', [2.4, 2.5, 2.6]),
    ('gt_eq', [2.5], 'double', [2.4, 2.5, 2.6]),
    ('gt', [0], 'double', [-1.0, 0.0, 1e-9]),
    ('one_of', [[9600, 57600]], 'int', [9600, 57600, 1]),
    ('one_of', [['rgb8', 'bgr8']], 'string', ['rgb8', 'mono8', '']),
    ('one_of', [[1.5, 2]], 'double', [1.5, 2.0, 1.0]),
    ('one_of', [[True]], 'bool', [True, False]),
    ('not_empty', None, 'string', ['', 'x']),
    ('not_empty', [], 'int_array', [[], [1]]),
    ('fixed_size', [2], 'string', ['ab', 'abc', '']),
    ('fixed_size', 2, 'double_array', [[1.0, 2.0], [1.0]]),
    ('size_gt', [1], 'string_array', [['a'], ['a', 'b']]),
    ('size_lt', [3], 'string', ['ab', 'abc']),
    ('unique', None, 'int_array', [[1, 2, 1], [1, 2], []]),
    ('unique', None, 'string_array', [['a', 'b'], ['a', 'a']]),
    ('unique', None, 'bool_array', [[True, False], [True, True]]),
    ('subset_of', [['a', 'b']], 'string_array', [['a'], ['a', 'c'], []]),
    ('subset_of', [[1, 2]], 'int_array', [[1, 2, 2], [3]]),
    ('element_bounds', [0.0, 2.0], 'double_array', [[0.5, 1.0], [3.0], []]),
    ('element_bounds', [0, 200], 'byte_array', [[1, 200], [201]]),
    ('lower_element_bounds', [0], 'int_array', [[0, 1], [-1]]),
    ('upper_element_bounds', [2], 'double_array', [[1.0, 2.0], [3.0]]),
    # every other type each validator applies to (test_every_applicable_type_is_covered)
    ('lt', [2.5], 'double', [2.4, 2.5, 2.6]),
    ('lt_eq', [3], 'int', [2, 3, 4]),
    ('gt_eq', [3], 'int', [2, 3, 4]),
    ('not_empty', None, 'bool_array', [[], [False]]),
    ('not_empty', None, 'double_array', [[], [0.0]]),
    ('not_empty', None, 'string_array', [[], ['']]),
    ('not_empty', None, 'byte_array', [[], [0]]),
    ('fixed_size', [2], 'bool_array', [[True, False], [True]]),
    ('fixed_size', [2], 'int_array', [[1, 2], [1, 2, 3]]),
    ('fixed_size', [2], 'string_array', [['a', 'b'], []]),
    ('fixed_size', [2], 'byte_array', [[1, 2], [1]]),
    ('size_gt', [1], 'string', ['a', 'ab']),
    ('size_gt', [1], 'bool_array', [[True], [True, False]]),
    ('size_gt', [1], 'int_array', [[1], [1, 2]]),
    ('size_gt', [1], 'double_array', [[1.0], [1.0, 2.0]]),
    ('size_gt', [1], 'byte_array', [[1], [1, 2]]),
    ('size_lt', [2], 'bool_array', [[True], [True, True]]),
    ('size_lt', [2], 'int_array', [[1], [1, 2]]),
    ('size_lt', [2], 'double_array', [[], [1.0, 2.0]]),
    ('size_lt', [2], 'string_array', [['a'], ['a', 'b']]),
    ('size_lt', [2], 'byte_array', [[1], [1, 2]]),
    ('unique', None, 'double_array', [[1.0, 2.0], [1.5, 1.5]]),
    ('unique', None, 'byte_array', [[1, 2], [3, 3]]),
    ('subset_of', [[True]], 'bool_array', [[True, True], [False]]),
    ('subset_of', [[0.5, 1]], 'double_array', [[0.5, 1.0], [2.0]]),
    ('subset_of', [[1, 2]], 'byte_array', [[1], [3]]),
    ('element_bounds', [0, 10], 'int_array', [[0, 10], [11], [-1]]),
    ('lower_element_bounds', [0.5], 'double_array', [[0.5], [0.4]]),
    ('lower_element_bounds', [10], 'byte_array', [[10], [9]]),
    ('upper_element_bounds', [2], 'int_array', [[2], [3]]),
    ('upper_element_bounds', [200], 'byte_array', [[200], [201]]),
]


def test_every_builtin_validator_is_covered() -> None:
    assert {c[0] for c in CASES} == set(BUILTIN_NAMES) == set(CPP_PREDICATES)


def test_every_applicable_type_is_covered() -> None:
    """Each validator is exercised on every parameter type the validator table lets it validate."""
    from nodl.model.parameter_types import parse_type
    from nodl.vocabulary import ARRAY_TYPES, SCALAR_TYPES

    types = [t for t in (*SCALAR_TYPES, *ARRAY_TYPES) if t != 'none']
    needed = {(name, t) for name in BUILTIN_NAMES for t in types if VALIDATORS[name].applies_to(parse_type(t))}
    assert needed - {(c[0], c[2]) for c in CASES} == set()
    assert {(c[0], c[2]) for c in CASES} <= needed


def test_cpp_translations_agree_with_the_table(tmp_path: Path) -> None:
    compiler = shutil.which('g++') or shutil.which('c++') or shutil.which('clang++')
    assert compiler, 'a C++ compiler is needed (CMake builds need one too)'
    body: list[str] = []
    expected: list[str] = []
    for index, (name, raw, type_name, values) in enumerate(CASES):
        rule = VALIDATORS[name]
        assert rule.accepts(raw), (name, raw)
        argument = rule.argument(raw)
        element = 'byte' if type_name == 'byte_array' else type_name.replace('_array', '')
        for n, value in enumerate(values):
            variable = f'v{index}_{n}'
            body.append(f'  const {cpp_type(type_name)} {variable} = {cpp_value(value, type_name)};')
            condition = CPP_PREDICATES[name](variable, argument, element)
            body.append(f'  std::cout << ({condition} ? 1 : 0) << "\\n";')
            python_value = bytes(value) if type_name == 'byte_array' else value
            expected.append('1' if rule.predicate(list(python_value) if type_name == 'byte_array'
                                                  else python_value, argument) else '0')
    program = '\n'.join(['#include <algorithm>', '#include <cstddef>', '#include <cstdint>',
                         '#include <iostream>', '#include <limits>', '#include <string>',
                         '#include <vector>', ''] + helper_lines() +
                        ['', 'int main()', '{'] + body + ['  return 0;', '}']) + '\n'
    source = tmp_path / 'validators.cpp'
    source.write_text(program, encoding='utf-8')
    binary = tmp_path / 'validators'
    compiled = subprocess.run([compiler, '-std=c++17', '-Wall', '-Wextra', '-o', str(binary),
                               str(source)], capture_output=True, text=True, timeout=120)
    assert compiled.returncode == 0, compiled.stderr
    assert 'warning' not in compiled.stderr, compiled.stderr
    run = subprocess.run([str(binary)], capture_output=True, text=True, timeout=30)
    assert run.returncode == 0
    verdicts = run.stdout.split()
    cases = [(c[0], c[1], v) for c in CASES for v in c[3]]
    assert len(verdicts) == len(expected) == len(cases)
    disagreements = [(case, got, want) for case, got, want in zip(cases, verdicts, expected, strict=True)
                     if got != want]
    assert disagreements == []
