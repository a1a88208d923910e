"""Control characters and Trojan Source bidi controls in what a launch file gives its nodes
(nodl.launch.text_checks): NODL221 and NODL222 at the character, in XML, YAML and
Python launch files; names leave their node out, rules are left out, values are kept."""

from __future__ import annotations

from pathlib import Path

import pytest

from nodl.analysis import analyse_launch
from nodl.launch import load_launch
from nodl.launch.model import SourceLocation
from nodl.launch.text_checks import place_character, unsafe_diagnostic

FIXTURES = Path(__file__).parent / 'fixtures' / 'launch' / 'text_safety'


def _found(name: str) -> tuple[list[tuple[str, int, int]], dict[str, object]]:
    result = load_launch(str(FIXTURES / name), {})
    found = [(d.code or '', d.line, d.column) for d in result.diagnostics if d.code in ('NODL221', 'NODL222')]
    assert all(d.severity.value == 'error' for d in result.diagnostics if d.code in ('NODL221', 'NODL222'))
    return found, {n.name or '': n for n in result.nodes}


def test_xml_every_character_at_its_place() -> None:
    """Character references are placed at their '&#'; a node whose name or namespace holds one
    is left out (that error only, no NODL519); a rule is left out, said once although
    set_remap gives it to two nodes; values are kept; RLM in Hebrew text is no finding."""
    found, nodes = _found('hostile.launch.xml')
    assert found == [
        ('NODL222', 5, 53),   # name="tal&#x202E;ker"
        ('NODL221', 6, 71),   # namespace="n&#x9B;s"
        ('NODL222', 7, 44),   # name="$(var renamed)": the attribute (the value is made elsewhere)
        ('NODL222', 8, 37),   # set_remap, once for both nodes in scope
        ('NODL222', 10, 35),  # <remap to="chat&#x2066;ter">
        ('NODL221', 11, 38),  # a value
        ('NODL222', 12, 20),  # a parameter name
    ]
    assert sorted(nodes) == ['listener', 'listener2']
    listener = nodes['listener']
    assert listener.remaps == [] and nodes['listener2'].remaps == []  # type: ignore[attr-defined]
    values = {k: v for source in listener.parameters for k, v in source.values.items()}  # type: ignore[attr-defined]
    assert values['greeting'] == 'hi \x9b31m there'
    assert values['hebrew'] == '\u05e9\u200f\u05dc\u05d5\u05dd'  # RLM: allowed


def test_messages_show_the_characters_as_escapes() -> None:
    result = load_launch(str(FIXTURES / 'hostile.launch.xml'), {})
    first = next(d for d in result.diagnostics if d.code == 'NODL222')
    assert first.message.startswith("the node name 'tal\\u202eker' holds U+202E RIGHT-TO-LEFT OVERRIDE")
    assert 'Trojan Source' in first.message and '\u202e' not in first.message
    rule = next(d for d in result.diagnostics if d.line == 10)
    assert 'the rule is left out' in rule.message


def test_yaml_escapes_are_placed_at_their_backslash() -> None:
    found, nodes = _found('hostile.launch.yaml')
    assert found == [('NODL221', 5, 13), ('NODL221', 15, 16), ('NODL222', 12, 16)]
    assert list(nodes) == ['listener']


def test_python_launch_file() -> None:
    """Python string escapes are placed at their backslash (columns as written); a list value
    holding one unsafe string is found too."""
    found, nodes = _found('hostile.launch.py')
    assert found == [('NODL222', 9, 23), ('NODL221', 11, 43), ('NODL222', 12, 36),
                     ('NODL221', 12, 64)]
    assert list(nodes) == ['listener']


def test_analysis_says_each_once_without_a_cascade() -> None:
    """analyse: the launch findings and the given parameter file's, and no 'not-analysable'
    for the rules left out."""
    analysis = analyse_launch(FIXTURES / 'hostile.launch.xml', prefixes=[])
    codes = [(f.code, Path(f.diagnostic.file).name, f.diagnostic.line) for f in analysis.findings
             if f.code in ('NODL221', 'NODL222')]
    assert len(codes) == 10
    assert ('NODL222', 'hostile.params.yaml', 4) in codes and ('NODL221', 'hostile.params.yaml', 5) in codes
    assert not [f for f in analysis.findings if f.kind == 'not-analysable']


@pytest.mark.parametrize('written, char, column', [
    ('<remap from="a" to="b&#x202e;c"/>', '\u202e', 22),
    ('<remap from="a" to="b&#8238;c"/>', '\u202e', 22),
    ('<remap from="a" to="b\u202ec"/>', '\u202e', 22),
    ('name: "a\\e"', '\x1b', 9),
    ('name: "a\\x1b"', '\x1b', 9),
    ("name='a\\N{RIGHT-TO-LEFT OVERRIDE}'", '\u202e', 8),
    ("name='a\\033'", '\x1b', 8),
    ("name='a\\\\u202e' + chr(0x202e)", '\u202e', 1),  # an escaped backslash; chr() not placed
])
def test_place_character(tmp_path: Path, written: str, char: str, column: int) -> None:
    path = tmp_path / 'x.launch.txt'
    path.write_text('# first line\n' + written + '\n', encoding='utf-8')
    assert place_character(SourceLocation(str(path), 2, 1), char) == (str(path), 2, column)


def test_place_character_stays_in_its_entry(tmp_path: Path) -> None:
    """The search stops where the entry ends: a later entry's character is not taken."""
    path = tmp_path / 'x.launch.xml'
    path.write_text('<launch>\n  <remap from="a" to="$(var x)"/>\n  <remap from="b" to="c&#x202e;"/>\n'
                    '</launch>\n', encoding='utf-8')
    assert place_character(SourceLocation(str(path), 2, 3), '\u202e') == (str(path), 2, 3)
    path.write_text('launch:\n- node:\n    name: $(var x)\n- node:\n    name: "\\u202e"\n', encoding='utf-8')
    assert place_character(SourceLocation(str(path), 2, 3), '\u202e') == (str(path), 2, 3)


def test_lrm_rlm_and_ordinary_text_are_no_finding() -> None:
    at = SourceLocation('<none>', 0, 0)
    assert unsafe_diagnostic('שלום\u200f abc\u200e\ttab\nline', 'the value', at) is None
    found = unsafe_diagnostic('a\u2069', 'the value', at)
    assert found is not None and found.code == 'NODL222' and (found.line, found.column) == (0, 0)
