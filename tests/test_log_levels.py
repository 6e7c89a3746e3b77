"""Log levels and the hierarchical logger tree."""

from __future__ import annotations

import threading

import pytest

from rostui.core.log import Level, LoggerTree


def test_level_values_are_rosgraph_log_bytes() -> None:
    assert [int(level) for level in Level] == [1, 2, 4, 8, 16]


def test_labels_and_texts() -> None:
    assert [level.label for level in Level] == ["DEBUG", " INFO", " WARN", "ERROR", "FATAL"]
    assert [level.text for level in Level] == ["debug", "info", "warn", "error", "fatal"]


@pytest.mark.parametrize("text,level", [
    ("debug", Level.DEBUG), ("INFO", Level.INFO), ("Warn", Level.WARN), ("warning", Level.WARN),
    (" error ", Level.ERROR), ("FATAL", Level.FATAL), (4, Level.WARN), (Level.ERROR, Level.ERROR),
])
def test_parse(text: object, level: Level) -> None:
    assert Level.parse(text) is level  # type: ignore[arg-type]


@pytest.mark.parametrize("bad", ["verbose", "", "3", 3, 0])
def test_parse_rejects_unknown_levels_clearly(bad: object) -> None:
    with pytest.raises(ValueError, match="unknown log level"):
        Level.parse(bad)  # type: ignore[arg-type]


def test_root_defaults_to_info_and_children_inherit() -> None:
    tree = LoggerTree()
    assert tree.effective_level("ros") is Level.INFO
    assert tree.effective_level("ros.pkg.sub.deeper") is Level.INFO
    tree.set_level("ros.pkg", "debug")
    assert tree.effective_level("ros.pkg") is Level.DEBUG
    assert tree.effective_level("ros.pkg.sub.deeper") is Level.DEBUG
    assert tree.effective_level("ros.pkg2") is Level.INFO  # a prefix is not a parent
    tree.set_level("ros.pkg.sub", Level.ERROR)
    assert tree.effective_level("ros.pkg.sub.deeper") is Level.ERROR
    tree.set_level("ros", Level.WARN)
    assert tree.effective_level("ros.other") is Level.WARN
    assert tree.effective_level("ros.pkg") is Level.DEBUG
    tree.clear_level("ros.pkg")
    assert tree.effective_level("ros.pkg") is Level.WARN
    assert tree.own_level("ros.pkg") is None


def test_loggers_lists_known_names_sorted_with_effective_levels() -> None:
    tree = LoggerTree()
    tree.register("ros.talker")
    tree.set_level("ros.roscpp.superdebug", "warn")
    tree.set_level("ros.roscpp", "debug")
    assert tree.loggers() == [
        ("ros", Level.INFO), ("ros.roscpp", Level.DEBUG),
        ("ros.roscpp.superdebug", Level.WARN), ("ros.talker", Level.INFO),
    ]
    # what roscpp's ~get_loggers answers with
    assert [(name, level.text) for name, level in tree.loggers()][0] == ("ros", "info")


def test_bad_level_or_name_changes_nothing() -> None:
    tree = LoggerTree()
    calls: list[int] = []
    tree.add_listener(lambda: calls.append(1))
    with pytest.raises(ValueError, match="unknown log level 'loud'"):
        tree.set_level("ros.pkg", "loud")
    with pytest.raises(ValueError, match="invalid logger name"):
        tree.set_level("ros..pkg", "info")
    assert calls == [] and tree.loggers() == [("ros", Level.INFO)]


def test_listeners_hear_every_change_until_removed() -> None:
    tree = LoggerTree()
    calls: list[Level] = []

    def listener() -> None:
        calls.append(tree.effective_level("ros.pkg"))

    tree.add_listener(listener)
    tree.set_level("ros.pkg", "error")
    tree.set_level("ros", "debug")
    tree.remove_listener(listener)
    tree.set_level("ros.pkg", "info")
    assert calls == [Level.ERROR, Level.ERROR]


def test_concurrent_changes_are_safe() -> None:
    tree = LoggerTree()

    def work(index: int) -> None:
        for i in range(300):
            tree.set_level(f"ros.p{index}.s{i % 7}", Level.DEBUG if i % 2 else Level.WARN)
            tree.effective_level(f"ros.p{index}.s{i % 7}.x")
            tree.loggers()

    threads = [threading.Thread(target=work, args=(n,)) for n in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(tree.loggers()) == 1 + 6 * 7
