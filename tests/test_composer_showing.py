"""nodl.composer.showing: what nodl system show prints, and its report."""

from __future__ import annotations

from composer_helpers import LAUNCH, definitions
from nodl.composer import Composition
from nodl.composer.showing import show_report, show_text


def test_show_text_lists_nodes_ports_connections_and_kept_parts() -> None:
    c = Composition.open(str(LAUNCH / 'demo.launch.xml'), definitions=definitions())
    text = show_text(c)
    assert text.startswith(f'{LAUNCH / "demo.launch.xml"} (xml): 4 nodes, 2 parts kept as written\n')
    for line in ('  /talker  demo_pkg talker  [n1]',
                 '    param rate = 5.0',
                 '    publisher chatter -> /chatter (std_msgs/msg/String)',
                 '    service server ~/reset -> /talker/reset (std_srvs/srv/Trigger)',
                 ('  /quiet  demo_pkg listener  [n3]  read-only: a condition decides whether it '
                  'is launched  (not launched with the default arguments)'),
                 '  /sub/counter  demo_pkg counter  [n5]',
                 '    param: a parameter file (kept, line 16)',
                 'kept as written (read-only here):',
                 '  line 5: <include>'):
        assert line in text.splitlines(), line
    assert '/rosout' not in text          # the client library's ports: with verbose only
    assert '/rosout' in show_text(c, verbose=True)
    report = show_report(c, False, 'nodl system show')
    assert report.summary == 'demo.launch.xml: 4 nodes, 0 errors, 4 warnings, 1 info'
    assert 'NODL979' in {d.code for d in report.diagnostics}
    assert report.json_payload()['nodes'][0]['name'] == 'talker'
