"""Chapter 4 end to end: console, /rosout, rosout.log and logger levels, with real ROS peers."""

from __future__ import annotations

import asyncio
import re
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

from rostui.core.msg import get_message_class
from rostui.core.node import AsyncNode

from conftest import SYSTEM_PYTHON, stop_process
from interop_helpers import run_tool
from test_node import run, until

Log = get_message_class("rosgraph_msgs/Log")
NAMES = {1: "DEBUG", 2: "INFO", 4: "WARN", 8: "ERROR", 16: "FATAL"}

COUNT_SCRIPT = textwrap.dedent("""
    # The book's count_and_log listing, against rostui's client API.
    from rostui import client as ros
    ros.init_node("count_and_log")
    rate = ros.Rate(20)
    i = 1
    while not ros.is_shutdown() and i <= 20:
        ros.logdebug("Counted to %d", i)
        if i % 3 == 0:
            ros.loginfo("%d is divisible by 3.", i)
        if i % 5 == 0:
            ros.logwarn("%d is divisible by 5.", i)
        if i % 10 == 0:
            ros.logerr("%d is divisible by 10.", i)
        if i % 20 == 0:
            ros.logfatal("%d is divisible by 20.", i)
        i += 1
        rate.sleep()
""")


def expected_count_messages() -> list[tuple[str, str]]:
    """(level, text) the count listing emits at the default INFO level, in order."""
    out = []
    for i in range(1, 21):
        for divisor, level in ((3, "INFO"), (5, "WARN"), (10, "ERROR"), (20, "FATAL")):
            if i % divisor == 0:
                out.append((level, f"{i} is divisible by {divisor}."))
    return out


CONSOLE_LINE = re.compile(r"^\[ ?(DEBUG|INFO|WARN|ERROR|FATAL)\] \[\d+\.\d{9}\]: (.*)$")


def console_messages(text: str) -> list[tuple[str, str]]:
    """(level, text) of every console line in ROS's default format."""
    return [m.groups() for m in map(CONSOLE_LINE.match, text.splitlines()) if m]  # type: ignore[misc]


def rosout_log(env: dict[str, str]) -> Path:
    """The current run's rosout.log."""
    return Path(env["ROS_HOME"]) / "log" / "latest" / "rosout.log"


def rosout_log_messages(env: dict[str, str], node: str) -> list[tuple[str, str]]:
    """(level, text) of the lines rosout wrote for one node."""
    pattern = re.compile(r"^\d+\.\d{9} (\w+) " + re.escape(node) + r" \[[^\]]*\] \[topics: [^\]]*\] (.*)$")
    text = rosout_log(env).read_text()
    return [m.groups() for m in map(pattern.match, text.splitlines()) if m]  # type: ignore[misc]


def test_count_listing_reaches_console_rosout_agg_and_rosout_log(rostui_core: Any, ros_env: dict[str, str]) -> None:
    expected = expected_count_messages()

    async def scenario() -> list[Any]:
        node = await AsyncNode("log_watcher").start()
        seen: list[Any] = []
        agg_sub = await node.subscribe("/rosout_agg", Log,
                                       lambda m: seen.append(m) if m.name == "/count_and_log" else None)
        await until(lambda: agg_sub.get_num_connections() > 0)  # else the first lines can pass before it connects
        proc = await asyncio.create_subprocess_exec(sys.executable, "-c", COUNT_SCRIPT, env=ros_env,
                                                    stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE)
        out, err = await proc.communicate()
        await until(lambda: len(seen) >= len(expected))
        await node.shutdown()
        return [out.decode(), err.decode(), seen]

    stdout, stderr, agg = run(scenario(), timeout=60)
    assert console_messages(stdout) == [m for m in expected if m[0] == "INFO"]
    assert console_messages(stderr) == [m for m in expected if m[0] != "INFO"]
    assert [(NAMES[m.level], m.msg) for m in agg] == expected
    first = agg[0]
    assert (first.file, first.function, first.line) == ("<string>", "<module>", 10)
    assert "/rosout" in first.topics and first.header.stamp.secs > 0
    assert [m.header.seq for m in agg] == list(range(agg[0].header.seq, agg[0].header.seq + len(agg)))
    assert rosout_log_messages(ros_env, "/count_and_log") == expected


LEVELS_SCRIPT = textwrap.dedent("""
    from rostui import client as ros
    ros.init_node("chatty")
    rate = ros.Rate(20)
    i = 0
    while not ros.is_shutdown():
        ros.logdebug("debug tick %d", i)
        ros.loginfo_throttle(60, "first info only")
        i += 1
        rate.sleep()
""")


def wait_line(proc: subprocess.Popen, pattern: str) -> str:
    """Read stdout lines until one matches; fail if the process ends first."""
    assert proc.stdout is not None
    for line in proc.stdout:
        if re.search(pattern, line):
            return line
    raise AssertionError(f"no line matching {pattern!r}")


