"""Rewriting the ``include`` references of a document's text (what installing a package does).

Given ``{FROM: TO}`` rules, :func:`rewrite_references` returns the document's
text with each matching reference replaced.  References are compared in the
form their resolver gives (:meth:`~nodl_schema.Resolver.normalize`): a
``local://`` reference as the absolute path of its file, any other as written.
The text is round-tripped with ruamel.yaml, so comments and key order are
kept; JSON input comes out as block-style YAML.
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any

from nodl_schema.composition import ResolutionError, resolver_for
from nodl_schema.local_resolver import LocalResolver
from nodl_schema.validation import check_text

__all__ = ['rewrite_references']


def _canonical(ref: str, origin: Path) -> str:
    resolver = resolver_for(ref)
    if resolver is None:
        raise ResolutionError(f'No registered resolver handles reference {ref!r}')
    return resolver.normalize(ref, origin)


def _block_style(node: Any) -> None:
    from ruamel.yaml.comments import CommentedBase

    stack = [node]
    while stack:
        item = stack.pop()
        if isinstance(item, CommentedBase):
            item.fa.set_block_style()
        if isinstance(item, dict):
            stack.extend(item.values())
        elif isinstance(item, list):
            stack.extend(item)


def rewrite_references(source: Path, rewrites: dict[str, str]) -> str:
    """The text of document ``source`` with its ``include`` references rewritten by ``rewrites``.

    A ``local://`` key of ``rewrites`` is matched by the file it names (give it
    as an absolute path).  Raises :class:`nodl_schema.ValidationError` when
    ``source`` is not a valid document, and :class:`ResolutionError` when a
    ``local://`` reference is left (it would not resolve once installed).
    Needs ruamel.yaml (``pip install 'nodl-toolkit[reference]'``).
    """
    try:
        from ruamel.yaml import YAML
    except ImportError:
        raise ImportError("nodl_schema.rewrite_references needs ruamel.yaml: pip install "
                          "'nodl-toolkit[reference]'") from None
    source = Path(source).resolve()
    text = source.read_text(encoding='utf-8')
    check_text(text, str(source))
    yaml = YAML()
    yaml.width = 4096  # no wrapping of long values
    yaml.indent(mapping=2, sequence=4, offset=2)
    data = yaml.load(text)
    rules = {_canonical(old, source): new for old, new in rewrites.items()}
    local = LocalResolver()
    for entry in data.get('include') or ():
        written = entry['ref']
        replacement = rules.get(_canonical(written, source))
        if replacement is not None:
            entry['ref'] = replacement
        elif local.handles(written):
            raise ResolutionError(f'{source}: local reference {written!r} was not registered to '
                                  'rewrite (it would not resolve once installed): give a rule for it')
    _block_style(data)
    out = io.StringIO()
    yaml.dump(data, out)
    return out.getvalue()
