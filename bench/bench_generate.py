"""Generating code for 100 definitions against loading those 100 definitions.

Target (issue 11, section 7): generating both languages (python and cpp, each
generator installed under ``nodl.generators``) for 100 node definitions takes
at most 3x the time of loading them (parse, every check, composition into the
resolved node: ``resolve_node`` on the text).  Corpus: corpus.py (25 parameters
with validators, 20 topics, services and actions each).  Best of several
rounds, interleaved, so that machine noise affects both alike.
"""

from __future__ import annotations

import time

from corpus import corpus
from nodl.generate import GenerateOptions, load_generators
from nodl.system import resolve_node

TARGET = 3.0
LANGUAGES = ('python', 'cpp')


def run(count: int = 100, rounds: int = 5) -> dict[str, float]:
    """Seconds to load ``count`` definitions, seconds to generate them, and the ratio."""
    texts = corpus(count)
    generators = load_generators()
    languages = [language for language in LANGUAGES if language in generators]
    options = [GenerateOptions(f'Driver{i}', f'driver_{i}') for i in range(count)]

    def load() -> list[dict[str, object]]:
        return [{lang: resolve_node(text, client_library=generators[lang].CLIENT_LIBRARY or None)
                 for lang in languages[:1]} for text in texts]

    nodes = [{lang: resolve_node(text, client_library=generators[lang].CLIENT_LIBRARY or None)
              for lang in languages} for text in texts]
    load_best = gen_best = float('inf')
    for _ in range(rounds):
        start = time.perf_counter()
        load()
        load_best = min(load_best, time.perf_counter() - start)
        start = time.perf_counter()
        for resolved, option in zip(nodes, options, strict=True):
            for lang in languages:
                generators[lang].generate(resolved[lang], option)  # type: ignore[arg-type]
        gen_best = min(gen_best, time.perf_counter() - start)
    return {'docs': count, 'languages': len(languages), 'load_s': load_best, 'generate_s': gen_best,
            'ratio': gen_best / load_best}


def main() -> bool:
    r = run()
    languages = [lang for lang in LANGUAGES if lang in load_generators()]
    print(f'generate ({" + ".join(languages)}) vs load, {r["docs"]} definitions')
    print(f'  load (resolve_node):  {r["load_s"] * 1000:8.1f} ms')
    print(f'  generate:             {r["generate_s"] * 1000:8.1f} ms')
    ok = r['ratio'] <= TARGET and r['languages'] == len(LANGUAGES)
    print(f'  ratio:                {r["ratio"]:.2f}x  (target <= {TARGET}x, both languages)  '
          f'{"OK" if ok else "ABOVE TARGET OR A LANGUAGE MISSING"}')
    return ok


if __name__ == '__main__':
    raise SystemExit(0 if main() else 1)
