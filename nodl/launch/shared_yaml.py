"""PyYAML as a Python launch file's code sees it: the same text read once, the same data written once.

A launch's helpers read and write the same YAML again and again.  nav2's ``RewrittenYaml``
(nav2_common) is one substitution per launch file, each performed where its node is
evaluated: every one loads the same parameter file with ``yaml.safe_load`` and most write the
same rewritten data with ``yaml.dump``, PyYAML's pure-Python loader and emitter each time
(about 40 ms a time for nav2's 18 KB ``nav2_params.yaml``, most of reading nav2's bringup).

While a Python launch file runs, the module ``yaml`` it (or a helper it imports) gets is
:meth:`SharedYaml.module`: PyYAML itself, whose ``safe_load`` and ``dump`` do the work once
for a walk of the launch and give the same result again:

* ``safe_load(stream)`` of a text (or bytes) read before in this walk returns a new copy of
  what that text gave (a pickle round trip: the same types, values, order and shared parts;
  the caller may change it).  The text is read from the stream whole, and PyYAML reads it
  with the stream's name, so an error is the one PyYAML raises for that stream;
* ``dump(data, stream=None, Dumper=yaml.Dumper, **options)`` of data made only of YAML's
  plain values (dicts, lists, strings, numbers, booleans, None), equal to data dumped before
  with the same options, type for type and in the same order (their pickles are equal), writes
  the text written then.

Everything else, and anything the memo cannot tell apart exactly (other types, a custom
Dumper, an ``encoding``), is PyYAML's own call.  So what a launch computes is unchanged:
only the same computation is not made twice.  Each substitution is still performed for every
node that asks, in the node's own context; this only spares PyYAML's work on equal input.
"""

from __future__ import annotations

import contextlib
import io
import pickle
import types
from typing import Any

import yaml

__all__ = ['SharedYaml']

#: The types of data ``yaml.dump`` writes the same way whatever else holds them.
_PLAIN = (str, int, float, bool, type(None))


def _plain(data: object, depth: int = 0) -> bool:
    """True if ``data`` holds only dicts, lists and plain scalars (not too deep to check)."""
    if isinstance(data, _PLAIN):
        return type(data) in _PLAIN  # (not a subclass: its representation may be its own)
    if depth > 100:
        return False
    if type(data) is dict:
        return all(_plain(k, depth + 1) and _plain(v, depth + 1) for k, v in data.items())
    if type(data) is list:
        return all(_plain(v, depth + 1) for v in data)
    return False


class SharedYaml:
    """The memo of one launch walk: texts read with ``safe_load``, data written with ``dump``."""

    def __init__(self) -> None:
        self._loaded: dict[str | bytes, bytes] = {}
        self._dumped: dict[bytes, str] = {}
        #: How many calls were answered from the memo (``safe_load``, ``dump``), for the tests.
        self.reused = [0, 0]
        self._module: types.ModuleType | None = None

    def module(self) -> types.ModuleType:
        """PyYAML with this walk's ``safe_load`` and ``dump`` (one module for the walk)."""
        if self._module is None:
            module = types.ModuleType('yaml', yaml.__doc__)
            module.__dict__.update({k: v for k, v in vars(yaml).items() if k not in ('safe_load', 'dump')})
            module.safe_load = self.safe_load  # type: ignore[attr-defined]
            module.dump = self.dump  # type: ignore[attr-defined]
            self._module = module
        return self._module

    def safe_load(self, stream: Any) -> Any:
        """``yaml.safe_load(stream)``, parsed once per text in this walk."""
        if hasattr(stream, 'read'):
            text = stream.read()
            if not isinstance(text, (str, bytes)):
                return yaml.safe_load(text)  # (PyYAML says what is wrong with it)
            source: Any = io.StringIO(text) if isinstance(text, str) else io.BytesIO(text)
            source.name = getattr(stream, 'name', '<file>')  # (where PyYAML's errors say it is)
        elif isinstance(stream, (str, bytes)):
            text = source = stream
        else:
            return yaml.safe_load(stream)
        kept = self._loaded.get(text)
        if kept is not None:
            self.reused[0] += 1
            return pickle.loads(kept)  # noqa: S301 - pickled here, from what safe_load made
        data = yaml.safe_load(source)
        with contextlib.suppress(Exception):  # (what cannot be pickled is not kept)
            self._loaded[text] = pickle.dumps(data, pickle.HIGHEST_PROTOCOL)
        return data

    def dump(self, data: Any, stream: Any = None, Dumper: Any = yaml.Dumper, **options: Any) -> Any:  # noqa: N803 - PyYAML's name
        """``yaml.dump(data, stream, Dumper, **options)``, emitted once per equal plain data."""
        if Dumper is not yaml.Dumper or options.get('encoding') is not None or not _plain(data):
            return yaml.dump(data, stream, Dumper=Dumper, **options)
        key = pickle.dumps((data, sorted(options.items())), pickle.HIGHEST_PROTOCOL)
        text = self._dumped.get(key)
        if text is None:
            text = yaml.dump(data, None, Dumper=Dumper, **options)
            self._dumped[key] = text
        else:
            self.reused[1] += 1
        if stream is None:
            return text
        stream.write(text)
        return None
