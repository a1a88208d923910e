"""The diagnostic_aggregator configuration, against the aggregator's documented parameters."""

from __future__ import annotations

import yaml

from nodl.monitor.aggregator import analyzer_config, format_config, tree_paths

#: The parameters diagnostic_aggregator documents for its two analyzers.
GENERIC = {'type', 'path', 'contains', 'startswith', 'name', 'expected', 'regex',
           'remove_prefix', 'find_and_remove_prefix', 'timeout', 'num_items', 'discard_stale'}
GROUP = {'type', 'path', 'analyzers'}


def test_one_generic_analyzer_per_namespace_in_one_group() -> None:
    config = yaml.safe_load(format_config(analyzer_config(['/robot/sensor', '/robot/arm/sensor',
                                                           '/talker'])))
    group = config['analyzers']['ros__parameters']['nodl']
    assert set(group) <= GROUP and group['type'] == 'diagnostic_aggregator/AnalyzerGroup'
    analyzers = group['analyzers']
    assert set(analyzers) == {'system', 'ns_robot', 'ns_robot_arm', 'ns_root'}
    for analyzer in analyzers.values():
        assert set(analyzer) <= GENERIC
        assert analyzer['type'] == 'diagnostic_aggregator/GenericAnalyzer'
    assert analyzers['ns_robot']['expected'] == ['nodl: /robot/sensor']  # not /robot/arm/...
    assert analyzers['ns_root'] == {'type': 'diagnostic_aggregator/GenericAnalyzer', 'path': 'root',
                                    'expected': ['nodl: /talker'], 'remove_prefix': ['nodl: /'],
                                    'timeout': 5.0}


def test_the_tree_the_aggregator_shows() -> None:
    names = ['nodl: system', 'nodl: /robot/sensor', 'nodl: /robot/arm/sensor', 'nodl: /talker']
    config = analyzer_config(['/robot/sensor', '/robot/arm/sensor', '/talker'])
    assert tree_paths(config, names + ['other']) == {
        'nodl: system': '/NoDL/System/system', 'nodl: /robot/sensor': '/NoDL/robot/sensor',
        'nodl: /robot/arm/sensor': '/NoDL/robot arm/sensor', 'nodl: /talker': '/NoDL/root/talker'}


def test_names_are_quoted_and_keys_valid_parameter_names() -> None:
    text = format_config(analyzer_config(['/a-b/x', '/a_b/y']))
    config = yaml.safe_load(text)
    keys = set(config['analyzers']['ros__parameters']['nodl']['analyzers'])
    assert keys == {'system', 'ns_a_b', 'ns_a_b_2'}
