"""A converted legacy node checked as v2, placed in its XML file (nodl.legacy.converted_document)."""

from __future__ import annotations

from conftest import FIXTURES
from nodl.diagnostics import Diagnostic, Severity
from nodl.frontends.legacy_xml import parse_legacy_xml
from nodl.legacy import Converted, convert_legacy
from nodl.legacy.converted_document import ConvertedDocument, converted_report
from nodl.loading import check_source, dump_nodl
from nodl.validation.kinds import Kind

LEGACY_PKG = FIXTURES / 'index' / 'legacy' / 'share' / 'legacy_pkg' / 'legacy_pkg.nodl.xml'


def converted(executable: str) -> Converted:
    return next(c for c in convert_legacy(parse_legacy_xml(LEGACY_PKG, str(LEGACY_PKG)))
                if c.node.executable == executable)


def test_the_report_is_the_v2_check_placed_in_the_legacy_file() -> None:
    talker = converted('talker')
    report = converted_report(talker)
    v2 = check_source(dump_nodl(talker.data, 'json', validate=False), kind=Kind.NODE)
    assert report.file == str(LEGACY_PKG)
    assert report.kind is Kind.NODE and report.data == v2.data
    # the same findings (the legacy format has no descriptions: NODL216), placed in the XML file
    assert [(d.severity, d.message, d.path, d.code) for d in report.diagnostics] == \
        [(d.severity, d.message, d.path, d.code) for d in v2.diagnostics]
    assert report.diagnostics and {d.file for d in report.diagnostics} == {str(LEGACY_PKG)}
    assert [(d.line, d.column) for d in report.diagnostics] == \
        [talker.position(d.path) for d in report.diagnostics]
    assert report.model() == v2.model()


def test_the_document_places_paths_at_the_xml_elements() -> None:
    talker = converted('talker')
    document = ConvertedDocument(talker)
    assert document.source.file == str(LEGACY_PKG) and document.data is talker.data
    for anchor in ('key', 'value'):
        assert document.position(('main', 'parameters', 'rate'), anchor) == \
            talker.position(('main', 'parameters', 'rate'))
    placed = document.place(Diagnostic(Severity.ERROR, 'x', ('main', 'publishers', 0, 'qos')))
    assert (placed.file, placed.line, placed.column) == (
        str(LEGACY_PKG), *talker.position(('main', 'publishers', 0, 'qos')))
    assert placed.path == ('main', 'publishers', 0, 'qos')  # the v2 path is kept


def test_a_placed_diagnostic_is_left_alone() -> None:
    document = ConvertedDocument(converted('talker'))
    already = Diagnostic(Severity.ERROR, 'x', ('main',), 'elsewhere.yaml', 3, 4)
    assert document.place(already) is already
