"""The monitor's logic without a screen: rows, sorting, filtering, statistics, message trees, publishing input."""

from __future__ import annotations

import pytest

from rostui.core.msg import get_message_class
from rostui.models.monitor.publish import PublishError, check_topic, message_from_text, message_template, parse_rate
from rostui.models.monitor.rows import (
    Column, Liveness, TopicRow, age_text, bandwidth_text, filter_rows, rate_text, sort_rows,
)
from rostui.models.monitor.stats import RATE_WINDOW_SECONDS, STALE_MIN_SECONDS, TopicStats
from rostui.tools.topic.rates import window_rate
from rostui.models.monitor.tree import ARRAY_SHOWN, PathError, constant_names, message_tree, value_at
from rostui.tools.topic.rates import HzStats


def rows() -> list[TopicRow]:
    return [
        TopicRow("/b", "std_msgs/String", ("/p",), (), 10.0, 200.0, 0.05, Liveness.LIVE),
        TopicRow("/a", "geometry_msgs/Twist", ("/p", "/q"), ("/s",), 100.0, 5000.0, 0.01, Liveness.LIVE),
        TopicRow("/c", "rosgraph_msgs/Log", (), ("/s",), None, None, None, Liveness.NO_PUBLISHERS),
    ]


def test_sort_by_each_column() -> None:
    """Names A-Z, counts and figures biggest first (no figure last), ages youngest first; reverse flips."""
    by = {c: [r.name for r in sort_rows(rows(), c)] for c in Column}
    assert by[Column.TOPIC] == ["/a", "/b", "/c"]
    assert by[Column.TYPE] == ["/a", "/c", "/b"]
    assert by[Column.PUBS] == ["/a", "/b", "/c"]
    assert by[Column.RATE] == ["/a", "/b", "/c"]
    assert by[Column.BANDWIDTH] == ["/a", "/b", "/c"]
    assert by[Column.AGE] == ["/a", "/b", "/c"]
    assert by[Column.LIVE] == ["/a", "/b", "/c"]
    assert [r.name for r in sort_rows(rows(), Column.TOPIC, reverse=True)] == ["/c", "/b", "/a"]
    assert Column.LIVE.next() is Column.TOPIC


def test_filter_matches_name_or_type_in_any_case() -> None:
    assert [r.name for r in filter_rows(rows(), "TWIST")] == ["/a"]
    assert [r.name for r in filter_rows(rows(), "/c")] == ["/c"]
    assert len(filter_rows(rows(), "  ")) == 3
    assert filter_rows(rows(), "nothing") == []


def test_cell_texts() -> None:
    assert rows()[1].cells() == ("/a", "geometry_msgs/Twist", "2", "1", "100.0", "5.00KB/s", "0.01s", "● live")
    assert (rate_text(None), rate_text(2.0), rate_text(1234.4)) == ("-", "2.000", "1234")
    assert (bandwidth_text(999), bandwidth_text(2_500_000)) == ("999.00B/s", "2.50MB/s")
    assert (age_text(None), age_text(12.34), age_text(125)) == ("-", "12.3s", "2m05s")


def test_rate_is_rostopic_hz_over_the_same_arrivals() -> None:
    """A steady 20 Hz stream: the monitor's rate is what HzStats (rostopic hz) computes from the same times."""
    stats, hz = TopicStats(), HzStats()
    for i in range(100):
        stats.add(1000.0 + i * 0.05, 10)
        hz.add(1000.0 + i * 0.05)
    sample = stats.sample(now=1000.0 + 99 * 0.05)
    assert sample.rate == pytest.approx(hz.stats()[0]) == pytest.approx(20.0)
    assert sample.bandwidth == pytest.approx(10 * 100 / (99 * 0.05))
    assert list(stats.rate_history) == [sample.rate]


def test_rate_window_forgets_old_arrivals() -> None:
    """After a pause, the rate is of the last ten seconds, not of the whole history."""
    stats = TopicStats()
    for i in range(50):
        stats.add(1000.0 + i * 0.01, 1)  # 100 Hz burst
    for i in range(20):
        stats.add(1100.0 + i * 0.5, 1)  # then 2 Hz
    assert stats.sample(now=1100.0 + 19 * 0.5).rate == pytest.approx(2.0)


def test_a_stalled_screen_does_not_lift_the_rate() -> None:
    """25 Hz sent; the screen stalled 1.2 s, so that moment's 30 messages came at once when it woke.

    When the window begins at that burst, rostopic hz's mean over the same arrivals reads about 10 %
    high (the burst's messages were sent before the window); the monitor counts the burst once.
    """
    sent = [1000.0 + i * 0.04 for i in range(750)]
    woke = 1010.0
    stalled = [t for t in sent if woke - 1.2 < t <= woke]
    arrivals = [woke + stalled.index(t) * 1e-5 if t in stalled else t for t in sent]  # handed over in turn
    stats, hz = TopicStats(), HzStats()
    for t in arrivals:
        stats.add(t, 10)
    now = woke + RATE_WINDOW_SECONDS - 0.01
    window = [t for t in arrivals if now - RATE_WINDOW_SECONDS <= t <= now]
    for t in window:
        hz.add(t)
    assert hz.stats()[0] > 27.5, "the naive mean is lifted by the burst"
    assert stats.sample(now=now).rate == pytest.approx(25.0, rel=0.005)


