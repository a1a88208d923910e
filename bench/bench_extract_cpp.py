"""C++ extraction (nodl extract's rclcpp reader) against bare tree-sitter-cpp parsing.

Target (issue 17, section 3): extracting a 100-file package takes at most 2.0x the time of
parsing the same files with the parser it uses (tree-sitter-cpp), measured interleaved in one
run, best of several rounds each.  The package: the real nodes of tests/fixtures/extract/cpp,
copied until there are 100 files (each copy in its own namespace folder).

Also prints precision and recall per entity kind over those fixtures against their
hand-checked expected.yaml: an extracted entity is correct when its section, name and type are
the expected ones; a gap (left open, never guessed) counts as not found, not as wrong.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from nodl.extract.cpp import CPP_SUFFIXES, cpp_parser, extract_cpp  # noqa: E402

TARGET = 2.0
FIXTURES = ROOT / 'tests' / 'fixtures' / 'extract' / 'cpp'
KINDS = ['publishers', 'subscriptions', 'service_servers', 'service_clients', 'action_servers',
         'action_clients', 'parameters']


def _package(root: Path, count: int = 100) -> list[str]:
    sources = sorted(p for p in FIXTURES.rglob('*') if p.suffix in CPP_SUFFIXES)
    files: list[str] = []
    copy = 0
    while len(files) < count:
        for source in sources:
            if len(files) == count:
                break
            target = root / f'copy{copy}' / source.parent.name / source.name
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(source, target)
            files.append(str(target))
        copy += 1
    return files


def _parse_only(files: list[str]) -> None:
    parser = cpp_parser()
    for path in files:
        with open(path, 'rb') as handle:
            parser.parse(handle.read())


def accuracy() -> dict[str, tuple[int, int, int]]:
    """Per kind: (correct extracted, extracted complete, expected)."""
    out = {kind: [0, 0, 0] for kind in KINDS}
    for case in sorted(p for p in FIXTURES.iterdir() if (p / 'expected.yaml').exists()):
        expected = yaml.safe_load((case / 'expected.yaml').read_text())['nodes']
        truth = {(e['section'], e['name'], e.get('truth', {}).get('type', e['type']))
                 for n in expected for e in n['entities']}
        for kind in KINDS:
            out[kind][2] += sum(1 for t in truth if t[0] == kind)
        for node in extract_cpp([str(case)]).nodes:
            for entity in node.entities:
                if not entity.complete:
                    continue
                out[entity.section][1] += 1
                out[entity.section][0] += (entity.section, entity.name, entity.type) in truth
    return {k: (v[0], v[1], v[2]) for k, v in out.items()}


def run(rounds: int = 5) -> dict[str, float]:
    with tempfile.TemporaryDirectory() as folder:
        files = _package(Path(folder))
        _parse_only(files)
        extract_cpp(files)  # warm-up
        parse_best = extract_best = float('inf')
        for _ in range(rounds):
            start = time.perf_counter()
            _parse_only(files)
            parse_best = min(parse_best, time.perf_counter() - start)
            start = time.perf_counter()
            extract_cpp(files)
            extract_best = min(extract_best, time.perf_counter() - start)
    return {'files': len(files), 'parse_s': parse_best, 'extract_s': extract_best,
            'ratio': extract_best / parse_best}


def main() -> bool:
    r = run()
    ok = r['ratio'] <= TARGET
    print(f'C++ extraction vs tree-sitter-cpp parsing ({r["files"]} files)')
    print(f'  parse only: {r["parse_s"] * 1000:8.1f} ms')
    print(f'  extraction: {r["extract_s"] * 1000:8.1f} ms')
    print(f'  ratio:      {r["ratio"]:.2f}x  (target <= {TARGET}x)  {"OK" if ok else "ABOVE TARGET"}')
    print('C++ extraction accuracy over the real fixtures (complete entities; gaps count as not found)')
    for kind, (correct, extracted, expected) in accuracy().items():
        precision = f'{correct / extracted:.2f}' if extracted else '  - '
        recall = f'{correct / expected:.2f}' if expected else '  - '
        print(f'  {kind:16} precision {precision} ({correct}/{extracted})  recall {recall} ({correct}/{expected})')
    return ok


if __name__ == '__main__':
    raise SystemExit(0 if main() else 1)
