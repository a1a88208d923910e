"""The legacy-xml frontend's reading: what an XML file is when a NoDL v2 document was expected.

YAML reads the text of an XML file as one long string, so without this
``nodl validate pkg.nodl.xml`` would say "document is a string, not a
mapping".  :func:`xml_diagnostics` recognises XML by its first character
and says what the file is instead: a legacy NoDL interface file (with the
legacy reader's own findings, so a user converting it sees them at once), a
package manifest, or some other XML document, and how to convert it.
"""

from __future__ import annotations

import re

from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.legacy_xml import legacy_document_from_tree
from nodl.frontends.xml_reader import load_xml

__all__ = ['NOT_V2_CODE', 'looks_like_xml', 'xml_diagnostics']

#: A legacy XML file (or other XML) read where a NoDL v2 document is expected.
NOT_V2_CODE = 'NODL817'

# An XML declaration, a comment, or an element; never YAML's '<<' merge key.
_XML_START = re.compile(r'\s*<(?:\?xml|!--|[A-Za-z_])')


def looks_like_xml(text: str) -> bool:
    """True if ``text`` (after a byte order mark and blanks) starts as an XML document does."""
    return _XML_START.match(text.lstrip('\ufeff')) is not None


def xml_diagnostics(text: str, file: str) -> list[Diagnostic] | None:
    """What an XML document given as NoDL v2 is, as placed diagnostics (None: not XML)."""
    if not looks_like_xml(text):
        return None
    tree = load_xml(text, file)
    root = tree.root
    line, column = (root.line, root.column) if root is not None else (1, 1)
    if root is None or (tree.diagnostics and root.tag not in ('interface', 'package')):
        return [Diagnostic(Severity.ERROR, 'this is XML, not a NoDL v2 document (YAML or JSON)',
                           (), file, line, column, code=NOT_V2_CODE)] + tree.diagnostics
    if root.tag == 'interface':
        legacy = legacy_document_from_tree(tree)
        return [Diagnostic(
            Severity.ERROR, 'this is a legacy NoDL XML file (specs 000-002), not a NoDL v2 document; '
            '`nodl convert FILE -o DIR` converts it (nodl show and nodl check read registered legacy '
            'files as they are)', (), file, line, column, code=NOT_V2_CODE)] + legacy.diagnostics
    if root.tag == 'package':
        return [Diagnostic(
            Severity.ERROR, 'this is a package manifest (package.xml), not a NoDL v2 document; '
            '`nodl convert package.xml -o DIR` converts the legacy NoDL files it exports',
            (), file, line, column, code=NOT_V2_CODE)] + tree.diagnostics
    return [Diagnostic(Severity.ERROR, f'this is an XML document (root <{root.tag}>), not a NoDL v2 '
                       'document (YAML or JSON)', (), file, line, column, code=NOT_V2_CODE)]
