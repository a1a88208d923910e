"""nodl.studio.vendor: the studio's browser libraries copied from npm's node_modules (lodash's
CommonJS modules exposed as window._), and what is missing said by name."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

from nodl.studio.vendor import (
    VENDOR_FILES,
    copy_vendor,
    missing_vendor_files,
    vendor_folder,
)

WEB = Path(vendor_folder()).parent.parent / 'web'


def fake_node_modules(root: Path) -> Path:
    modules = root / 'node_modules'
    for item in VENDOR_FILES:
        path = modules / item.source
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text('module.exports = function ' + item.name.split('.')[0].replace('-', '_')
                        + '() { return 42; };\n' if item.lodash else f'/* {item.name} */\n')
        (modules / item.source.split('/')[0] / 'LICENSE').write_text('MIT\n')
    return modules


def test_the_files_are_copied_and_lodash_exposed(tmp_path: Path) -> None:
    target = tmp_path / 'vendor'
    written = copy_vendor(fake_node_modules(tmp_path), target)
    assert [p.name for p in written] == [f.name for f in VENDOR_FILES]
    assert missing_vendor_files(target) == []
    assert (target / 'LICENSE.cytoscape').read_text() == 'MIT\n'
    memoize = (target / 'lodash.memoize.js').read_text()
    assert 'var module = {exports: {}}' in memoize and 'window._.memoize = module.exports;' in memoize
    # what the browser runs: the wrapped module gives window._.memoize
    result = subprocess.run(['node', '-e', 'var window = {};\n' + memoize
                             + '\nconsole.log(window._.memoize());'],
                            capture_output=True, text=True, timeout=30, check=True)
    assert result.stdout.strip() == '42'
    assert (target / 'cytoscape.min.js').read_text() == '/* cytoscape.min.js */\n'


def test_missing_files_are_named(tmp_path: Path) -> None:
    assert missing_vendor_files(tmp_path) == [f.name for f in VENDOR_FILES]


def test_the_pinned_versions_are_exact_and_locked() -> None:
    package = json.loads((WEB / 'package.json').read_text())
    lock = json.loads((WEB / 'package-lock.json').read_text())
    assert package['dependencies'] == {'cytoscape': '3.34.4', 'cytoscape-edgehandles': '4.0.1'}
    locked = {name.removeprefix('node_modules/'): entry['version']
              for name, entry in lock['packages'].items() if name}
    assert locked == {'cytoscape': '3.34.4', 'cytoscape-edgehandles': '4.0.1',
                      'lodash.memoize': '4.1.2', 'lodash.throttle': '4.1.1'}
    assert all(entry.get('license') == 'MIT' for name, entry in lock['packages'].items() if name)
    assert all(entry.get('integrity', '').startswith('sha512-')
               for name, entry in lock['packages'].items() if name)
