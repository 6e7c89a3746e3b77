"""`rostui topic` against real `rostopic` on the same live system (rostui core and a real roscore).

Master-only commands (list, info, type, find) must print what rostopic prints,
byte for byte after normalize(); echo, hz, bw and pub are compared with the
real tool on the same topics, and real rostopic reads what `rostui topic pub`
publishes.
"""

from __future__ import annotations

import re
import sys
import time
from typing import Iterator

import pytest

from cli_helpers import normalize, rostui
from conftest import have_rospy, need_command, need_peer
from interop_helpers import Peer, Spawn, example, peers, rospy_peer, rostui_peer, run_tool, spawn, wait_for_node, wait_until  # noqa: F401

RATE_LINE = re.compile(r"average rate: (\d+\.\d{3})")


def rostui_argv(*args: str) -> list[str]:
    """argv of the real rostui command line."""
    return [sys.executable, "-m", "rostui", *args]


def need_rostopic() -> None:
    need_command("rostopic")


def start_live(spawn: Spawn) -> dict[str, Peer]:
    """A talker (rostui, 10 Hz on /chatter), a rospy listener on /chatter and a latched /latched."""
    need_rostopic()
    talker = spawn(example("talker.py"), label="talker")
    listener = spawn(rospy_peer("rospy_listener.py", "/chatter", "1000000"), label="listener")
    latcher = spawn(rostui_peer("latch", "/latched", "hello latched"), label="latcher")
    listener.wait_for("subscribed")
    latcher.wait_for("ready")
    listener.wait_for("data: hello world")
    return {"talker": talker, "listener": listener, "latcher": latcher}


@pytest.fixture
def live(any_master: str, ros_env: dict[str, str], spawn: Spawn, rospy_available: None) -> dict[str, Peer]:
    """The graph of :func:`start_live`, for a test that adds to it (hz, bw, pub)."""
    return start_live(spawn)


@pytest.fixture(scope="module")
def shared(module_master: str, module_ros_env: dict[str, str]) -> Iterator[dict[str, str]]:
    """The graph of :func:`start_live` plus a latched geometry_msgs/Point on /point from real `rostopic pub`,
    shared by the module's tests that only read it; its environment."""
    need_peer(have_rospy(), "rospy (Debian python3-rospy)")
    with peers(module_ros_env) as spawn:
        start_live(spawn)
        point = spawn(["rostopic", "pub", "/point", "geometry_msgs/Point", "--", "1.5", "-2", "3"], label="rostopic pub")
        point.wait_for("publishing and latching message")
        yield module_ros_env


def both(args: list[str], env: dict[str, str]) -> tuple[tuple[int, str, str], tuple[int, str, str]]:
    """(rc, stdout, stderr) of `rostopic ARGS` and `rostui topic ARGS`, normalized."""
    real = run_tool(["rostopic", *args], env, check=False)
    ours = rostui(["topic", *args], env)
    return ((real.returncode, normalize(real.stdout), normalize(real.stderr)),
            (ours.returncode, normalize(ours.stdout), normalize(ours.stderr)))


# ----------------------------------------------------------------------------- master-only commands
@pytest.mark.parametrize("args", [
    ["list"], ["list", "-v"], ["list", "-p"], ["list", "-s"], ["list", "-v", "-p"], ["list", "/rosout"],
    ["info", "/chatter"], ["info", "/rosout"], ["info", "/latched"],
    ["type", "/chatter"], ["type", "/rosout/header/stamp"], ["type", "/rosout/header"],
    ["find", "std_msgs/String"], ["find", "rosgraph_msgs/Log"], ["find", "nothing/Here"],
], ids=lambda a: " ".join(a))
def test_master_commands_match_rostopic(shared: dict[str, str], args: list[str]) -> None:
    real, ours = both(args, shared)
    assert ours == real


@pytest.mark.parametrize("args", [["info", "/nope"], ["type", "/nope"]], ids=lambda a: " ".join(a))
def test_unknown_topic_errors_match_rostopic(shared: dict[str, str], args: list[str]) -> None:
    real, ours = both(args, shared)
    assert ours == real
    assert ours[0] == 1 and ours[1] == "" and ours[2].count("\n") == 1


