"""The policy of a launched system, resolved as `nodl analyse` resolves it (its test system)."""

from pathlib import Path

import pytest

from nodl.analysis import analyse_launch
from nodl.policy.launched import launch_policy
from nodl.policy.writer import write_policy
from test_policy_generate import round_trip

REPO = Path(__file__).parent.parent
ANALYSIS = REPO / 'tests' / 'fixtures' / 'analysis'
PREFIX = [str(ANALYSIS / 'prefix')]


@pytest.fixture(autouse=True)
def _in_repo(monkeypatch):
    monkeypatch.chdir(REPO)


def test_launched_system_golden_and_round_trip(golden):
    launch = ANALYSIS / 'launch' / 'system.launch.xml'
    result = launch_policy(launch, prefixes=PREFIX)
    assert result.ok, result.diagnostics
    text = write_policy(result.policy)
    golden.check(text, REPO / 'tests' / 'fixtures' / 'policy' / 'expected' / 'launched_system.policy.xml')
    instances = [n.instance for n in analyse_launch(launch, prefixes=PREFIX, checks={}).nodes]
    assert instances and all(i is not None for i in instances)
    round_trip(instances, text)


def test_the_three_frontends_give_one_policy():
    bodies = set()
    for name in ('system.launch.xml', 'system.launch.yaml', 'system.launch.py'):
        result = launch_policy(ANALYSIS / 'launch' / name, prefixes=PREFIX)
        text = write_policy(result.policy)
        # comments name the launch file and lines; the grants themselves must agree
        bodies.add('\n'.join(line.split(' <!--')[0] for line in text.splitlines()
                             if not line.lstrip().startswith('<!--')))
    assert len(bodies) == 1


def test_missing_launch_file_is_an_os_error(tmp_path):
    with pytest.raises(OSError):
        launch_policy(tmp_path / 'none.launch.xml')


def test_clock_when_use_sim_time_can_be_true_at_start():
    """set_parameter applies to every later node; a node's own <param> or parameter file after it
    wins (launch_ros's order); a launch argument decides; the writable parameter alone grants nothing."""
    launch = REPO / 'tests' / 'fixtures' / 'policy' / 'sim_time.launch.xml'
    clock = ('topic', 'subscribe', '/clock')

    def with_clock(arguments):
        result = launch_policy(launch, arguments, prefixes=PREFIX)
        assert result.ok, result.diagnostics
        return {p.fqn for _, p in result.policy.profiles() if clock in p.grants}

    assert with_clock({}) == {'/s/global'}
    assert with_clock({'sim': 'true'}) == {'/s/global', '/s/by_argument'}



def test_a_composable_node_is_in_its_containers_enclave():
    result = launch_policy(ANALYSIS / 'launch' / 'checks.launch.xml', prefixes=PREFIX, allow_missing=True)
    enclaves = {p.fqn: e.path for e, p in result.policy.profiles()}
    # (a composable node does not take its container's namespace: it is /camera)
    assert enclaves['/camera'] == enclaves['/robot/box'] == '/robot/box'
    camera = result.policy.profile('/camera')
    assert camera is not None and any('loaded into the container /robot/box' in n for n in camera.notes)


def test_the_prefixes_given_resolve_nodl_mixins_too(monkeypatch):
    """A definition whose publisher comes from a nodl:// mixin, in a prefix that is given but not
    in AMENT_PREFIX_PATH: its profile is written (it was a NODL566 gap before)."""
    monkeypatch.setenv('AMENT_PREFIX_PATH', PREFIX[0])   # no package 'mixed' there
    result = launch_policy(ANALYSIS / 'launch' / 'mixin.launch.xml',
                           prefixes=[str(ANALYSIS / 'mixin_prefix')])
    assert result.ok, result.diagnostics
    talker = result.policy.profile('/demo/talker')
    assert talker is not None and ('topic', 'publish', '/demo/chatter') in talker.names()
