"""An XML file read where NoDL v2 is expected says what it is (nodl.frontends.xml_recognise, the legacy-xml frontend).

Before, YAML read the XML text as one string: "document is a string, not a mapping".
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from conftest import FIXTURES, REPO
from nodl import ValidationError, check_source, load_nodl
from nodl.frontends.xml_recognise import looks_like_xml, xml_diagnostics

LEGACY = FIXTURES / 'legacy'


def test_only_xml_is_recognised() -> None:
    assert looks_like_xml('<?xml version="1.0"?>\n<interface/>')
    assert looks_like_xml('\ufeff\n  <!-- a comment -->\n<interface/>')
    assert looks_like_xml('<interface version="1"/>')
    assert not looks_like_xml('<<: {a: 1}\n')  # YAML's merge key
    assert not looks_like_xml('nodl_version: 2\n')
    assert not looks_like_xml('{"nodl_version": 2}')
    assert xml_diagnostics('nodl_version: 2\n', 'x.yaml') is None


def test_a_legacy_file_is_named_with_the_legacy_readers_findings() -> None:
    report = check_source(LEGACY / 'invalid_v2.nodl.xml')
    codes = [d.code for d in report.diagnostics]
    assert codes[0] == 'NODL817' and 'NODL011' not in codes
    assert 'legacy NoDL XML file' in report.diagnostics[0].message
    assert 'nodl convert' in report.diagnostics[0].message
    assert 'NODL802' in codes  # the legacy reader's own error, at its line
    assert all(d.line for d in report.diagnostics)


def test_load_nodl_refuses_a_legacy_file_saying_what_it_is() -> None:
    with pytest.raises(ValidationError) as raised:
        load_nodl(LEGACY / 'boolean_attributes.nodl.xml')
    assert [d.code for d in raised.value.diagnostics] == ['NODL817']


@pytest.mark.parametrize(('text', 'words'), [
    ('<package format="3"><name>p</name></package>', 'package manifest'),
    ('<launch/>', 'root <launch>'),
    ('<interface version="1"><node name="a"', 'legacy NoDL XML file'),  # not well-formed
])
def test_other_xml(text: str, words: str) -> None:
    diagnostics = check_source(text).diagnostics
    assert diagnostics[0].code == 'NODL817' and words in diagnostics[0].message


def test_validate_on_a_legacy_file_and_a_directory_of_legacy_files(tmp_path: Path) -> None:
    legacy = LEGACY / 'role_attributes.nodl.xml'
    result = subprocess.run([sys.executable, '-m', 'nodl', 'validate', str(legacy)],
                            cwd=REPO, text=True, capture_output=True, timeout=60)
    assert result.returncode == 1
    assert result.stdout.startswith(f'{legacy}:1:1: error: this is a legacy NoDL XML file')
    assert 'not a mapping' not in result.stdout and 'Traceback' not in result.stderr
