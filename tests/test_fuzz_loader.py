"""Fuzzing the loader with hypothesis.

Seeds are valid NoDL documents: the examples (``examples/*.yaml``) and the
fixture files under ``tests/fixtures/fuzz_seeds/``.  Two families of
mutation start from them:

* text mutations: insert, delete and replace characters, swap and duplicate
  lines, change indentation (spaces and tabs), inject YAML syntax
  (``&*!|>{}[],:#%@`` and friends), and flip bytes after encoding;
* data mutations: parse the seed, replace values with random JSON-like
  values (or with plausible NoDL values, to get past the first checks),
  drop keys, add unknown keys, then dump as YAML or JSON.

Properties: ``check_source`` never raises; every diagnostic has a line and
column >= 0, a non-empty message and a severity of error, warning
or info; ``load_nodl`` raises nothing but ``ValidationError``, and raises
exactly when the report has errors.  A document that loads can be dumped and
loaded again to the same data.

The runs are derandomized (reproducible in CI) and sized to finish in a few
seconds.
"""

from __future__ import annotations

import copy
import json
import math
import re
from pathlib import Path
from typing import Any

import yaml
from hypothesis import HealthCheck, Phase, example, given, settings
from hypothesis import strategies as st

from nodl import ValidationError, check_source, dump_nodl, load_nodl
from nodl.diagnostics import Severity

TESTS = Path(__file__).resolve().parent
REPO = TESTS.parent
SEED_FILES = sorted(REPO.glob('examples/*.yaml')) + sorted((TESTS / 'fixtures' / 'fuzz_seeds').iterdir())
SEEDS = [path.read_text(encoding='utf-8') for path in SEED_FILES]
# libyaml where available: the pure-Python loader and dumper would dominate the run time.
_Loader = getattr(yaml, 'CSafeLoader', yaml.SafeLoader)
_Dumper = getattr(yaml, 'CSafeDumper', yaml.SafeDumper)
SEED_DATA = [yaml.load(text, Loader=_Loader) for text in SEEDS]

SEVERITIES = {Severity.ERROR, Severity.WARNING, Severity.INFO}
LINE_BREAKS = re.compile('\r\n|[\n\r\x85\u2028\u2029]')

# No shrink phase: shrinking multi-kilobyte documents can take far longer than
# the run itself; a failure still reports the (unshrunk) document that failed.
FUZZ = settings(max_examples=200, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow],
                phases=[Phase.explicit, Phase.reuse, Phase.generate])


# --- the properties -----------------------------------------------------------------

def same_data(a: Any, b: Any) -> bool:
    """Equality where NaN equals NaN (a float default_value may be .nan)."""
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_data(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same_data(x, y) for x, y in zip(a, b, strict=True))
    return bool(a == b) and type(a) is type(b)


def check_invariants(source: str | bytes) -> None:
    report = check_source(source)  # must never raise
    diagnostics = report.diagnostics
    for diagnostic in diagnostics:
        assert isinstance(diagnostic.line, int) and diagnostic.line >= 0, diagnostic
        assert isinstance(diagnostic.column, int) and diagnostic.column >= 0, diagnostic
        assert isinstance(diagnostic.message, str) and diagnostic.message.strip(), diagnostic
        assert diagnostic.severity in SEVERITIES, diagnostic
        assert str(diagnostic.severity) in ('error', 'warning', 'info')
        text = str(diagnostic)
        assert text.startswith(diagnostic.file)
        assert json.dumps(diagnostic.to_dict())
    # YAML also breaks lines at CR, NEL, LS and PS; libyaml places "end of
    # stream" on the line after the last one.
    text = source if isinstance(source, str) else source.decode('utf-8', 'replace')
    lines = len(LINE_BREAKS.split(text)) + 1
    assert all(d.line <= lines for d in diagnostics), [str(d) for d in diagnostics]

    try:
        model = load_nodl(source)
    except ValidationError as exc:
        assert report.has_errors(), f'load_nodl raised, check_source found no error: {exc}'
        assert exc.errors, 'a ValidationError without an error'
        assert exc.errors == report.errors
        return
    assert not report.has_errors(), [str(d) for d in report.errors]
    # What loads can be written out and read back to the same data.
    for fmt in ('yaml', 'json'):
        again = load_nodl(dump_nodl(model, fmt))
        assert same_data(again.to_dict(), model.to_dict()), fmt


def test_seeds_are_valid_documents() -> None:
    assert len(SEED_FILES) >= 3
    for path in SEED_FILES:
        report = check_source(path)
        assert not report.has_errors(), [str(d) for d in report.errors]
        assert load_nodl(path) is not None


# --- text mutations ------------------------------------------------------------------

