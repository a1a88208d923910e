"""Hostile input: each is rejected with exactly one clear one-line error, fast and small.

Every payload runs in a process of its own (a child forked from one warm
worker subprocess), so that a crash in libyaml (a segfault on deep nesting)
fails the test instead of killing the test run, and so that the peak memory
(``ru_maxrss``) measured there belongs to that payload alone.  Limits: under
2 s (``time.perf_counter``) and under 200 MB of peak memory growth, for
``check_source`` and for ``load_nodl`` each.

The depth limit is checked at its boundary in-process: exactly
``MAX_DEPTH`` (100) collection levels are accepted, one more is rejected.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from nodl import ValidationError, check_source, load_nodl
from nodl.frontends.source import MAX_BYTES
from nodl.frontends.yaml_json import MAX_DEPTH

REPO = Path(__file__).resolve().parent.parent
MAX_SECONDS = 2.0
MAX_MEGABYTES = 200

DEPTH = f'document nests deeper than {MAX_DEPTH} levels'


# --- payloads -------------------------------------------------------------------

def billion_laughs() -> str:
    """The classic: 9 levels of 10 aliases each, 10**9 'lol's once expanded."""
    lines = ['lol0: &lol0 "lol"']
    for level in range(1, 10):
        refs = ', '.join([f'*lol{level - 1}'] * 10)
        lines.append(f'lol{level}: &lol{level} [{refs}]')
    return '\n'.join(lines) + '\n'


def billion_laughs_block() -> str:
    """The same attack in block style, inside a plausible parameter definition."""
    out = ['type: string_array', 'description: laughs', 'x-lol:', '  l0: &l0 lol']
    for level in range(1, 10):
        out.append(f'  l{level}: &l{level}')
        out.extend(f'    - *l{level - 1}' for _ in range(10))
    out.append('default_value: *l9')
    return '\n'.join(out) + '\n'


def quadratic_blowup() -> str:
    """One big anchored list referenced many times (no nesting at all)."""
    items = ', '.join(str(i) for i in range(2000))
    refs = ', '.join(['*big'] * 200)
    return f'type: int_array\nbig: &big [{items}]\ndefault_value: [{refs}]\n'


def alias_depth() -> str:
    """Aliases that nest the data far deeper than the text: 14 x 95 levels."""
    items = []
    for i in range(14):
        inner = f'*a{i - 1}' if i else 'x'
        items.append(f'&a{i} ' + '[' * 95 + inner + ']' * 95)
    return 'type: int\ndescription: d\nvalidation:\n  my_ns::check: [' + ', '.join(items) + ']\n'


def deep_block_mappings(levels: int) -> str:
    return ''.join(' ' * i + f'k{i}:\n' for i in range(levels)) + ' ' * levels + 'leaf\n'


def deep_block_sequences(levels: int) -> str:
    """``levels`` nested block sequences under a key: ``levels + 1`` collection levels."""
    return 'k:\n' + ''.join(' ' * (2 * i) + '-\n' for i in range(levels)) + ' ' * (2 * levels) + 'x\n'


PAYLOADS: dict[str, Callable[[], Any]] = {
    'billion_laughs': billion_laughs,
    'billion_laughs_bytes': lambda: billion_laughs().encode('utf-8'),
    'billion_laughs_block': billion_laughs_block,
    'quadratic_blowup': quadratic_blowup,
    'recursive_alias_sequence': lambda: 'a: &a [*a]\n',
    'recursive_alias_mapping': lambda: 'type: int\nx: &a\n  b: *a\n',
    'recursive_alias_merge': lambda: 'a: &a\n  k: 1\n  <<: *a\n',
    'alias_depth': alias_depth,
    'flow_150': lambda: 'a: ' + '[' * 150 + ']' * 150 + '\n',
    'flow_mapping_150': lambda: 'a: ' + '{b: ' * 150 + '1' + '}' * 150 + '\n',
    'json_150': lambda: '{"a": ' * 150 + '1' + '}' * 150,
    'flow_5m_open': lambda: '[' * 5_000_000,
    'flow_5m_braces': lambda: '{' * 5_000_000,  # starts with '{': strict JSON
    'flow_5m_braces_under_key': lambda: 'a: ' + '{' * 5_000_000,
    'json_5000': lambda: '{"a": ' * 5000 + '1' + '}' * 5000,
    'json_5000_lists': lambda: '{"a": ' + '[' * 5000 + ']' * 5000 + '}',
    'flow_5m_balanced': lambda: '[' * 5_000_000 + ']' * 5_000_000,
    'flow_5m_under_key': lambda: 'type: int\ndefault_value: ' + '[' * 5_000_000,
    'block_mappings_150': lambda: deep_block_mappings(150),
    'block_sequences_150': lambda: deep_block_sequences(150),
    'block_dashes_150': lambda: '- ' * 150 + 'x\n',
    'over_10mb_str': lambda: 'type: string\ndescription: "' + 'x' * MAX_BYTES + '"\n',
    'over_10mb_bytes': lambda: b'type: string\ndescription: "' + b'x' * MAX_BYTES + b'"\n',
    'over_10mb_comment': lambda: '#' * (MAX_BYTES + 1),
    'non_utf8': lambda: b'type: string\ndescription: caf\xe9\n',
    'utf16': lambda: '\ufefftype: string\n'.encode('utf-16-le'),
    'tabs': lambda: 'nodl_version: 2\nparameters:\n\tspeed:\n\t\ttype: double\n',
    'empty': lambda: '',
    'empty_bytes': lambda: b'',
    'only_comments': lambda: '# nothing\n# at all\n',
    'list': lambda: '- nodl_version: 2\n- type: int\n',
    'scalar': lambda: 'nodl_version\n',
    'nul_byte': lambda: b'type: int\ndescription: "\x00"\n',
    'lone_surrogate': lambda: 'type: string\ndescription: \ud83d\n',
    'bad_int_tag': lambda: 'type: int\ndefault_value: !!int lots\n',
    'python_tag': lambda: 'type: string\ndefault_value: !!python/object/apply:os.system ["true"]\n',
}

#: name -> (text the one error message contains, (line, column) or None)
EXPECTED: dict[str, tuple[str, tuple[int, int] | None]] = {
    'billion_laughs': ('"billion laughs"', None),
    'billion_laughs_bytes': ('"billion laughs"', None),
    'billion_laughs_block': ('"billion laughs"', None),
    'quadratic_blowup': ('"billion laughs"', None),
    'recursive_alias_sequence': ('recursive YAML alias', None),
    'recursive_alias_mapping': ('recursive YAML alias', None),
    'recursive_alias_merge': ('recursive YAML alias', None),
    'alias_depth': (f'{DEPTH} through YAML aliases', None),
    'flow_150': (DEPTH, (1, 103)),
    'flow_mapping_150': (DEPTH, None),
    'json_150': (DEPTH, None),
    'flow_5m_open': (DEPTH, (1, 101)),
    'flow_5m_braces': ('JSON syntax error: Expecting property name', (1, 2)),
    'flow_5m_braces_under_key': (DEPTH, (1, 103)),
    'json_5000': (DEPTH, (1, 601)),
    'json_5000_lists': (DEPTH, (1, 106)),
    'flow_5m_balanced': (DEPTH, (1, 101)),
    'flow_5m_under_key': (DEPTH, (2, 115)),
    'block_mappings_150': (DEPTH, (101, 101)),
    'block_sequences_150': (DEPTH, None),
    'block_dashes_150': (DEPTH, None),
    'over_10mb_str': ('larger than the limit of 10,485,760 bytes (10 MB)', (0, 0)),
    'over_10mb_bytes': ('larger than the limit of 10,485,760 bytes (10 MB)', (0, 0)),
    'over_10mb_comment': ('larger than the limit of 10,485,760 bytes (10 MB)', (0, 0)),
    'non_utf8': ('not valid UTF-8 (byte 0xe9', (2, 17)),
    'utf16': ('UTF-16', (1, 1)),
    'tabs': ('tab character used for indentation', (3, 1)),
    'empty': ('document is empty', (1, 1)),
    'empty_bytes': ('document is empty', (1, 1)),
    'only_comments': ('document is empty', (1, 1)),
    'list': ('document is a list, not a mapping', (1, 1)),
    'scalar': ('document is a string, not a mapping', (1, 1)),
    'nul_byte': ('character that is not allowed (#x0000)', (2, 15)),
    'lone_surrogate': ('lone surrogate', (2, 14)),
    'bad_int_tag': ("'lots' is not an integer", (2, 16)),
    'python_tag': ('unsupported YAML tag', (2, 16)),
}

#: A worker that imports the library once, then checks each payload in a forked
#: child: the child's exit status shows a crash (a signal such as SIGSEGV),
#: and its ru_maxrss growth is the payload's peak memory alone.
WORKER = textwrap.dedent('''
    import json, os, resource, signal, sys, time
    from nodl import ValidationError, check_source, load_nodl
    # Warm up: imports and schemas are not the payload's cost.
    check_source('nodl_version: 2\\n')
    load_nodl('type: int\\ndescription: warm-up\\n')

    def measure(source):
        before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        start = time.perf_counter()
        report = check_source(source)
        diagnostics = [dict(d.to_dict(), text=str(d)) for d in report.diagnostics]
        check_seconds = time.perf_counter() - start
        start = time.perf_counter()
        try:
            load_nodl(source)
            raised = None
        except ValidationError as exc:
            raised = {'type': 'ValidationError', 'errors': [str(d) for d in exc.errors],
                      'text': str(exc)}
        except BaseException as exc:
            raised = {'type': type(exc).__name__, 'errors': [], 'text': repr(exc)}
        load_seconds = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        return {'diagnostics': diagnostics, 'check_seconds': check_seconds,
                'load_seconds': load_seconds, 'raised': raised,
                'megabytes': (after - before) / 1024}

    for line in sys.stdin:
        path, kind = json.loads(line)
        with open(path, 'rb') as stream:
            data = stream.read()
        source = data.decode('utf-8', 'surrogatepass') if kind == 'str' else data
        read_end, write_end = os.pipe()
        pid = os.fork()
        if pid == 0:
            os.close(read_end)
            signal.alarm(60)  # a hang becomes SIGALRM, not a stuck test run
            try:
                result = measure(source)
            except BaseException as exc:
                result = {'crash': repr(exc)}
            with os.fdopen(write_end, 'w') as out:
                json.dump(result, out)
            os._exit(0)
        os.close(write_end)
        with os.fdopen(read_end) as pipe:
            output = pipe.read()
        _, status = os.waitpid(pid, 0)
        signalled = os.WTERMSIG(status) if os.WIFSIGNALED(status) else 0
        print(json.dumps({'signal': signalled, 'exit': os.waitstatus_to_exitcode(status),
                          'output': output}), flush=True)
''')


@pytest.fixture(scope='module')
def worker() -> Any:
    env = dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    process = subprocess.Popen([sys.executable, '-c', WORKER], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, cwd=REPO, env=env)
    yield process
    assert process.stdin is not None
    process.stdin.close()
    process.wait(timeout=30)


def run_isolated(worker: Any, name: str, tmp_path: Path) -> dict[str, Any]:
    payload = PAYLOADS[name]()
    path = tmp_path / 'payload'
    if isinstance(payload, str):
        path.write_bytes(payload.encode('utf-8', 'surrogatepass'))
    else:
        path.write_bytes(payload)
    kind = 'str' if isinstance(payload, str) else 'bytes'
    worker.stdin.write(json.dumps([str(path), kind]) + '\n')
    worker.stdin.flush()
    line = worker.stdout.readline()
    assert line, 'the worker process died'
    status = json.loads(line)
    assert status['signal'] == 0 and status['exit'] == 0, (
        f'{name}: the checker died (signal {status["signal"]}, exit {status["exit"]})')
    outcome = json.loads(status['output'])
    assert 'crash' not in outcome, f'{name}: check_source or load_nodl raised {outcome}'
    return outcome


def test_every_payload_has_an_expectation() -> None:
    assert set(PAYLOADS) == set(EXPECTED)


@pytest.mark.parametrize('name', sorted(PAYLOADS))
def test_hostile_input_is_one_clear_error_fast_and_small(
        worker: Any, name: str, tmp_path: Path) -> None:
    fragment, where = EXPECTED[name]
    outcome = run_isolated(worker, name, tmp_path)

    diagnostics = outcome['diagnostics']
    assert len(diagnostics) == 1, [d['text'] for d in diagnostics]
    (only,) = diagnostics
    assert only['severity'] == 'error'
    assert fragment in only['message'], only['text']
    assert '\n' not in only['text'] and len(only['text']) < 300
    if where is not None:
        assert (only['line'], only['column']) == where, only['text']

    raised = outcome['raised']
    assert raised is not None and raised['type'] == 'ValidationError', raised
    assert raised['errors'] == [only['text']]
    assert raised['text'] == only['text']

    assert outcome['check_seconds'] < MAX_SECONDS, outcome
    assert outcome['load_seconds'] < MAX_SECONDS, outcome
    assert outcome['megabytes'] < MAX_MEGABYTES, outcome


# --- the depth boundary (in-process) ------------------------------------------------

def depth_errors(source: str) -> list[str]:
    return [str(d) for d in check_source(source).diagnostics if 'deeper than' in d.message]


def test_the_depth_limit_is_100_collection_levels() -> None:
    assert MAX_DEPTH == 100


@pytest.mark.parametrize('build', [
    lambda n: '[' * n + ']' * n,                                  # a list of lists
    lambda n: 'a: ' + '[' * (n - 1) + ']' * (n - 1),              # under a key
    lambda n: '{"a": ' * n + '1' + '}' * n,                        # JSON objects
    lambda n: 'a: ' + '{b: ' * (n - 1) + '1' + '}' * (n - 1),     # YAML flow mappings
    lambda n: deep_block_mappings(n),                              # block mappings
    lambda n: deep_block_sequences(n - 1),                         # block sequences
    lambda n: '- ' * n + 'x\n',                                    # compact sequences
    lambda n: 'x: &x [[1]]\ny: ' + '[' * (n - 3) + '*x' + ']' * (n - 3) + '\n',  # via an alias
], ids=['flow-root', 'flow-key', 'json', 'flow-mapping', 'block-mapping', 'block-sequence',
        'compact-sequence', 'alias'])
def test_exactly_max_depth_is_accepted_and_one_more_is_rejected(
        build: Callable[[int], str]) -> None:
    assert depth_errors(build(MAX_DEPTH)) == []
    assert depth_errors(build(MAX_DEPTH - 1)) == []
    too_deep = build(MAX_DEPTH + 1)
    assert len(depth_errors(too_deep)) == 1
    assert len(check_source(too_deep).diagnostics) == 1


def test_a_document_at_the_depth_limit_still_loads_its_data() -> None:
    text = 'type: int\ndescription: d\nvalidation:\n  my_ns::check: ' + \
        '[' * (MAX_DEPTH - 2) + '1' + ']' * (MAX_DEPTH - 2) + '\n'
    model = load_nodl(text)
    value: Any = model.to_dict()['validation']['my_ns::check']
    levels = 2  # the document and its validation mapping
    while isinstance(value, list):
        value, levels = value[0], levels + 1
    assert (value, levels) == (1, MAX_DEPTH)


def test_depth_through_aliases_is_rejected_before_anything_else_sees_the_data() -> None:
    with pytest.raises(ValidationError) as info:
        load_nodl(alias_depth())
    assert len(info.value.diagnostics) == 1
    assert 'through YAML aliases' in str(info.value)


def test_many_small_aliases_below_the_limit_are_fine() -> None:
    text = ('type: int_array\ndescription: d\n'
            'default_value: [&v 1, ' + ', '.join(['*v'] * 499) + ']\n')
    model = load_nodl(text)
    assert model.to_dict()['default_value'] == [1] * 500


def test_many_problems_are_placed_in_linear_time() -> None:
    # Placing each duplicate key used to walk the whole tree again: 4,000 took 86 s.
    # (Each duplicate sits in a mapping of its own, so each needed a search of its own.)
    text = 'nodl_version: 2\nparameters:\n' + ''.join(
        f'  p{i}:\n    type: int\n    type: int\n' for i in range(4000))
    start = time.perf_counter()
    report = check_source(text)
    duplicates = [d for d in report.diagnostics if 'duplicate key' in d.message]
    assert time.perf_counter() - start < 2.0
    assert len(duplicates) == 4000
    assert (duplicates[-1].line, duplicates[-1].path) == (3 + 3 * 3999 + 2, ('parameters', 'p3999'))
