"""The unresolved entities of a draft `nodl extract` wrote (nodl.targets.drafts)."""

from __future__ import annotations

from pathlib import Path

from conftest import FIXTURES
from nodl.targets.drafts import DraftGap, GapLine, describe, draft_gaps, gaps_of_text

DRAFT = FIXTURES / 'overlays' / 'gaps' / 'defs' / 'relay_pkg' / 'relay.nodl.yaml'


def test_the_fixture_drafts_three_communication_gaps_in_their_order() -> None:
    gaps = draft_gaps(str(DRAFT))
    assert [(g.section, g.name, g.communication) for g in gaps] == [
        ('publishers', 'status', True),          # its QoS is unknown, its name is not
        ('subscriptions', None, True),           # NODL901: the name is computed at run time
        ('service_clients', 'lookup', True),
    ]
    first = gaps[0].lines[0]
    assert (first.file, first.code) == (str(DRAFT), 'NODL903')
    # the GAP comment's own place in the draft
    assert DRAFT.read_text(encoding='utf-8').splitlines()[first.line - 1].lstrip().startswith('# GAP')
    assert first.column == 5
    assert describe(gaps) == '1 publisher, 1 subscription and 1 service client'


def test_a_file_nodl_extract_did_not_write_has_no_gaps(tmp_path: Path) -> None:
    # the same text without the extraction header: a hand-written file's comments are its own
    text = ''.join(line for line in DRAFT.read_text(encoding='utf-8').splitlines(keepends=True)
                   if 'by nodl extract' not in line)
    hand = tmp_path / 'relay.nodl.yaml'
    hand.write_text(text, encoding='utf-8')
    assert draft_gaps(str(hand)) == []
    assert draft_gaps(str(tmp_path / 'absent.nodl.yaml')) == []
    assert draft_gaps(None) == []


def test_an_entity_uncommented_since_is_resolved() -> None:
    text = ('  publishers:\n'
            '    # GAP src/a.py:3:5: topic QoS is computed at run time [NODL903]\n'
            '    # fill in what is missing, then uncomment:\n'
            '    - name: status\n'
            '      type: std_msgs/msg/String\n')
    assert gaps_of_text(text, 'a.nodl.yaml') == []


def test_a_parameter_gap_and_a_run_of_gap_lines() -> None:
    text = ('  parameters:\n'
            '    # GAP src/a.py:3:5: default value is computed at run time [NODL905]\n'
            '    # GAP src/a.py:3:9: description is computed at run time\n'
            '    # fill in what is missing, then uncomment:\n'
            '    # rate:\n'
            '    #   type: double\n')
    [gap] = gaps_of_text(text, 'a.nodl.yaml')
    assert gap == DraftGap('parameters', 'rate', (
        GapLine('a.nodl.yaml', 2, 5, 'src/a.py:3:5: default value is computed at run time', 'NODL905'),
        GapLine('a.nodl.yaml', 3, 5, 'src/a.py:3:9: description is computed at run time', None)))
    assert not gap.communication
    assert describe([gap, gap]) == '2 parameters'