def test_json_outputs(shared: dict[str, str]) -> None:
    import json

    listed = json.loads(rostui(["topic", "list", "--json"], shared).stdout)
    chatter = next(t for t in listed if t["topic"] == "/chatter")
    assert chatter["type"] == "std_msgs/String" and len(chatter["publishers"]) == 1 and chatter["subscribers"]
    info = json.loads(rostui(["topic", "info", "/chatter", "--json"], shared).stdout)
    assert info["type"] == "std_msgs/String"
    assert info["publishers"][0]["uri"].startswith("http://")
    assert json.loads(rostui(["topic", "type", "/rosout/header/stamp", "--json"], shared).stdout) == {
        "topic": "/rosout/header/stamp", "type": "rosgraph_msgs/Log", "field": "header/stamp", "field_type": "time"}
    assert json.loads(rostui(["topic", "find", "std_msgs/String", "--json"], shared).stdout) == ["/chatter", "/latched"] or \
        sorted(json.loads(rostui(["topic", "find", "std_msgs/String", "--json"], shared).stdout)) == ["/chatter", "/latched"]


# ----------------------------------------------------------------------------- echo
@pytest.mark.parametrize("args", [
    ["echo", "-n", "1", "/latched"], ["echo", "-n1", "--nostr", "/latched"], ["echo", "-n", "1", "/point"],
    ["echo", "-n", "1", "/point/y"], ["echo", "-n", "1", "-w", "4", "/point"], ["echo", "-n", "1", "--noarr", "/point"],
], ids=lambda a: " ".join(a))
def test_echo_latched_matches_rostopic(shared: dict[str, str], args: list[str]) -> None:
    real, ours = both(args, shared)
    assert ours == real
    assert ours[0] == 0 and ours[1].endswith("---\n")


def test_echo_plot_matches_rostopic(shared: dict[str, str]) -> None:
    real, ours = both(["echo", "-n", "1", "-p", "/point"], shared)
    stamp = re.compile(r"^\d{19},", re.M)
    assert ours[1].startswith("%time,field.x,field.y,field.z\n")
    assert stamp.sub("T,", ours[1]) == stamp.sub("T,", real[1])


def test_echo_live_topic_and_field(shared: dict[str, str]) -> None:
    r = rostui(["topic", "echo", "-n", "2", "/chatter"], shared)
    assert r.returncode == 0, r.stderr
    assert re.fullmatch(r'data: "hello world \d+"\n---\ndata: "hello world \d+"\n---\n', r.stdout)
    r = rostui(["topic", "echo", "-n", "1", "/rosout/topics"], shared)
    assert r.returncode == 0, r.stderr
    assert r.stdout == run_tool(["rostopic", "echo", "-n", "1", "/rosout/topics"], shared).stdout
    real = run_tool(["rostopic", "echo", "-n", "1", "--noarr", "--nostr", "/rosout"], shared)
    ours = rostui(["topic", "echo", "-n", "1", "--noarr", "--nostr", "/rosout"], shared)
    digits = re.compile(r" *\d+")  # two different messages: nsecs is padded to width 9 when shorter
    assert digits.sub(" N", ours.stdout) == digits.sub(" N", real.stdout)


def test_echo_waits_for_topic_then_prints(rostui_core: object, ros_env: dict[str, str], spawn: Spawn) -> None:
    echo = spawn(rostui_argv("topic", "echo", "-n", "1", "/later"), label="rostui echo")
    echo.wait_for(r"WARNING: topic \[/later\] does not appear to be published yet")
    spawn(rostui_peer("latch", "/later", "at last"), label="latcher").wait_for("ready")
    assert echo.wait_exit() == 0
    assert echo.output.endswith('data: "at last"\n---')


# ----------------------------------------------------------------------------- hz / bw
def _reports(peer: Peer, pattern: str, n: int) -> list[str]:
    """Wait for *n* lines matching *pattern*; return every line so far."""
    wait_until(lambda: peer.count(pattern) >= n, f"{n} lines matching {pattern!r} from {peer.label}")
    return peer.output.splitlines()


