"""The studio's third-party browser files: Cytoscape.js and cytoscape-edgehandles.

They come from the npm registry (``nodl/studio/web/package.json`` and its lock, exact
versions) and are copied into ``nodl/studio/static/vendor/`` (not committed) by
``make install``, which runs ``npm ci --prefix nodl/studio/web`` and then :func:`copy_vendor`
(through :func:`nodl.cli.verbs.studio.copy_vendor_main`).  The installed package ships the
copies.

edgehandles' browser build expects lodash's ``memoize`` and ``throttle`` as ``window._``;
their npm packages are CommonJS modules, so each is copied wrapped in a function that
hands its ``module.exports`` to ``window._`` (the file's text is otherwise unchanged).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import NamedTuple

__all__ = [
    'INSTALL_HINT',
    'VENDOR_FILES',
    'VendorFile',
    'copy_vendor',
    'missing_vendor_files',
    'vendor_folder',
]

#: What to run when the files are missing (from a clone of the sources).
INSTALL_HINT = ('run `make install` in the nodl sources (it runs `npm ci --prefix nodl/studio/web` '
                'and copies the files), then reinstall nodl')


class VendorFile(NamedTuple):
    """One file served under ``/static/vendor/``."""

    #: Its name in the vendor folder.
    name: str
    #: Where npm puts it, relative to ``web/node_modules``.
    source: str
    #: The ``window._`` member a CommonJS module is exposed as (None: copied as it is).
    lodash: str | None = None


#: In the order the page loads them.
VENDOR_FILES = (
    VendorFile('cytoscape.min.js', 'cytoscape/dist/cytoscape.min.js'),
    VendorFile('lodash.memoize.js', 'lodash.memoize/index.js', 'memoize'),
    VendorFile('lodash.throttle.js', 'lodash.throttle/index.js', 'throttle'),
    VendorFile('cytoscape-edgehandles.js', 'cytoscape-edgehandles/cytoscape-edgehandles.js'),
)

_HERE = Path(__file__).resolve().parent


def vendor_folder() -> Path:
    """The folder the vendor files are served from."""
    return _HERE / 'static' / 'vendor'


def missing_vendor_files(folder: Path | None = None) -> list[str]:
    """The names of the vendor files that are not in ``folder`` (default: the package's)."""
    where = folder or vendor_folder()
    return [f.name for f in VENDOR_FILES if not (where / f.name).is_file()]


def _wrapped(text: str, member: str) -> str:
    return ('(function () {\n  var module = {exports: {}}, exports = module.exports;\n'
            f'{text}\n  window._ = window._ || {{}};\n  window._.{member} = module.exports;\n'
            '})();\n')


def copy_vendor(node_modules: Path, folder: Path | None = None) -> list[Path]:
    """Copy the vendor files from ``node_modules`` (after ``npm ci``) into ``folder``; each
    written atomically.  OSError (with the missing file's name) when npm did not install one."""
    from nodl.writing import write_file

    target = folder or vendor_folder()
    target.mkdir(parents=True, exist_ok=True)
    written = []
    for item in VENDOR_FILES:
        text = (node_modules / item.source).read_text(encoding='utf-8')
        if item.lodash:
            text = _wrapped(text, item.lodash)
        path = target / item.name
        write_file(os.fspath(path), text)
        written.append(path)
    for name in ('cytoscape', 'cytoscape-edgehandles', 'lodash.memoize', 'lodash.throttle'):
        licence = node_modules / name / 'LICENSE'
        if licence.is_file():
            write_file(os.fspath(target / f'LICENSE.{name}'), licence.read_text(encoding='utf-8'))
    return written