def test_debug_appears_only_after_level_set_via_real_rosservice(rostui_core: Any, ros_env: dict[str, str]) -> None:
    proc = subprocess.Popen([sys.executable, "-c", LEVELS_SCRIPT], env=ros_env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    try:
        wait_line(proc, r"first info only")
        loggers = run_tool(["rosservice", "call", "/chatty/get_loggers"], ros_env).stdout
        assert 'name: "ros.unknown_package"' in loggers and 'level: "info"' in loggers
        bad = run_tool(["rosservice", "call", "/chatty/set_logger_level", "ros", "loud"], ros_env, check=False)
        assert bad.returncode != 0
        assert "unknown log level 'loud'" in bad.stdout + bad.stderr
        run_tool(["rosservice", "call", "/chatty/set_logger_level", "ros.unknown_package", "debug"], ros_env)
        line = wait_line(proc, r"debug tick \d+")
        assert CONSOLE_LINE.match(line.rstrip("\n")).group(1) == "DEBUG"  # type: ignore[union-attr]
        loggers = run_tool(["rosservice", "call", "/chatty/get_loggers"], ros_env).stdout
        assert 'level: "debug"' in loggers
    finally:
        stop_process(proc)


CLIENT_SETS_LEVEL = textwrap.dedent("""
    import sys
    from rostui import client as ros
    ros.init_node("level_setter", anonymous=True)
    target, logger, level = sys.argv[1:4]
    ros.set_logger_level(target, logger, level)
    print(dict(ros.get_loggers(target))[logger])
""")


def test_rostui_client_sets_levels_on_rostui_and_rospy_nodes(rostui_core: Any, ros_env: dict[str, str],
                                                            rospy_available: None, tmp_path: Path) -> None:
    rospy_script = tmp_path / "rospy_chatty.py"
    rospy_script.write_text(textwrap.dedent("""
        import rospy
        rospy.init_node("rospy_chatty")
        rate = rospy.Rate(20)
        i = 0
        while not rospy.is_shutdown():
            rospy.logdebug("rospy debug %d", i)
            rospy.loginfo_once("rospy up")
            i += 1
            rate.sleep()
    """))
    ours = subprocess.Popen([sys.executable, "-c", LEVELS_SCRIPT], env=ros_env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    theirs = subprocess.Popen([SYSTEM_PYTHON, str(rospy_script)], env=ros_env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
    try:
        wait_line(ours, r"first info only")
        wait_line(theirs, r"rospy up")
        for target, logger, shown in (("/chatty", "ros", "debug"), ("/rospy_chatty", "rosout", "DEBUG")):
            done = subprocess.run([sys.executable, "-c", CLIENT_SETS_LEVEL, target, logger, "debug"],
                                  env=ros_env, capture_output=True, text=True, timeout=30)
            assert done.returncode == 0, done.stderr
            assert done.stdout.strip() == shown
        wait_line(ours, r"\[DEBUG\].*debug tick")
        wait_line(theirs, r"rospy debug \d+")
    finally:
        stop_process(ours)
        stop_process(theirs)


def test_real_rostopic_echo_shows_a_rostui_log_message(rostui_core: Any, ros_env: dict[str, str]) -> None:
    proc = subprocess.Popen([sys.executable, "-c", LEVELS_SCRIPT.replace("60,", "0.2,")], env=ros_env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        out = run_tool(["rostopic", "echo", "-n", "1", "/rosout_agg"], ros_env).stdout
    finally:
        stop_process(proc)
    fields = dict(re.findall(r'^(\w+): (.+)$', out, flags=re.M))
    assert fields["level"] == "2"
    assert fields["name"] == '"/chatty"'
    assert fields["msg"] == '"first info only"'
    assert fields["file"] == '"<string>"' and fields["function"] == '"<module>"' and fields["line"] == "8"
    assert re.search(r"^\s+secs: [1-9]\d*$", out, flags=re.M)
    assert re.search(r"^topics: \n\s+- /rosout$", out, flags=re.M)


def test_rospy_node_messages_land_in_rostui_rosout_log(rostui_core: Any, ros_env: dict[str, str],
                                                       rospy_available: None, tmp_path: Path) -> None:
    script = tmp_path / "rospy_logger.py"
    script.write_text(textwrap.dedent("""
        import rospy
        rospy.init_node("rospy_logger")
        rospy.sleep(1.0)
        rospy.logwarn("careful %d", 1)
        rospy.logerr("broken %d", 2)
        rospy.sleep(1.0)
    """))
    subprocess.run([SYSTEM_PYTHON, str(script)], env=ros_env, timeout=60, capture_output=True)

    async def settle() -> None:
        await until(lambda: len(rosout_log_messages(ros_env, "/rospy_logger")) >= 2)
    run(settle())
    assert rosout_log_messages(ros_env, "/rospy_logger")[-2:] == [("WARN", "careful 1"), ("ERROR", "broken 2")]


def test_console_colors_only_when_forced_or_on_a_terminal(rostui_core: Any, ros_env: dict[str, str]) -> None:
    script = 'from rostui import client as ros\nros.init_node("colors")\nros.logwarn("hue")\n'
    plain = subprocess.run([sys.executable, "-c", script], env=ros_env, capture_output=True, text=True, timeout=30)
    forced = subprocess.run([sys.executable, "-c", script], env=dict(ros_env, ROSTUI_FORCE_COLOR="1"),
                            capture_output=True, text=True, timeout=30)
    assert "\033[" not in plain.stderr and "hue" in plain.stderr
    assert "\033[33m[ WARN]" in forced.stderr

