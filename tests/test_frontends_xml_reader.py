"""The safe XML reader: positions of elements and attributes, attribute placement, hostile input."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import FIXTURES, REPO
from nodl.diagnostics import Severity
from nodl.frontends.xml_reader import XmlAttribute, XmlElement, XmlTree, load_xml

LEGACY = FIXTURES / 'legacy'
ERRORS = LEGACY / 'errors'


def errors_of(tree: XmlTree) -> list[tuple[int, int, str]]:
    return [(d.line, d.column, d.message) for d in tree.diagnostics if d.severity is Severity.ERROR]


# --------------------------------------------------------------------------
# Positions


def test_columns_count_characters_not_bytes() -> None:
    tree = load_xml('<interface version="1">\n  <node name="ééé" executable="x" bogus="1"/>\n'
                    '</interface>\n')
    bogus = tree.root.children[0].get('bogus')  # type: ignore[union-attr]
    assert bogus is not None and (bogus.line, bogus.column) == (2, 35)


def test_crlf_and_cr_line_breaks_count_as_one_line() -> None:
    for newline in ('\r\n', '\r'):
        text = newline.join(['<interface version="1">', '  <node executable="x">',
                             '    <topic name="t" type="a/msg/B" />', '  </node>', '</interface>'])
        topic = load_xml(text).root.children[0].children[0]  # type: ignore[union-attr]
        assert (topic.line, topic.column) == (3, 5), newline


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(['a', 'pkg', 'x:y', 'value-sep', 'é', 'n_1']),
                          st.sampled_from([' ', '  ', '\t', '\n  ', '\r\n ']),
                          st.sampled_from(['=', ' = ', '=\n']),
                          st.sampled_from(['"v"', "'w'", '"a>b"', '"x\ny"', '"é"', '""', '"b=\'c\'"'])),
                max_size=5, unique_by=lambda t: t[0]),
       st.sampled_from(['', ' ', 'é ', '<!-- c -->']), st.sampled_from(['/>', ' />', '\n/>']))
def test_attributes_are_placed_as_one_by_one(attributes, lead, close) -> None:
    """The placement of a tag's attributes in one match (a tag on one line) gives the
    positions the attribute-by-attribute scan gives (every tag, on one line or not)."""
    from nodl.frontends import xml_reader as X

    tag = '<t' + ''.join(f'{space}{name}{equals}{value}' for name, space, equals, value in attributes) + close
    text = f'<root>\n{lead}{tag}</root>'
    element = load_xml(text).root.children[0]  # type: ignore[union-attr]
    lines = X._Lines(text)
    pairs = [part for a in element.attributes for part in (a.name, a.value)]
    start = lines.offset(element.line, element.column)
    assert element.attributes == X._place_attributes_by_name(lines, element.line, element.column, pairs, start)
    assert [a.name for a in element.attributes] == [name for name, *_ in attributes]


# --------------------------------------------------------------------------
# Malformed and hostile input


def test_malformed_xml_is_one_positioned_error() -> None:
    tree = load_xml(ERRORS / 'malformed.nodl.xml')
    assert errors_of(tree) == [(4, 5, 'malformed XML: mismatched tag')]


def test_billion_laughs_is_rejected_before_any_expansion() -> None:
    start = time.perf_counter()
    tree = load_xml(ERRORS / 'billion_laughs.nodl.xml')
    assert time.perf_counter() - start < 1.0
    errors = errors_of(tree)
    assert [(line, column) for line, column, _ in errors] == [(2, 1)]
    assert 'document type declarations (<!DOCTYPE ...>) are not allowed' in errors[0][2]
    assert tree.root is None


def test_external_entities_are_never_resolved() -> None:
    tree = load_xml(ERRORS / 'external_entity.nodl.xml')
    assert [(line, column) for line, column, _ in errors_of(tree)] == [(1, 1)]
    assert tree.root is None
    assert not any('root:' in d.message for d in tree.diagnostics)


def test_undeclared_entity_is_malformed_xml() -> None:
    tree = load_xml('<interface version="1"><node name="&x;"/></interface>')
    assert [message for *_, message in errors_of(tree)] == ['malformed XML: undefined entity']


def test_files_over_10_mb_are_rejected(tmp_path: Path) -> None:
    big = tmp_path / 'big.nodl.xml'
    big.write_bytes(b'<interface version="1">' + b' ' * (10 * 1024 * 1024) + b'</interface>')
    errors = errors_of(load_xml(big))
    assert len(errors) == 1
    assert 'larger than the limit' in errors[0][2] and '10 MB' in errors[0][2]


def test_non_utf8_is_rejected_with_position() -> None:
    errors = errors_of(load_xml(ERRORS / 'latin1.nodl.xml'))
    assert [(line, column) for line, column, _ in errors] == [(2, 18)]
    assert 'not valid UTF-8' in errors[0][2]


def test_a_declared_non_utf8_encoding_is_a_warning() -> None:
    tree = load_xml('<?xml version="1.0" encoding="ISO-8859-1"?>\n'
                    '<interface version="1"><node executable="caf\u00e9"/></interface>')
    assert errors_of(tree) == []
    assert tree.root.children[0].get('executable').value == 'caf\u00e9'  # type: ignore[union-attr]
    assert "encoding 'ISO-8859-1'" in tree.diagnostics[0].message


def test_missing_file_is_an_os_error() -> None:
    with pytest.raises(FileNotFoundError):
        load_xml(LEGACY / 'does_not_exist.nodl.xml')


# --------------------------------------------------------------------------
# The tree and the module


def test_load_xml_keeps_the_tree() -> None:
    tree = load_xml(LEGACY / 'role_attributes.nodl.xml')
    assert tree.root is not None and tree.root.tag == 'interface'
    assert [c.tag for c in tree.root.children] == ['node', 'node']
    assert tree.root.children[0].get('executable').value == 'first'  # type: ignore[union-attr]


def test_attributes_are_placed_when_first_read() -> None:
    tree = load_xml('<a>\n  <b x="1"\n     y=\'2\'/></a>')
    element = tree.root.children[0]  # type: ignore[union-attr]
    assert element.pairs == ['x', '1', 'y', '2']  # what a reader of values alone needs
    assert element.attributes == [XmlAttribute('x', '1', 2, 6), XmlAttribute('y', '2', 3, 6)]
    assert element.attributes is element.attributes  # placed once
    made = XmlElement('c', [XmlAttribute('z', '3', 1, 4)], 1, 1)
    assert made.pairs == ['z', '3'] and made.get('z') == XmlAttribute('z', '3', 1, 4)


def test_module_imports_neither_dataclasses_nor_pathlib() -> None:
    code = ('import sys; import nodl.frontends.xml_reader; '
            "print('dataclasses' in sys.modules, 'pathlib' in sys.modules)")
    result = subprocess.run([sys.executable, '-S', '-c', code], cwd=REPO, text=True,
                            capture_output=True, timeout=60,
                            env={**os.environ, 'PYTHONPATH': str(REPO)})
    assert result.stdout.split() == ['False', 'False'], result.stderr
