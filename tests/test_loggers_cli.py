"""`rostui loggers NODE` and `rostui loggers NODE LOGGER LEVEL`: the app's calls without the app, and bad input.

Run as real processes against rostui, rospy and roscpp nodes under
`rostui core` and a real roscore.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from cli_helpers import rostui
from conftest import master_port
from interop_helpers import roscpp_peer_bin, rospy_peer, run_tool, spawn, wait_until  # noqa: F401  (fixtures)
from live_helpers import Program


def listed(node: str, env: dict[str, str]) -> str:
    """`rostui loggers NODE` once the node serves get_loggers; its stdout."""
    results: list[Any] = []

    def ok() -> bool:
        results[:] = [rostui(["loggers", node], env)]
        return results[0].returncode == 0
    wait_until(ok, f"`rostui loggers {node}` to succeed")
    return results[0].stdout


def test_list_and_set_a_rostui_node(any_master: str, ros_env: dict[str, str], tmp_path: Path) -> None:
    """The book's count_and_log: two loggers listed, ros.agitr set to DEBUG (relative name, lower case)."""
    count = Program(ros_env, tmp_path, "agitr", "count")
    try:
        assert listed("/count_and_log", ros_env) == "ros        INFO\nros.agitr  INFO\n"
        result = rostui(["loggers", "count_and_log", "ros.agitr", "debug"], ros_env)
        assert (result.returncode, result.stdout, result.stderr) == (0, "", "")
        assert listed("/count_and_log", ros_env) == "ros        INFO\nros.agitr  DEBUG\n"
    finally:
        count.stop()


def test_list_and_set_a_rospy_node(any_master: str, rospy_available: None, spawn: Any,
                                   ros_env: dict[str, str]) -> None:
    """rospy answers INFO (upper case) for its Python loggers; rosout set to DEBUG is read back as DEBUG."""
    spawn(rospy_peer("rospy_debug_logger.py"), label="rospy debug logger").wait_for(r"^ready$")
    before = listed("/rospy_debug_logger", ros_env)
    assert re.search(r"^rosout +INFO$", before, re.MULTILINE) and re.search(r"^rospy +INFO$", before, re.MULTILINE)
    result = rostui(["loggers", "/rospy_debug_logger", "rosout", "DEBUG"], ros_env)
    assert result.returncode == 0, result.stderr
    assert re.search(r"^rosout +DEBUG$", listed("/rospy_debug_logger", ros_env), re.MULTILINE)


def test_set_a_roscpp_level_then_rosservice_reads_it(any_master: str, roscpp_peer_bin: Path, spawn: Any,
                                                     ros_env: dict[str, str]) -> None:
    """roscpp takes rostui's upper-case level: real rosservice then reads ros.roscpp at warn."""
    spawn([str(roscpp_peer_bin), "__name:=cpp_set", "serve", "/cpp_set_toggle"], label="roscpp peer")
    run_tool(["rosservice", "call", "--wait", "/cpp_set/set_logger_level", "ros.roscpp", "INFO"], ros_env)
    result = rostui(["loggers", "/cpp_set", "ros.roscpp", "warn"], ros_env)
    assert result.returncode == 0, result.stderr
    out = run_tool(["rosservice", "call", "/cpp_set/get_loggers"], ros_env).stdout
    assert re.search(r'name: "ros\.roscpp"\s+level: "warn"', out), out


def test_bad_input_one_line_and_nonzero(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """Unknown level, missing level, unknown node, bad timeout: one ERROR line each, exit 1."""
    cases = [
        (["loggers", "/rosout", "ros", "loud"],
         "ERROR: unknown log level 'loud' (use debug, info, warn, error or fatal)"),
        (["loggers", "/rosout", "ros"],
         "ERROR: rostui loggers /rosout ros: give a LEVEL too (DEBUG, INFO, WARN, ERROR or FATAL)"),
        (["loggers", "/nope"], "ERROR: /nope/get_loggers is not registered with the master: node /nope is not running"),
        (["loggers", "--timeout", "0", "/rosout"], "ERROR: --timeout must be positive, got 0"),
    ]
    for args, line in cases:
        result = rostui(args, ros_env)
        assert (result.returncode, result.stdout, result.stderr) == (1, "", line + "\n"), args


def test_no_master_and_no_terminal(ros_env: dict[str, str]) -> None:
    """No master: one line naming its URI.  The app without a terminal: one line saying what to use."""
    result = rostui(["loggers", "/rosout"], ros_env)
    port = master_port(ros_env)
    assert (result.returncode, result.stderr) == (1, f"ERROR: Unable to communicate with master at http://127.0.0.1:{port}/\n")
    result = rostui(["loggers"], ros_env)
    assert result.returncode == 1
    assert result.stderr.startswith("ERROR: rostui loggers draws in a terminal"), result.stderr