YAML_SPECIALS = list('&*!|>{}[],:#%@?-\'"`~<=\\') + ['\t', '\n', ' ', '\r', '\ufeff', '\x00', '\x85']
TOKENS = [
    '&a ', '*a', '*b', '&b [*a, *a]', '!foo ', '!!binary ', '!!set ', '!!int ', '!!bool ',
    '!!float ', '!!str ', '!!python/object/apply:os.system ', '<<: *a\n', '<<: ', '---\n',
    '...\n', '%YAML 1.1\n', '%TAG ! tag:x,2000:\n', '? ', ': ', '- ', '| ', '>- ', '{', '}',
    '[', ']', '[[[[[[', '{a: ', '"', "'", '# ', '\t', '  ', '\n', '\r\n', '0x1F', '1e5', '.nan',
    '2001-12-14', 'yes', 'null', '~', '"\\ud800"', '"\\x00"', '@', '`',
]

VALUE_PREFIXES = ['!!int ', '!!float ', '!!bool ', '!!null ', '!!str ', '!!binary ', '!!set ',
                  '!!map ', '!!seq ', '!!timestamp ', '!foo ', '!<tag:yaml.org,2002:int> ', '&a ',
                  '*a ', '| ', '> ', '[', '{', '- ', '? ', '"', "'"]

characters = st.one_of(st.sampled_from(YAML_SPECIALS), st.characters(codec='utf-8'))
snippets = st.one_of(st.sampled_from(TOKENS), st.text(characters, min_size=1, max_size=6))


