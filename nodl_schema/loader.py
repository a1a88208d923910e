"""Reading, including and writing documents, as the reference API does.

:func:`parse_nodl` reads and validates document text; :func:`load_nodl` reads
a file and (by default) resolves its ``include`` references through the
registered resolvers and merges what they name into one document;
:func:`dump_nodl` writes a document as YAML or JSON.  Validation is the
toolkit's: an invalid document raises :class:`nodl_schema.ValidationError`,
with diagnostics at ``file:line:col``.
"""

from __future__ import annotations

import collections
import dataclasses
import json
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import IO, Any

from nodl_schema.composition import ResolutionError, merge_documents, resolve
from nodl_schema.models import NodlDocument
from nodl_schema.validation import check_text

__all__ = ['IncludedDocument', 'DocumentTree', 'resolve_document', 'parse_nodl', 'load_nodl',
           'load_nodl_with_doc_tree', 'dump_nodl']


@dataclasses.dataclass
class IncludedDocument:
    """A document reached through a reference, with the documents it includes in turn."""

    ref: str
    doc: NodlDocument
    resolved_includes: list[IncludedDocument]


@dataclasses.dataclass
class DocumentTree:
    """A document and everything it includes, as a tree (the root has no reference)."""

    root_doc: NodlDocument
    resolved_includes: list[IncludedDocument]

    def flatten(self) -> list[NodlDocument]:
        """Every document of the tree, breadth first, the root first."""
        found = [self.root_doc]
        pending = collections.deque(self.resolved_includes)
        while pending:
            included = pending.popleft()
            found.append(included.doc)
            pending.extend(included.resolved_includes)
        return found


def resolve_document(doc: NodlDocument, origin: Path | None = None) -> DocumentTree:
    """Resolve ``doc``'s includes (``origin``: its file, for ``local://`` references), recursively.

    Each document may be reached once: a cycle, or two paths to one document, is
    a :class:`ResolutionError` naming both chains of references.  Included
    documents are read and validated like :func:`load_nodl` ``(resolve=False)``.
    """
    reached: dict[Path, list[str]] = {}
    if origin is not None:
        reached[origin.resolve()] = []

    def follow(ref: str, chain: list[str], including: Path | None) -> IncludedDocument:
        chain = chain + [ref]
        path = resolve(ref, including)
        key = path.resolve()
        if key in reached:
            earlier = ' > '.join(reached[key]) or 'the root document'
            raise ResolutionError(f'Double-inclusion detected: {" > ".join(chain)!r} reaches '
                                  f'{path}, as {earlier!r} did already (a document may be '
                                  'included once)', [str(path)])
        reached[key] = chain
        included = load_nodl(path, resolve=False)
        children = [follow(r.ref, chain, path) for r in included.include or ()]
        return IncludedDocument(ref=ref, doc=included, resolved_includes=children)

    return DocumentTree(root_doc=doc,
                        resolved_includes=[follow(r.ref, [], origin) for r in doc.include or ()])


def parse_nodl(data: str | bytes | IO[str] | IO[bytes]) -> NodlDocument:
    """Read YAML or JSON text (a str, bytes or a file object) as a validated document.

    Raises :class:`nodl_schema.ValidationError` (a :class:`ValueError`) for text
    that is not YAML, not a mapping, or not a valid document.
    """
    return _model(check_text(data))


def _model(data: Any) -> NodlDocument:
    document: NodlDocument = NodlDocument.parse_obj(data)
    return document


def load_nodl(source: Path, *, resolve: bool = True) -> NodlDocument:
    """Read and validate the document in file ``source``.

    With ``resolve`` (the default) its ``include`` references are resolved and
    the documents they name merged in: the result has no ``include``.  Raises
    :class:`nodl_schema.ValidationError` for an invalid document,
    :class:`ResolutionError` for a reference that does not resolve (or what a
    resolver raises), :class:`nodl_schema.composition.MergeError` for a name
    declared twice, and :class:`OSError` for a file that cannot be read.
    """
    if resolve:
        merged, _ = load_nodl_with_doc_tree(source)
        return merged
    return _model(check_text(Path(source)))


def load_nodl_with_doc_tree(source: Path) -> tuple[NodlDocument, DocumentTree]:
    """:func:`load_nodl` of ``source``, and the tree of documents it was merged from."""
    source = Path(source)
    doc = _model(check_text(source))
    tree = resolve_document(doc, source.absolute())
    return merge_documents(tree.flatten()), tree


def dump_nodl(doc: NodlDocument | dict[str, Any], *, format: str = 'yaml') -> str:
    """A document (model or plain dict) as ``yaml`` or ``json`` text.

    Fields that are None are left out; validators are written by their key
    (``bounds<>``).  Keys keep their order.
    """
    if format not in ('yaml', 'json'):
        raise ValueError(f'Unsupported format {format!r} for nodl serialization: yaml or json')
    data: Any = (json.loads(doc.json(exclude_none=True, by_alias=True))
                 if isinstance(doc, NodlDocument) else doc)
    if format == 'json':
        return json.dumps(data, indent=2)
    from nodl.text_safety import dump_yaml

    return dump_yaml(data)

