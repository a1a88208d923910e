"""Message helpers: nodl.validation.messages (the one "did you mean" of the toolkit)."""

from __future__ import annotations

from nodl.validation.messages import close_matches, did_you_mean


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
