"""The pure parts of rostui.models.loggers: level spelling, finding logger nodes, the preferred logger."""

from __future__ import annotations

import pytest

from rostui.models.loggers import (
    LEVEL_NAMES, LoggerLevel, LoggerNode, display_level, format_loggers, logger_nodes, preferred_logger, request_level,
    resolve_node_name,
)

ROSPY = ["rosgraph", "rosgraph.network", "rosout", "rospy", "rospy.core", "rospy.topics", "xmlrpc"]
ROSCPP = ["ros", "ros.roscpp", "ros.roscpp.roscpp_internal", "ros.roscpp.superdebug"]


def test_levels_shown_upper_case_whatever_the_node_sends() -> None:
    """roscpp/rostui answer lower case, rospy upper case: all shown DEBUG..FATAL; unknown text kept, upper-cased."""
    assert LEVEL_NAMES == ("DEBUG", "INFO", "WARN", "ERROR", "FATAL")
    assert [display_level(t) for t in ("debug", "INFO", "warn", "Error", "fatal", "WARNING")] == \
        ["DEBUG", "INFO", "WARN", "ERROR", "FATAL", "WARN"]
    assert display_level("trace") == "TRACE"


def test_request_levels_are_upper_case_names() -> None:
    """Every node type accepts the upper-case name; anything else is refused before a call is made."""
    assert [request_level(t) for t in ("debug", "Info", "WARN", "error", "FATAL")] == list(LEVEL_NAMES)
    with pytest.raises(ValueError, match="unknown log level 'loud'"):
        request_level("loud")


def test_logger_nodes_from_the_service_list() -> None:
    """Nodes are the prefixes of <node>/get_loggers, sorted; can_set when set_logger_level is served too."""
    services = [
        ["/turtlesim/get_loggers", ["/turtlesim"]],
        ["/turtlesim/set_logger_level", ["/turtlesim"]],
        ["/ns/talker/get_loggers", ["/ns/talker"]],
        ["/ns/talker/set_logger_level", ["/ns/talker"]],
        ["/half/get_loggers", ["/half"]],
        ["/spawn", ["/turtlesim"]],
        ["/get_loggers", ["/odd"]],
        ["/turtlesim/get_loggers_extra", ["/turtlesim"]],
    ]
    assert logger_nodes(services) == [
        LoggerNode("/half", can_set=False), LoggerNode("/ns/talker"), LoggerNode("/turtlesim"),
    ]


def test_preferred_logger_is_the_one_users_change() -> None:
    """rospy: rosout; roscpp/rostui: ros.<package>, never roscpp's own; else ros; else the first."""
    assert preferred_logger(ROSPY) == "rosout"
    assert preferred_logger(["ros", "ros.agitr", "ros.agitr.motor"]) == "ros.agitr"
    assert preferred_logger(ROSCPP + ["ros.turtlesim"]) == "ros.turtlesim"
    assert preferred_logger(ROSCPP) == "ros"
    assert preferred_logger(["a.b", "c"]) == "a.b"
    assert preferred_logger([]) is None


def test_format_loggers_aligns_levels() -> None:
    """One line per logger, levels in one column."""
    items = [LoggerLevel("ros", "INFO", "info"), LoggerLevel("ros.roscpp", "DEBUG", "debug")]
    assert format_loggers(items) == "ros         INFO\nros.roscpp  DEBUG\n"
    assert format_loggers([]) == ""


def test_node_names_resolve_like_rosnode(monkeypatch: pytest.MonkeyPatch) -> None:
    """Relative names resolve in ROS_NAMESPACE; global names stay; a trailing slash is dropped."""
    monkeypatch.delenv("ROS_NAMESPACE", raising=False)
    assert resolve_node_name("talker") == "/talker"
    assert resolve_node_name("/a/b/") == "/a/b"
    monkeypatch.setenv("ROS_NAMESPACE", "/robot")
    assert resolve_node_name("talker") == "/robot/talker"
    assert resolve_node_name("/talker") == "/talker"
