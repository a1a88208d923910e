"""load_nodl throughput against bare yaml.CSafeLoader parsing of the same texts.

Target (issue 7, section 8): load_nodl (parse, every check, the typed model)
reaches at least 1.0x the throughput of ``yaml.load(text, Loader=CSafeLoader)``
on each of two corpora of realistic node definitions (see corpus.py): the
hand-written style (comments, flow-style QoS and validator lists) and the
block style ``yaml.safe_dump`` writes (every list and mapping one item a line).
The two are measured interleaved, several rounds, best round each, so that
machine noise affects both alike.
"""

from __future__ import annotations

import time

import yaml

from corpus import block_corpus, corpus
from nodl import load_nodl

TARGET = 1.0
CORPORA = {'hand-written style': corpus, 'block style (yaml.safe_dump)': block_corpus}


def _round(fn, texts) -> float:
    start = time.perf_counter()
    for text in texts:
        fn(text)
    return time.perf_counter() - start


def run(texts: list[str], rounds: int = 7) -> dict[str, float]:
    """Throughput of load_nodl and of CSafeLoader on ``texts``, and their ratio."""
    loader = yaml.CSafeLoader
    for text in texts:  # warm-up and a correctness guard
        load_nodl(text)
    yaml_best = nodl_best = float('inf')
    for _ in range(rounds):
        yaml_best = min(yaml_best, _round(lambda t: yaml.load(t, Loader=loader), texts))
        nodl_best = min(nodl_best, _round(load_nodl, texts))
    size = sum(len(t.encode()) for t in texts) / len(texts)
    yaml_rate = len(texts) / yaml_best
    nodl_rate = len(texts) / nodl_best
    return {'docs': len(texts), 'avg_bytes': size, 'yaml_docs_per_s': yaml_rate,
            'nodl_docs_per_s': nodl_rate, 'ratio': nodl_rate / yaml_rate}


def main() -> bool:
    ok = True
    for name, make in CORPORA.items():
        r = run(make())
        print(f'load_nodl vs CSafeLoader, {name} ({r["docs"]} docs, {r["avg_bytes"]:.0f} bytes avg)')
        print(f'  CSafeLoader: {r["yaml_docs_per_s"]:8.1f} docs/s')
        print(f'  load_nodl:   {r["nodl_docs_per_s"]:8.1f} docs/s')
        print(f'  ratio:       {r["ratio"]:.2f}x  (target >= {TARGET}x)  '
              f'{"OK" if r["ratio"] >= TARGET else "BELOW TARGET"}')
        ok = ok and r['ratio'] >= TARGET
    return ok


if __name__ == '__main__':
    raise SystemExit(0 if main() else 1)
