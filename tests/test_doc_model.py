"""nodl doc's page content: the header, parameters, the parameter file, endpoints, QoS in words."""

from __future__ import annotations

import sys

import yaml

from conftest import FIXTURES
from nodl.composition.resolved import resolve_node
from nodl.doc.blocks import Code, Heading, Link, Table, text_of
from nodl.doc.model import PageSource, node_page, qos_words, value_text
from nodl.interface_types.resolve import interface_index
from nodl.model.qos import QoSProfile
from nodl.validation.validators import lookup

TALKER = FIXTURES / 'doc' / 'talker.nodl.yaml'

#: The ament prefix of the virtual environment (std_msgs, std_srvs... are installed there).
PREFIXES = [sys.prefix]


def _page():  # type: ignore[no-untyped-def]
    resolved = resolve_node(TALKER)
    source = PageSource(None, None, 'talker.nodl.yaml', 'file')
    return node_page(resolved, source, interface_index(prefixes=PREFIXES), lambda p: p)


def _table_after(page, title: str) -> Table:  # type: ignore[no-untyped-def]
    blocks = page.blocks
    at = next(i for i, b in enumerate(blocks) if isinstance(b, Heading) and b.text == title)
    return next(b for b in blocks[at:] if isinstance(b, Table))


def test_a_deadline_reads_as_a_rate() -> None:
    qos = QoSProfile('KEEP_LAST', 'RELIABLE', 10, 'TRANSIENT_LOCAL', deadline_ns=100_000_000)
    words = qos_words(qos)
    assert words.startswith('reliable, keep last 10, transient local')
    assert 'expects at least 10 Hz (deadline 100 ms)' in words
    assert qos_words(QoSProfile('KEEP_ALL', 'BEST_EFFORT')) == 'best effort, keep all'
    assert qos_words(None) == ''


def test_the_parameters_table_names_types_three_ways_and_uses_the_validators_words() -> None:
    page, findings = _page()
    assert findings == []
    table = _table_after(page, 'Parameters')
    rows = {text_of(row[0]): [text_of(cell) for cell in row] for row in table.rows}
    assert rows['rate'][1:4] == ['PARAMETER_DOUBLE', 'double', 'float']
    assert rows['rate'][6] == lookup('bounds<>').describe([0.1, 50.0])  # the table's own words
    assert rows['greeting'][5] == 'yes'
    assert rows['targets'][1:5] == ['PARAMETER_STRING_ARRAY', 'std::vector<std::string>', 'list[str]',
                                    'required']
    assert rows['use_sim_time'][8] == 'base:node'


def test_the_parameter_file_is_valid_yaml_with_every_default() -> None:
    page, _ = _page()
    code = next(b for b in page.blocks if isinstance(b, Code))
    data = yaml.safe_load(code.text)
    values = data['/**']['ros__parameters']
    assert values['rate'] == 2.0 and values['greeting'] == 'hello'
    assert 'targets' not in values
    assert '# required, no default: targets' in code.text


def test_endpoints_link_their_field_table_and_leave_the_client_library_out_of_the_tables() -> None:
    page, _ = _page()
    table = _table_after(page, 'Publishers')
    [row] = table.rows
    assert text_of(row[0]) == 'chatter'
    link = row[1][0]
    assert isinstance(link, Link) and link.label == 'node-talker-type-std-msgs-msg-string'
    assert any(isinstance(b, Heading) and b.label == link.label for b in page.blocks)
    assert 'expects at least 2 Hz' in text_of(row[2])
    assert not any(isinstance(b, Heading) and b.text == 'Service clients' for b in page.blocks)
    assert all('/rosout' not in text_of(r[0]) for r in table.rows)


def test_values_read_as_written() -> None:
    assert value_text([-2.5, 2.5]) == '[-2.5, 2.5]'
    assert value_text(True) == 'true'
    assert value_text(' x') == "' x'"
