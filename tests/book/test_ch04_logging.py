"""Chapter 4, Log messages: count's lines at each level on the console, on /rosout, in rqt_console
(``rostui console``), in rosout.log, and the logger level set from the command line and rqt_logger_level
(``rostui loggers``).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from book_helpers import Desk, cli, desk, dot_edges, lines, log_lines, ok, poll, start_core

__all__ = ["desk"]

pytestmark = pytest.mark.timeout(300)  # one chapter, start to end, on a busy machine

COUNTED = r"^\[DEBUG\] \[\d+\.\d+\]: Counted to \d+$"


def test_count_logs_to_console_rosout_console_app_and_rosout_log(desk: Desk, tmp_path: Path) -> None:
    env = desk.env
    start_core(desk)

    # 4.4.1: DEBUG and INFO go to standard output, WARN, ERROR and FATAL to standard error.
    split = desk.terminal("split")
    split.run("rostui run agitr count > out.log")
    split.wait_for(r"^\[FATAL\] \[\d+\.\d+\]: 20 is divisible by 20\.$")
    assert split.interrupt() == 0
    screen = split.screen(200)
    assert log_lines(screen, "WARN")[:2] == ["5 is divisible by 5.", "10 is divisible by 5."]
    assert log_lines(screen, "ERROR")[:1] == ["10 is divisible by 10."] and log_lines(screen, "INFO") == []
    stdout = (tmp_path / "out.log").read_text()
    assert log_lines(stdout, "INFO")[:3] == ["3 is divisible by 3.", "6 is divisible by 3.", "9 is divisible by 3."]
    assert log_lines(stdout, "WARN") == [] and "Counted to" not in stdout  # DEBUG is off by default

    # 4.3: messages logged once (Listing 4.4): each level appears one time, however long the loop runs.
    split.run("rostui run agitr once")
    split.wait_for(r"^\[FATAL\] \[\d+\.\d+\]: This appears only once\.$")
    poll(lambda: "/log_once" in lines(ok("node list", env)), "log_once still running")
    assert split.interrupt() == 0
    for level in ("INFO", "WARN", "ERROR", "FATAL"):
        assert log_lines(split.screen(200), level).count("This appears only once.") == 1, level

    # Formatting console messages with ROSCONSOLE_FORMAT.
    split.run("ROSCONSOLE_FORMAT='[${severity}] [${node}]: ${message}' rostui run agitr hello")
    assert split.exit_status() == 0
    split.wait_for(r"^\[ INFO\] \[/hello_ros\]: Hello, ROS!$")

    # 4.4.2: messages on /rosout, and rqt_console (`rostui console`) on /rosout_agg.
    count = desk.terminal("count")
    count.run("rostui run agitr count")
    count.wait_for(r"is divisible by 3\.$")
    echo = desk.terminal("echo")
    echo.run("rostui topic echo /rosout")
    echo.wait_for(r'^level: 4\nname: "/count_and_log"\nmsg: "\d+ is divisible by 5\."\nfile: ".*"\nfunction: ".*"\n'
                  r"line: \d+\ntopics: \n  - /rosout\n---$")
    echo.interrupt()
    console = desk.terminal("console")
    console.run("rostui console")
    console.wait_for(r"\d+ is divisible by 20\.\s+FATAL\s+/count_and_log\s")
    console.wait_for(r"\d+ is divisible by 3\.\s+INFO\s+/count_and_log\s")
    names = lines(ok("node list", env))
    tool = next(name for name in names if name not in ("/count_and_log", "/rosout"))
    graph = dot_edges(ok("graph --dot --show-debug", env))
    assert {("/count_and_log", "/rosout", "/rosout"), ("/rosout", tool, "/rosout_agg")} <= graph
    console.keys("q")
    assert console.exit_status() == 0

    # 4.4.3: rosout.log under ROS_HOME/log/run_id, and rosclean.
    run_id = ok("param get /run_id", env).strip()
    assert re.fullmatch(r"[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}", run_id)
    rosout_log = Path(env["ROS_HOME"]) / "log" / run_id / "rosout.log"
    poll(lambda: rosout_log.exists() and "20 is divisible by 20." in rosout_log.read_text(), "count's lines in rosout.log")
    text = rosout_log.read_text()
    for level, message in (("INFO", "3 is divisible by 3."), ("WARN", "5 is divisible by 5."),
                           ("ERROR", "10 is divisible by 10."), ("FATAL", "20 is divisible by 20.")):
        assert re.search(rf"^\d+\.\d+ {level} /count_and_log \[.*\] \[topics: .*\] {re.escape(message)}$", text,
                         re.MULTILINE), level
    assert re.fullmatch(r"\d+(\.\d+)?[KMG]? ROS node logs\n", ok("clean check", env))

    # 4.5: the logger level from the command line (rosservice call ... set_logger_level) enables DEBUG.
    call = cli("service call /count_and_log/set_logger_level ros.agitr DEBUG", env)
    assert call.returncode == 0 and call.stdout == "\n", call
    count.wait_for(COUNTED)
    assert re.search(r"^ros\.agitr\s+DEBUG$", ok("loggers /count_and_log", env), re.MULTILINE)
    wrong = cli("service call /count_and_log/set_logger_level ros.agitr LOUD", env)
    assert wrong.returncode != 0 and wrong.stderr.startswith("ERROR: service [/count_and_log/set_logger_level] "
                                                             "responded with an error"), wrong

    # rqt_logger_level: `rostui loggers`, the node on the left, its loggers in the middle, i sets INFO.
    loggers = desk.terminal("loggers")
    loggers.run("rostui loggers")
    loggers.wait_for(r"2 nodes serve")
    loggers.wait_for(r"Loggers · /count_and_log")  # the first node is selected at start
    loggers.wait_for(r"ros\.agitr")
    loggers.keys("i")
    loggers.wait_for(r"ros\.agitr set to")
    poll(lambda: re.search(r"^ros\.agitr\s+INFO$", ok("loggers /count_and_log", env), re.MULTILINE) is not None,
         "ros.agitr back at INFO")
    loggers.keys("q")
    assert loggers.exit_status() == 0
    assert count.interrupt() == 0
