"""A private ament prefix whose interface packages define some types otherwise than the
environment's: put in front of AMENT_PREFIX_PATH, it makes the index read another version
of a type than the one a running node was built with (version skew, issue 18)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

VENV = Path(sys.prefix)
INDEX = Path('share') / 'ament_index' / 'resource_index' / 'rosidl_interfaces'

#: Changed definitions (ROS 2 interface files) of types the test nodes use.
STRING_WITH_REVISION = 'string data\nint32 revision\n'
TRIGGER_WITH_ATTEMPT = 'int32 attempt\n---\nbool success\nstring message\n'
FIBONACCI_WITH_PROGRESS = ('int32 order\nbool fast\n---\nint32[] sequence\n---\n'
                           'int32[] sequence\nfloat64 progress\n')


def skewed_prefix(root: Path, changed: dict[str, str]) -> Path:
    """A prefix under ``root`` holding every package of ``changed`` (full type name ->
    the new file's text) as the environment installs it, but with those types defined by a
    ``.msg``/``.srv``/``.action`` file of the given text (and no ``.idl``)."""
    prefix = root / 'prefix'
    (prefix / INDEX).mkdir(parents=True, exist_ok=True)
    by_package: dict[str, dict[str, str]] = {}
    for name, text in changed.items():
        by_package.setdefault(name.split('/')[0], {})[name] = text
    for package, types in by_package.items():
        listing = (VENV / INDEX / package).read_text(encoding='utf-8').splitlines()
        dropped = set()
        for name, text in types.items():
            _, namespace, base = name.split('/')
            folder = prefix / 'share' / package / namespace
            if not folder.exists():
                shutil.copytree(VENV / 'share' / package / namespace, folder)
            (folder / f'{base}.idl').unlink()
            (folder / f'{base}.{namespace}').write_text(text, encoding='utf-8')
            dropped.add(f'{namespace}/{base}.idl')
            if f'{namespace}/{base}.{namespace}' not in listing:
                listing.append(f'{namespace}/{base}.{namespace}')
        (prefix / INDEX / package).write_text(
            '\n'.join(line for line in listing if line not in dropped) + '\n', encoding='utf-8')
    return prefix
