"""Console lines: ROSCONSOLE_FORMAT tokens, streams, roscpp's colors only where wanted."""

from __future__ import annotations

import io
import os
import pty
import re

import pytest

from rostui.core.log import (
    COLORS, DEFAULT_FORMAT, RESET, Console, ConsoleLogger, Level, LogRecord, format_line,
    stamp_text, wall_time_text,
)

STAMP = 1_795_347_590_920_084_394


def record(level: Level = Level.INFO, message: str = "info 2") -> LogRecord:
    return LogRecord(level, message, "/cpplog", "ros.pkg", "count.py", 17, "Counter.tick", STAMP)


def plain(**kwargs: object) -> tuple[Console, io.StringIO, io.StringIO]:
    out, err = io.StringIO(), io.StringIO()
    return Console(stdout=out, stderr=err, env={}, **kwargs), out, err  # type: ignore[arg-type]


def test_default_format_matches_roscpp() -> None:
    console, out, _ = plain()
    assert console.fmt == DEFAULT_FORMAT
    console.write(record())
    # roscpp printed: "[ INFO] [1795347590.920084394]: info 2"
    assert out.getvalue() == "[ INFO] [1795347590.920084394]: info 2\n"


def test_every_token() -> None:
    fmt = "${severity}|${time}|${message}|${node}|${file}|${line}|${function}|${logger}|${thread}|${bogus}"
    console, out, _ = plain(fmt=fmt)
    console.write(record(Level.DEBUG, "m"))
    fields = out.getvalue().rstrip("\n").split("|")
    assert fields[:8] == ["DEBUG", "1795347590.920084394", "m", "/cpplog", "count.py", "17",
                          "Counter.tick", "ros.pkg"]
    assert fields[8].isdigit() and fields[9] == "${bogus}"


def test_format_from_environment() -> None:
    console = Console(env={"ROSCONSOLE_FORMAT": "${node}: ${message}"}, stdout=io.StringIO())
    assert console.format(record()) == "/cpplog: info 2"


def test_walltime_token_is_now() -> None:
    console, out, _ = plain(fmt="${walltime}")
    console.write(record())
    assert re.fullmatch(r"\d{10}\.\d{9}\n", out.getvalue())
    assert out.getvalue() != stamp_text(STAMP) + "\n"


@pytest.mark.parametrize("level,to_err", [(Level.DEBUG, False), (Level.INFO, False), (Level.WARN, True),
                                          (Level.ERROR, True), (Level.FATAL, True)])
def test_levels_choose_the_stream(level: Level, to_err: bool) -> None:
    console, out, err = plain()
    console.write(record(level, "x"))
    assert (err if to_err else out).getvalue().endswith(": x\n")
    assert (out if to_err else err).getvalue() == ""


def test_default_streams_follow_sys(capsys: pytest.CaptureFixture[str]) -> None:
    console = Console(env={})
    console.write(record(Level.INFO, "to out"))
    console.write(record(Level.ERROR, "to err"))
    captured = capsys.readouterr()
    assert captured.out == "[ INFO] [1795347590.920084394]: to out\n"
    assert captured.err == "[ERROR] [1795347590.920084394]: to err\n"


def test_roscpp_colors_when_forced() -> None:
    console, out, err = plain(color=True)
    for level in Level:
        console.write(record(level, level.name))
    # the escape codes real roscpp wrapped its lines in
    assert out.getvalue().splitlines() == [
        "\033[32m[DEBUG] [1795347590.920084394]: DEBUG\033[0m",
        "\033[0m[ INFO] [1795347590.920084394]: INFO\033[0m",
    ]
    assert err.getvalue().splitlines() == [
        "\033[33m[ WARN] [1795347590.920084394]: WARN\033[0m",
        "\033[31m[ERROR] [1795347590.920084394]: ERROR\033[0m",
        "\033[31m[FATAL] [1795347590.920084394]: FATAL\033[0m",
    ]
    assert COLORS[Level.WARN] == "\033[33m" and RESET == "\033[0m"


@pytest.fixture
def tty() -> io.TextIOWrapper:
    leader, follower = pty.openpty()
    stream = os.fdopen(follower, "w")
    yield stream
    stream.close()
    os.close(leader)


def test_tty_gets_color_pipe_does_not(tty: io.TextIOWrapper) -> None:
    pipe = io.StringIO()
    assert Console(stdout=tty, env={})._colored(tty) is True
    assert Console(stdout=pipe, env={})._colored(pipe) is False


def test_no_color_wins_on_a_tty(tty: io.TextIOWrapper) -> None:
    assert Console(stdout=tty, env={"NO_COLOR": "1"})._colored(tty) is False
    assert Console(stdout=tty, env={"NO_COLOR": ""})._colored(tty) is True


def test_force_color_env_colors_a_pipe_even_with_no_color() -> None:
    out = io.StringIO()
    console = Console(stdout=out, env={"ROSTUI_FORCE_COLOR": "1", "NO_COLOR": "1"})
    console.write(record(Level.DEBUG, "d"))
    assert out.getvalue().startswith("\033[32m[DEBUG]") and out.getvalue().endswith("\033[0m\n")


class Broken(io.StringIO):
    def write(self, text: str) -> int:
        raise BrokenPipeError(32, "Broken pipe")


class Counting(io.StringIO):
    flushes = 0

    def flush(self) -> None:
        self.flushes += 1
        super().flush()


def test_broken_or_closed_streams_never_raise() -> None:
    Console(stdout=Broken(), env={}).write(record())
    closed = io.StringIO()
    closed.close()
    Console(stdout=closed, stderr=closed, env={}).write(record(Level.ERROR))


def test_each_line_is_flushed() -> None:
    out = Counting()
    console = Console(stdout=out, env={})
    console.write(record())
    console.write(record())
    assert out.flushes == 2


def test_multiline_message_is_one_record() -> None:
    console, out, _ = plain(fmt="${message}")
    console.write(record(message="a\nb"))
    assert out.getvalue() == "a\nb\n"


def test_legacy_helpers_still_work(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROSCONSOLE_FORMAT", raising=False)
    monkeypatch.delenv("ROSTUI_FORCE_COLOR", raising=False)
    assert re.fullmatch(r"\[ WARN\] \[\d+\.\d{9}\]: hi", format_line(Level.WARN, "hi"))
    assert format_line(Level.INFO, "m", "/n", fmt="${node} ${message}") == "/n m"
    assert wall_time_text(1.5) == "1.500000000"
    logger = ConsoleLogger("/n", Level.WARN)
    logger.info("hidden")
    logger.warn("shown")
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.endswith(": shown\n")