def test_hz_matches_rostopic(live: dict[str, Peer], ros_env: dict[str, str], spawn: Spawn) -> None:
    real = spawn(["rostopic", "hz", "/chatter"], label="rostopic hz")
    ours = spawn(rostui_argv("topic", "hz", "/chatter"), label="rostui hz")
    real_lines, our_lines = _reports(real, "average rate", 3), _reports(ours, "average rate", 3)
    shape = re.compile(r"\d+(\.\d+)?")
    assert our_lines[0] == real_lines[0] == "subscribed to [/chatter]"
    assert [shape.sub("X", x) for x in our_lines[1:5]] == [shape.sub("X", x) for x in real_lines[1:5]]
    assert our_lines[2].startswith("\tmin: ") and "window: " in our_lines[2]
    rate = float(RATE_LINE.search(our_lines[-2] if "average" in our_lines[-2] else our_lines[-1]).group(1))
    assert abs(rate - 10.0) < 0.2


def test_hz_several_topics_table(live: dict[str, Peer], ros_env: dict[str, str], spawn: Spawn) -> None:
    ours = spawn(rostui_argv("topic", "hz", "/chatter", "/rosout"), label="rostui hz")
    ours.wait_for(r"/rosout\s+\d")
    lines = ours.output.splitlines()
    assert lines[:2] == ["subscribed to [/chatter]", "subscribed to [/rosout]"]
    head = next(i for i, x in enumerate(lines) if x.lstrip().startswith("topic"))
    assert lines[head].split() == ["topic", "rate", "min_delta", "max_delta", "std_dev", "window"]
    assert set(lines[head + 1]) == {"="}
    assert lines[head + 2].startswith("/chatter ") and lines[head + 3].startswith("/rosout ")


def test_bw_matches_rostopic(live: dict[str, Peer], ros_env: dict[str, str], spawn: Spawn) -> None:
    real = spawn(["rostopic", "bw", "/chatter"], label="rostopic bw")
    ours = spawn(rostui_argv("topic", "bw", "/chatter"), label="rostui bw")
    real_lines, our_lines = _reports(real, "average:", 2), _reports(ours, "average:", 2)
    shape = re.compile(r"\d+(\.\d+)?")
    assert our_lines[0] == real_lines[0] == "subscribed to [/chatter]"
    assert [shape.sub("X", x) for x in our_lines[1:5]] == [shape.sub("X", x) for x in real_lines[1:5]]
    assert re.fullmatch(r"\tmean: [\d.]+B min: [\d.]+B max: [\d.]+B window: \d+", our_lines[2]), our_lines[2]


def test_pub_rate_measured_by_hz(rostui_core: object, ros_env: dict[str, str], spawn: Spawn) -> None:
    spawn(rostui_argv("topic", "pub", "-r", "10", "/rated", "std_msgs/String", "tick"), label="rostui pub -r")
    hz = spawn(rostui_argv("topic", "hz", "/rated"), label="rostui hz")
    lines = _reports(hz, "average rate", 4)
    rates = [float(m.group(1)) for m in map(RATE_LINE.search, lines) if m]
    assert abs(rates[-1] - 10.0) <= 0.2, rates


# ----------------------------------------------------------------------------- pub
def test_pub_latched_like_rostopic(live: dict[str, Peer], ros_env: dict[str, str], spawn: Spawn) -> None:
    real = spawn(["rostopic", "pub", "/real_pt", "geometry_msgs/Point", "1", "2", "3"], label="rostopic pub")
    ours = spawn(rostui_argv("topic", "pub", "/our_pt", "geometry_msgs/Point", "1", "2", "3"), label="rostui pub")
    real.wait_for("latching")
    ours.wait_for("latching")
    assert ours.output == real.output == "publishing and latching message. Press ctrl-C to terminate"
    a = run_tool(["rostopic", "echo", "-n", "1", "/real_pt"], ros_env).stdout
    b = run_tool(["rostopic", "echo", "-n", "1", "/our_pt"], ros_env).stdout
    assert a == b == "x: 1.0\ny: 2.0\nz: 3.0\n---\n"
    info = run_tool(["rostopic", "info", "/our_pt"], ros_env).stdout
    assert info.startswith("Type: geometry_msgs/Point\n\nPublishers: \n * /rostopic_")