def test_window_rate() -> None:
    """A steady stream, a burst at the start, at the end and in the middle; too few arrivals."""
    steady = [i * 0.1 for i in range(11)]
    assert window_rate(steady) == pytest.approx(10.0)
    assert window_rate([0.0, 0.0, 0.0] + [i * 0.1 for i in range(1, 11)]) == pytest.approx(10.0)
    assert window_rate(steady + [1.0, 1.0, 1.0]) == pytest.approx(13 / 1.0)
    assert window_rate([0.0, 0.5, 0.5, 0.5, 1.0]) == pytest.approx(4.0)
    assert window_rate([5.0]) is None and window_rate([]) is None
    assert window_rate([5.0, 5.0, 5.0]) == 0.0
    assert window_rate([5.0, 5.0001, 5.00015]) is None  # too short a span to tell a rate from a held-up reader


def test_stale_after_missed_periods() -> None:
    """Messages every 0.1 s, then none: stale only after the minimum wait; its rate is dropped."""
    stats = TopicStats()
    for i in range(11):
        stats.add(1000.0 + i * 0.1, 1)
    assert stats.sample(now=1001.05).rate == pytest.approx(10.0)
    assert not stats.stale_at(1001.0 + STALE_MIN_SECONDS - 0.1)
    assert stats.stale_at(1001.0 + STALE_MIN_SECONDS + 0.1)
    assert stats.sample(now=1010.0).rate is None
    assert stats.age(1010.0) == pytest.approx(9.0)


def test_tree_resolves_log_level_and_truncates_arrays() -> None:
    """rosgraph_msgs/Log level 2 shows INFO; a long array shows its first items and a count of the rest."""
    log = get_message_class("rosgraph_msgs/Log")(level=2, msg="hi", topics=[f"/t{i}" for i in range(12)])
    items = {item.label: item for item in message_tree(log)}
    assert items["level"].line == "level: 2 (INFO)" and items["level"].numeric
    assert items["msg"].line == "msg: 'hi'"
    topics = items["topics"]
    assert topics.text == "string[12]"
    assert [c.label for c in topics.children][-2:] == [f"[{ARRAY_SHOWN - 1}]", f"… {12 - ARRAY_SHOWN} more"]
    assert items["header"].children[1].line == "stamp: 0.000000000"
    assert constant_names(type(log), "uint8", 16) == ["FATAL"]
    assert constant_names(type(log), "string", 2) == []


def test_value_at_paths() -> None:
    scan = get_message_class("sensor_msgs/LaserScan")(ranges=[1.0, 2.5], angle_min=-1.5)
    assert value_at(scan, "ranges[1]") == 2.5
    assert value_at(scan, "angle_min") == -1.5
    assert value_at(scan, "header/seq") == 0.0
    for bad in ("ranges[7]", "nope", "header/frame_id", "ranges[x]"):
        with pytest.raises(PathError):
            value_at(scan, bad)


def test_publish_input() -> None:
    """The template is rostopic pub's completion; edits fill the message; bad input is one line."""
    cls, template = message_template("geometry_msgs/Twist")
    assert template.splitlines()[:2] == ["linear:", "  x: 0.0"]
    msg = message_from_text(cls, "linear: {x: 2.0}\nangular: {z: 1.8}")
    assert (msg.linear.x, msg.angular.z) == (2.0, 1.8)
    assert message_from_text(cls, "") == cls()
    for text, words in (("linear: {x: [", "message:1:"), ("linear: {q: 1}", "linear.q")):
        with pytest.raises(PublishError) as err:
            message_from_text(cls, text)
        assert words in str(err.value) and "\n" not in str(err.value)
    with pytest.raises(PublishError, match="invalid message type: nope/Nope"):
        message_template("nope/Nope")
    assert parse_rate("") is None and parse_rate(" 10 ") == 10.0
    for bad in ("x", "0", "-1", "nan", "inf"):
        with pytest.raises(PublishError):
            parse_rate(bad)
    assert check_topic("cmd") == "/cmd"
    with pytest.raises(PublishError, match="not allowed"):
        check_topic("a b")


def test_sparkline_starts_rates_at_zero_and_spans_a_fields_range() -> None:
    """Rates are drawn from zero (100.0 and 100.1 Hz look alike); a field's plot spans its own range."""
    from rostui.apps.monitor.detail import sparkline

    assert sparkline([100.0, 100.1, 100.0], 10, 1) == ["███"]
    assert sparkline([0.0, 5.0, 10.0], 10, 2) == ["  █", " ██"]
    assert sparkline([-1.0, 0.0, 1.0], 10, 1, floor=None) == [" ▄█"]
    assert sparkline(list(range(100)), 5, 1, floor=None) == sparkline([95, 96, 97, 98, 99], 5, 1, floor=None)
    assert sparkline([], 10, 2) == ["", ""]


def test_tree_of_a_big_array_counts_it() -> None:
    """A megabyte image shows its length and first items (the array is not copied)."""
    image = get_message_class("sensor_msgs/Image")(height=1000, width=1000, data=bytes(range(256)) * 3907)
    data = {item.label: item for item in message_tree(image)}["data"]
    assert data.text == "uint8[1000192]"
    assert [c.line for c in data.children][:2] == ["[0]: 0", "[1]: 1"] and data.children[-1].label == "… 1000184 more"
