"""NodeLog: level gate before formatting, once/throttle per call site, sinks, call-site fields."""

from __future__ import annotations

import io

import pytest

from rostui.core.log import Console, Level, LoggerTree, LogRecord, NodeLog, package_logger


class FakeClock:
    """A settable nanosecond clock."""

    def __init__(self, start: int = 1_000 * 1_000_000_000) -> None:
        self.now = start

    def __call__(self) -> int:
        return self.now

    def advance(self, seconds: float) -> None:
        self.now += int(seconds * 1_000_000_000)


class Explosive:
    """Fails loudly if anything tries to format it."""

    def __mod__(self, other: object) -> str:
        raise AssertionError("formatted a disabled message")

    def __str__(self) -> str:
        raise AssertionError("stringified a disabled message")

    __repr__ = __str__


@pytest.fixture
def clock() -> FakeClock:
    return FakeClock()


@pytest.fixture
def records() -> list[LogRecord]:
    return []


@pytest.fixture
def log(clock: FakeClock, records: list[LogRecord]) -> NodeLog:
    node_log = NodeLog("/count", "ros.agitr", LoggerTree(), None, clock=clock)
    node_log.add_sink(records.append)
    return node_log


def test_default_level_is_info(log: NodeLog, records: list[LogRecord]) -> None:
    log.debug("no")
    log.info("yes %d", 1)
    log.warn("w")
    log.error("e")
    log.fatal("f")
    assert [(r.level, r.message) for r in records] == [
        (Level.INFO, "yes 1"), (Level.WARN, "w"), (Level.ERROR, "e"), (Level.FATAL, "f")]
    assert log.level is Level.INFO


def test_disabled_calls_never_format(log: NodeLog, records: list[LogRecord]) -> None:
    bomb = Explosive()
    log.debug(bomb)
    log.debug("%s", bomb)
    log.debug(bomb, bomb, logger="sub")
    log.log(Level.DEBUG, bomb, bomb)
    log.debug_once(bomb, bomb)
    log.debug_throttle(1.0, bomb, bomb)
    log.log_once(Level.DEBUG, bomb)
    log.log_throttle(1.0, Level.DEBUG, bomb)
    log.tree.set_level("ros", "fatal")
    log.error(bomb, bomb)
    log.warn_once(bomb)
    log.info_throttle(0.1, bomb)
    assert records == []


def test_level_change_in_tree_takes_effect_immediately(log: NodeLog, records: list[LogRecord]) -> None:
    log.debug("before")
    log.tree.set_level("ros.agitr", "debug")
    log.debug("after %s", "set")
    log.tree.set_level("ros", "error")  # the node's own setting still wins
    log.debug("still")
    log.tree.clear_level("ros.agitr")
    log.warn("now hidden")
    log.error("shown")
    assert [r.message for r in records] == ["after set", "still", "shown"]


def test_named_child_logger_inherits_and_can_differ(log: NodeLog, records: list[LogRecord]) -> None:
    log.debug("hidden", logger="sub")
    log.set_level("debug", logger="sub")
    log.debug("shown", logger="sub")
    log.debug("default still info")
    assert [(r.logger, r.message) for r in records] == [("ros.agitr.sub", "shown")]
    assert ("ros.agitr.sub", Level.DEBUG) in log.tree.loggers()
    assert log.enabled(Level.DEBUG, "sub") and not log.enabled(Level.DEBUG)


def test_record_carries_call_site_and_clock(log: NodeLog, records: list[LogRecord], clock: FakeClock) -> None:
    class Counter:
        def tick(self) -> None:
            log.info("tick")

    Counter().tick()
    (rec,) = records
    assert rec.file == "test_log_nodelog.py"
    assert rec.function == "Counter.tick"
    assert rec.node == "/count" and rec.logger == "ros.agitr"
    assert rec.stamp == clock.now and rec.secs == 1000 and rec.nsecs == 0
    import inspect
    source = inspect.getsource(test_record_carries_call_site_and_clock).splitlines()
    offset = next(i for i, text in enumerate(source) if 'log.info("tick")' in text)
    assert rec.line == test_record_carries_call_site_and_clock.__code__.co_firstlineno + offset


def test_stacklevel_points_at_the_wrappers_caller(log: NodeLog, records: list[LogRecord]) -> None:
    def loginfo(msg: str, *args: object) -> None:
        log.info(msg, *args, stacklevel=2)

    def user_code() -> None:
        loginfo("from user %d", 5)

    user_code()
    assert records[0].function == "user_code" and records[0].message == "from user 5"


