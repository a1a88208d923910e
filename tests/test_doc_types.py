"""nodl doc's field tables: fields, nested types, constants; unavailable types are findings."""

from __future__ import annotations

import sys

from nodl.composition.entities import Location
from nodl.doc.blocks import Heading, Link, Note, Table, text_of
from nodl.doc.types import type_appendix
from nodl.interface_types.resolve import interface_index

#: The ament prefix of the virtual environment (std_msgs, std_srvs... are installed there).
PREFIXES = [sys.prefix]


def test_a_message_table_links_its_nested_types_which_get_their_own_table() -> None:
    blocks, findings = type_appendix(interface_index(prefixes=PREFIXES), 'p', {'std_msgs/msg/Header': None})
    assert findings == []
    titles = [b.text for b in blocks if isinstance(b, Heading)]
    assert titles == ['std_msgs/msg/Header', 'builtin_interfaces/msg/Time']
    first = next(b for b in blocks if isinstance(b, Table))
    stamp = next(r for r in first.rows if text_of(r[0]) == 'stamp')
    assert isinstance(stamp[1][0], Link) and stamp[1][0].label == 'p-type-builtin-interfaces-msg-time'
    assert text_of(stamp[2]) == 'builtin_interfaces::msg::Time'


def test_constants_and_service_parts_are_shown() -> None:
    blocks, _ = type_appendix(interface_index(prefixes=PREFIXES), 'p', {'diagnostic_msgs/msg/DiagnosticStatus': None,
                                                       'std_srvs/srv/Trigger': None})
    constants = [b for b in blocks if isinstance(b, Table) and b.columns[0] == 'Constant']
    assert [text_of(r[0]) for r in constants[0].rows][:2] == ['OK', 'WARN']
    titles = [b.text for b in blocks if isinstance(b, Heading)]
    assert 'std_srvs/srv/Trigger: Request' in titles and 'std_srvs/srv/Trigger: Response' in titles


def test_a_type_of_a_package_not_installed_is_a_finding_with_what_to_install() -> None:
    where = Location('node.nodl.yaml', 7, 13)
    blocks, findings = type_appendix(interface_index(prefixes=PREFIXES), 'p', {'missing_msgs/msg/Thing': where})
    [finding] = findings
    assert finding.code == 'NODL270' and (finding.file, finding.line, finding.column) == (
        'node.nodl.yaml', 7, 13)
    assert 'install it' in finding.message and 'ros-$ROS_DISTRO-missing-msgs' in finding.message
    assert [b.kind for b in blocks if isinstance(b, Note)] == ['warning']


def test_a_type_the_installed_package_does_not_define_is_a_finding() -> None:
    _, findings = type_appendix(interface_index(prefixes=PREFIXES), 'p', {'std_msgs/msg/Strnig': None})
    assert [f.code for f in findings] == ['NODL271']
