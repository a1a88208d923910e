"""Wording helpers: nodl.wording (the one "did you mean" of the toolkit)."""

from __future__ import annotations

from nodl.wording import close_matches, did_you_mean


def test_a_word_in_another_case_is_suggested_first() -> None:
    assert did_you_mean('Subscriptions', ['publishers', 'subscriptions']) == \
        "; did you mean 'subscriptions'?"


def test_a_close_word_is_suggested() -> None:
    assert did_you_mean('subscribers', ['publishers', 'subscriptions']) == \
        "; did you mean 'subscriptions'?"


def test_nothing_close_suggests_nothing() -> None:
    assert did_you_mean('qqqq', ['publishers', 'subscriptions']) == ''
    assert did_you_mean(5, ['publishers']) == ''


def test_a_node_name_is_matched_by_its_last_segment_first() -> None:
    graph = ['/a/scan', '/b/scan', '/c/scanner', '/d/scan']
    assert close_matches('/x/scan', graph, most=3) == ['/a/scan', '/b/scan', '/d/scan']
    assert did_you_mean('/x/scan', graph, most=3, aside=True) == \
        " (did you mean '/a/scan' or '/b/scan' or '/d/scan'?)"


def test_a_misspelt_node_name_gets_the_closest_names() -> None:
    graph = ['/ux/graph_talker', '/other/thing']
    assert did_you_mean('/ux/graph_talkr', graph, most=3, aside=True) == \
        " (did you mean '/ux/graph_talker'?)"


def test_a_higher_cutoff_asks_for_closer_words() -> None:
    assert close_matches('sensor_msg', ['sensor_msgs', 'std_msgs'], most=3) == ['sensor_msgs']
    assert close_matches('snsr_mg', ['sensor_msgs'], most=3) == ['sensor_msgs']
    assert close_matches('snsr_mg', ['sensor_msgs'], most=3, cutoff=0.8) == []


def test_with_prefix_the_candidates_a_word_begins_come_first() -> None:
    codes = ['NODL101', 'NODL210', 'NODL211', 'NODL121']
    assert close_matches('NODL21', codes, most=3, prefix=True) == ['NODL210', 'NODL211', 'NODL121']
    assert close_matches('NODL21', codes, most=1, prefix=True) == ['NODL210']
    assert close_matches('nodl210', codes, prefix=True) == ['NODL210']