def test_once_is_per_call_site(log: NodeLog, records: list[LogRecord]) -> None:
    for i in range(5):
        log.info_once("site A %d", i)
        log.info_once("site B %d", i)
    assert [r.message for r in records] == ["site A 0", "site B 0"]
    assert records[0].line != records[1].line


def test_once_is_not_used_up_while_disabled(log: NodeLog, records: list[LogRecord]) -> None:
    for i in range(3):
        if i == 1:
            log.tree.set_level("ros.agitr", "debug")
        log.debug_once("dbg %d", i)
    assert [r.message for r in records] == ["dbg 1"]


def test_all_once_variants(log: NodeLog, records: list[LogRecord]) -> None:
    log.set_level(Level.DEBUG)
    for _ in range(3):
        log.debug_once("d")
        log.info_once("i")
        log.warn_once("w")
        log.error_once("e")
        log.fatal_once("f")
        log.log_once(Level.INFO, "l")
    assert [r.message for r in records] == ["d", "i", "w", "e", "f", "l"]


def test_throttle_per_call_site_with_injected_clock(log: NodeLog, records: list[LogRecord],
                                                     clock: FakeClock) -> None:
    seen: list[tuple[float, str]] = []
    elapsed = 0.0
    for _ in range(25):  # 2.5 s of ticks every 0.1 s
        log.info_throttle(1.0, "slow")
        log.warn_throttle(0.5, "fast")
        clock.advance(0.1)
        elapsed += 0.1
    seen = [r.message for r in records]
    assert seen.count("slow") == 3  # t = 0, 1.0, 2.0
    assert seen.count("fast") == 5  # t = 0, 0.5, 1.0, 1.5, 2.0
    stamps = [r.stamp for r in records if r.message == "slow"]
    assert [b - a for a, b in zip(stamps, stamps[1:])] == [1_000_000_000, 1_000_000_000]


def test_throttle_rearms_when_clock_goes_back(log: NodeLog, records: list[LogRecord], clock: FakeClock) -> None:
    for step in (0.0, 0.2, -5.0):
        clock.advance(step)
        log.error_throttle(1.0, "x")
    assert len(records) == 2


def test_all_throttle_variants(log: NodeLog, records: list[LogRecord], clock: FakeClock) -> None:
    log.set_level("debug")
    for _ in range(2):
        log.debug_throttle(1, "d")
        log.info_throttle(1, "i")
        log.warn_throttle(1, "w")
        log.error_throttle(1, "e")
        log.fatal_throttle(1, "f")
        log.log_throttle(1, Level.WARN, "l")
    assert [r.message for r in records] == ["d", "i", "w", "e", "f", "l"]


def test_console_and_sinks(clock: FakeClock) -> None:
    out, err = io.StringIO(), io.StringIO()
    log = NodeLog("/n", package_logger("agitr"), console=Console(stdout=out, stderr=err, env={}), clock=clock)
    got: list[str] = []

    def sink(record: LogRecord) -> None:
        got.append(record.message)

    log.add_sink(sink)
    log.info("one")
    log.remove_sink(sink)
    log.error("two")
    assert got == ["one"]
    assert out.getvalue() == "[ INFO] [1000.000000000]: one\n"
    assert err.getvalue() == "[ERROR] [1000.000000000]: two\n"
    assert log.default_logger == "ros.agitr" and package_logger(None) == "ros.unknown_package"


def test_a_failing_sink_is_reported_once_and_does_not_break_logging(
        log: NodeLog, records: list[LogRecord], capsys: pytest.CaptureFixture[str]) -> None:
    def bad(record: LogRecord) -> None:
        raise OSError("disk full")

    log.add_sink(bad)
    log.info("a")
    log.info("b")
    log.add_sink(records.append)
    assert [r.message for r in records] == ["a", "b"]
    assert capsys.readouterr().err.count("disk full") == 1


def test_non_string_message(log: NodeLog, records: list[LogRecord]) -> None:
    log.info(42)
    log.info("%s and %s", "a", "b")
    assert [r.message for r in records] == ["42", "a and b"]


def test_close_stops_following_the_tree(log: NodeLog, records: list[LogRecord]) -> None:
    log.close()
    log.tree.set_level("ros", "fatal")
    assert log.level is Level.INFO