def test_pub_once_yaml_dict_and_auto_stamp(rostui_core: object, ros_env: dict[str, str], spawn: Spawn) -> None:
    need_rostopic()
    echo = spawn(["rostopic", "echo", "-n", "1", "/stamped"], label="rostopic echo")
    echo.wait_for("does not appear to be published yet")
    t0 = time.monotonic()
    r = rostui(["topic", "pub", "-1", "/stamped", "geometry_msgs/PointStamped",
                "{header: auto, point: {x: 1.0, y: 2, z: 3}}"], ros_env)
    elapsed = time.monotonic() - t0
    assert r.returncode == 0, r.stderr
    assert r.stdout == "publishing and latching message for 3.0 seconds\n"
    assert elapsed >= 3.0
    assert echo.wait_exit() == 0
    out = echo.output
    secs = int(re.search(r"secs: (\d+)", out).group(1))
    assert abs(secs - time.time()) < 60
    assert "point: \n  x: 1.0\n  y: 2.0\n  z: 3.0" in out


def test_pub_file_and_stdin(rostui_core: object, ros_env: dict[str, str], spawn: Spawn, tmp_path) -> None:
    msgs = tmp_path / "msgs.yaml"
    msgs.write_text('data: "first"\n---\ndata: "second"\n---\n')
    echo = spawn(rostui_argv("topic", "echo", "-n", "2", "/from_file"), label="echo file")
    echo.wait_for("does not appear")
    r = rostui(["topic", "pub", "/from_file", "std_msgs/String", "-f", str(msgs)], ros_env)
    assert r.returncode == 0, r.stderr
    assert echo.wait_exit() == 0
    assert 'data: "first"\n---\ndata: "second"\n---' in echo.output
    echo = spawn(rostui_argv("topic", "echo", "-n", "2", "/from_stdin"), label="echo stdin")
    echo.wait_for("does not appear")
    r = rostui(["topic", "pub", "/from_stdin", "std_msgs/String"], ros_env, input=msgs.read_text())
    assert r.returncode == 0, r.stderr
    assert echo.wait_exit() == 0
    assert 'data: "first"\n---\ndata: "second"\n---' in echo.output


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("args, expected", [
    (["pub", "/x", "foo/Bar", "1"], "ERROR: invalid message type: foo/Bar."),
    (["pub", "/x", "std_msgs/String", "{data: [}"], "ERROR: Argument error: argument 1"),
    (["pub", "/x", "geometry_msgs/Point", "1", "2"], "ERROR: Not enough arguments"),
    (["pub", "/x", "geometry_msgs/Point", "1", "2", "3", "4"], "ERROR: Too many arguments"),
    (["pub", "/x", "std_msgs/String", "{dat: 1}"], "ERROR: No field name [dat]"),
    (["pub", "/x", "std_msgs/Int8", "300"], "ERROR: Field [data] value 300 out of range"),
    (["pub", "-r", "1", "-1", "/x", "std_msgs/String", "a"], "ERROR: You cannot select both -r and -1"),
    (["info", "/nope"], "ERROR: Unknown topic /nope"),
    (["echo", "/rosout/topics[a]"], "ERROR: field 'topics' has invalid slice argument 'a'"),
], ids=lambda a: " ".join(a) if isinstance(a, list) else None)
def test_bad_input_one_line(rostui_core: object, ros_env: dict[str, str], args: list[str], expected: str) -> None:
    r = rostui(["topic", *args], ros_env, timeout=20)
    assert r.returncode == 1
    assert r.stdout == ""
    assert r.stderr.startswith(expected) and r.stderr.count("\n") == 1, r.stderr


def test_bad_file_names_line(rostui_core: object, ros_env: dict[str, str], tmp_path) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("data: a\n---\ndata: [1, \n  }\n")
    r = rostui(["topic", "pub", "/x", "std_msgs/String", "-f", str(bad)], ros_env)
    assert r.returncode == 1 and r.stderr.count("\n") == 1
    assert f"{bad}:" in r.stderr


@pytest.mark.parametrize("args", [
    ["list"], ["info", "/a"], ["type", "/a"], ["find", "std_msgs/String"], ["echo", "/a"], ["hz", "/a"],
    ["bw", "/a"], ["pub", "/a", "std_msgs/String", "x"],
], ids=lambda a: " ".join(a))
def test_no_master(ros_env: dict[str, str], args: list[str]) -> None:
    r = rostui(["topic", *args], ros_env, timeout=20)
    assert r.returncode == 1
    assert r.stderr == f"ERROR: Unable to communicate with master at {ros_env['ROS_MASTER_URI']}/\n" or \
        r.stderr == f"ERROR: Unable to communicate with master at {ros_env['ROS_MASTER_URI']}\n"
    assert r.stdout == ""