@st.composite
def mutate_text(draw: st.DrawFn, text: str) -> str:
    for _ in range(draw(st.integers(1, 6))):
        operation = draw(st.sampled_from(
            ['insert', 'delete', 'replace', 'swap', 'duplicate', 'indent', 'tabify', 'token',
             'tag', 'alias']))
        lines = text.split('\n')
        valued = [i for i, line in enumerate(lines) if ': ' in line]
        if operation in ('tag', 'alias') and valued:
            # Work on a value: tag it, or anchor one value and alias it from another.
            i = draw(st.sampled_from(valued))
            key, _, value = lines[i].partition(': ')
            if operation == 'tag':
                lines[i] = f'{key}: {draw(st.sampled_from(VALUE_PREFIXES))}{value}'
            else:
                j = draw(st.sampled_from(valued))
                lines[i] = f'{key}: &x {value}'
                if j != i:
                    lines[j] = lines[j].partition(': ')[0] + ': *x'
            text = '\n'.join(lines)
        if operation in ('insert', 'token'):
            at = draw(st.integers(0, len(text)))
            piece = draw(st.sampled_from(TOKENS) if operation == 'token' else snippets)
            text = text[:at] + piece + text[at:]
        elif operation == 'delete' and text:
            at = draw(st.integers(0, len(text) - 1))
            text = text[:at] + text[at + draw(st.integers(1, 20)):]
        elif operation == 'replace' and text:
            at = draw(st.integers(0, len(text) - 1))
            text = text[:at] + draw(characters) + text[at + 1:]
        elif operation == 'swap' and len(lines) > 1:
            i, j = draw(st.integers(0, len(lines) - 1)), draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
            text = '\n'.join(lines)
        elif operation == 'duplicate':
            i = draw(st.integers(0, len(lines) - 1))
            lines.insert(i, lines[i])
            text = '\n'.join(lines)
        elif operation == 'indent':
            i = draw(st.integers(0, len(lines) - 1))
            delta = draw(st.integers(-4, 4))
            stripped = lines[i].lstrip(' ')
            indent = max(0, len(lines[i]) - len(stripped) + delta)
            lines[i] = ' ' * indent + stripped
            text = '\n'.join(lines)
        elif operation == 'tabify':
            i = draw(st.integers(0, len(lines) - 1))
            stripped = lines[i].lstrip(' ')
            spaces = len(lines[i]) - len(stripped)
            lines[i] = draw(st.sampled_from(['\t', '\t' * max(1, spaces // 2), ' \t'])) + stripped
            text = '\n'.join(lines)
    return text


@st.composite
def text_mutants(draw: st.DrawFn) -> str:
    return draw(mutate_text(draw(st.sampled_from(SEEDS))))


@FUZZ
@given(text_mutants())
# Cases the fuzzer found once; kept so that they are always tried.
@example('type: int\ndefault_value: !!int lots\n')     # explicit tag, impossible value
@example('type: !!bool maybe\n')
@example('null: 1\ntype: int\n')                      # a null key
@example('1.5: x\ntype: int\n')                       # a float key
@example('nodl_version: 2\nparameters:\n  ~: {type: int}\n')
@example('&odl_version: 2\nbase: node\n')               # an anchored null key
@example('a: &a [*a]\n')
def test_text_mutations_never_crash_the_loader(text: str) -> None:
    check_invariants(text)


@settings(FUZZ, max_examples=120)
@given(text_mutants(), st.data())
def test_byte_mutations_never_crash_the_loader(text: str, data: st.DataObject) -> None:
    raw = bytearray(text.encode('utf-8'))
    for _ in range(data.draw(st.integers(1, 4))):
        at = data.draw(st.integers(0, len(raw)))
        raw[at:at + data.draw(st.integers(0, 2))] = data.draw(st.binary(min_size=1, max_size=3))
    if data.draw(st.booleans()):
        raw[:0] = data.draw(st.sampled_from([b'\xef\xbb\xbf', b'\xff\xfe', b'\xfe\xff', b'']))
    check_invariants(bytes(raw))


# --- data mutations ------------------------------------------------------------------

keys = st.one_of(
    st.sampled_from(['nodl_version', 'type', 'default_value', 'description', 'read_only',
                     'validation', 'parameters', 'publishers', 'subscriptions', 'main', 'base',
                     'mixins', 'qos', 'history', 'depth', 'reliability', 'name', 'bounds<>',
                     'one_of<>', 'x-unknown', '<<', '']),
    st.text(st.characters(codec='utf-8'), max_size=10))

nodl_values = st.sampled_from([
    2, 1, 3, 0, -1, 2.0, True, False, None, '', 'double', 'int', 'string', 'bool_array',
    'string_fixed_0', 'int_array_fixed_3', 'KEEP_LAST', 'KEEP_ALL', 'RELIABLE', 'BEST_EFFORT',
    'VOLATILE', 'node', 'lifecycle_node', '~/topic', '/a/b', 'bad name!', 'pkg/msg/Type',
    'pkg/Type', 'std_srvs/srv/Trigger', 'nodl://pkg/iface', 'missing.nodl.yaml',
    [0.0, 1.0], [1.0, 0.0], [[1, 2, 3]], [], {}, {'bounds<>': [0, 10]}, {'not_empty<>': None},
    {'history': 'KEEP_LAST', 'reliability': 'RELIABLE'}, 10 ** 30, -(2 ** 63), 1e308,
])

json_values = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(), st.floats(), st.text(max_size=12),
              nodl_values),
    lambda children: st.one_of(st.lists(children, max_size=4),
                               st.dictionaries(keys, children, max_size=4)),
    max_leaves=8)


def containers(data: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Paths of every mapping and list in ``data``."""
    found: list[tuple[Any, ...]] = []
    if isinstance(data, dict):
        found.append(path)
        for key, value in data.items():
            found.extend(containers(value, path + (key,)))
    elif isinstance(data, list):
        found.append(path)
        for index, value in enumerate(data):
            found.extend(containers(value, path + (index,)))
    return found


def get(data: Any, path: tuple[Any, ...]) -> Any:
    for part in path:
        data = data[part]
    return data


@st.composite
def data_mutants(draw: st.DrawFn) -> str:
    data = copy.deepcopy(draw(st.sampled_from(SEED_DATA)))
    for _ in range(draw(st.integers(1, 4))):
        target = get(data, draw(st.sampled_from(containers(data))))
        operation = draw(st.sampled_from(['replace', 'replace', 'drop', 'add']))
        # A copy: sampled constants must not be mutated by a later step.
        value = copy.deepcopy(draw(json_values))
        if isinstance(target, dict):
            if operation == 'add' or not target:
                target[draw(keys)] = value
            elif operation == 'drop':
                del target[draw(st.sampled_from(sorted(target)))]
            else:
                target[draw(st.sampled_from(sorted(target)))] = value
        else:
            if operation == 'add' or not target:
                target.insert(draw(st.integers(0, len(target))), value)
            elif operation == 'drop':
                del target[draw(st.integers(0, len(target) - 1))]
            else:
                target[draw(st.integers(0, len(target) - 1))] = value
    fmt = draw(st.sampled_from(['yaml', 'yaml-flow', 'json', 'json-compact']))
    if fmt == 'yaml':
        return yaml.dump(data, Dumper=_Dumper, sort_keys=False, allow_unicode=draw(st.booleans()))
    if fmt == 'yaml-flow':
        return yaml.dump(data, Dumper=_Dumper, default_flow_style=True,
                         width=draw(st.integers(20, 200)))
    if fmt == 'json':
        return json.dumps(data, indent=2, ensure_ascii=draw(st.booleans()))
    return json.dumps(data, separators=(',', ':'))


@settings(FUZZ, max_examples=150)
@given(data_mutants())
def test_data_mutations_never_crash_the_loader(text: str) -> None:
    check_invariants(text)


@settings(FUZZ, max_examples=60)
@given(data_mutants(), st.data())
def test_data_mutations_then_text_mutations(text: str, data: st.DataObject) -> None:
    # Mutated data, dumped, then mutated as text: reaches odd corners of both.
    check_invariants(text)
    check_invariants(data.draw(mutate_text(text)))
