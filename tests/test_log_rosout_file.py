"""rosout.log: our lines compared with the lines real rosout writes for the same messages."""

from __future__ import annotations

import json
import re
import subprocess
import time
from pathlib import Path
from types import SimpleNamespace

from conftest import SYSTEM_PYTHON, stop_process

from rostui.core.log import Level, LogRecord, RosoutLogWriter, format_rosout_line, startup_text

# (secs, nsecs, level, name, file, line, function, topics, msg)
CASES = [
    (123, 45, 2, "/fake_node", "f.py", 7, "fn", [], "plain info"),
    (124, 0, 1, "/fake_node", "a b.py", 0, "Cls.meth", ["/a"], "debug msg"),
    (125, 999999999, 4, "/fake_node", "x.cpp", 99, "main", ["/a", "/b"], "warn: multi\nline"),
    (126, 1, 8, "/fake_node", "", 0, "", [], ""),
    (127, 2, 16, "/fake_node", "count.py", 1, "<module>", ["/chatter", "/rosout"], "fatal \u00fcn\u00efcode [x]"),
    (1795347562, 722323656, 2, "", "f.py", 3, "g", [], "no node name"),
    (129, 0, 2, "/fake_node", "f.py", 9, "fn", [], "END-MARKER"),
]

PEER = r'''
import json, sys, time
import rospy
from rosgraph_msgs.msg import Log
rospy.init_node("rosout_format_peer")
pub = rospy.Publisher("/rosout", Log, queue_size=100)
deadline = time.time() + 20
while pub.get_num_connections() < 1 and time.time() < deadline:
    time.sleep(0.05)
time.sleep(0.3)
for secs, nsecs, level, name, file, line, function, topics, text in json.loads(sys.argv[1]):
    m = Log()
    m.header.stamp = rospy.Time(secs, nsecs)
    m.level, m.name, m.msg, m.file, m.function, m.line, m.topics = level, name, text, file, function, line, topics
    pub.publish(m)
    time.sleep(0.05)
print("published", flush=True)
time.sleep(60)
'''


def expected_block() -> str:
    return "".join(format_rosout_line(*case) for case in CASES)


def test_rosout_log_lines_match_real_rosout(real_roscore: subprocess.Popen, ros_env: dict[str, str],
                                            rospy_available: None, tmp_path: Path) -> None:
    log_file = Path(ros_env["ROS_HOME"]) / "log" / "latest" / "rosout.log"
    deadline = time.monotonic() + 30
    while not log_file.exists() and time.monotonic() < deadline:
        time.sleep(0.1)
    assert log_file.exists(), "real rosout wrote no rosout.log"
    script = tmp_path / "peer.py"
    script.write_text(PEER)
    peer = subprocess.Popen([SYSTEM_PYTHON, str(script), json.dumps(CASES)], env=ros_env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)
    try:
        deadline = time.monotonic() + 40
        content = ""
        while time.monotonic() < deadline:
            content = log_file.read_text(encoding="utf-8", errors="replace")
            if "END-MARKER" in content or peer.poll() is not None:
                break
            time.sleep(0.1)
    finally:
        stop_process(peer, timeout=3)
    assert "END-MARKER" in content, f"rosout never logged the peer's messages:\n{content}"
    # the real file opens with two empty lines and its startup stamp
    assert re.match(r"\A\n\n\d+\.\d{9}  Node Startup\n", content), repr(content[:80])
    assert expected_block() in content, f"ours:\n{expected_block()}\nreal rosout:\n{content}"


def test_writer_produces_header_then_lines(tmp_path: Path) -> None:
    path = tmp_path / "run" / "rosout.log"
    writer = RosoutLogWriter(path, clock=lambda: 1795347558_161969690)
    for case in CASES:
        writer.write(*case)
    writer.close()
    assert path.read_text() == "\n\n1795347558.161969690  Node Startup\n" + expected_block()
    assert startup_text(5_000_000_001) == "\n\n5.000000001  Node Startup\n"


def test_writer_accepts_log_messages_and_records(tmp_path: Path) -> None:
    path = tmp_path / "rosout.log"
    writer = RosoutLogWriter(path, clock=lambda: 0)
    msg = SimpleNamespace(header=SimpleNamespace(stamp=SimpleNamespace(secs=5, nsecs=7)), level=4,
                          name="/n", file="f.py", line=3, function="fn", topics=("/a", "/rosout"), msg="hi")
    writer.write_message(msg)
    writer.write_record(LogRecord(Level.ERROR, "rec", "/n", "ros.x", "g.py", 4, "h", 6_000_000_008), ["/t"])
    writer.close()
    assert path.read_text().splitlines()[3:] == [
        "5.000000007 WARN /n [f.py:3(fn)] [topics: /a, /rosout] hi",
        "6.000000008 ERROR /n [g.py:4(h)] [topics: /t] rec",
    ]


def test_unknown_level_is_written_as_its_number() -> None:
    assert format_rosout_line(1, 2, 3, "/n", "f", 1, "g", [], "m") == "1.000000002 3 /n [f:1(g)] [topics: ] m\n"


def test_writer_rotates_and_keeps_backups(tmp_path: Path) -> None:
    path = tmp_path / "rosout.log"
    writer = RosoutLogWriter(path, max_bytes=200, backups=2, clock=lambda: 0)
    for i in range(40):
        writer.write(i, 0, 2, "/n", "f.py", 1, "g", [], f"message number {i}")
    writer.close()
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["rosout.log", "rosout.log.1", "rosout.log.2"]
    assert all(p.stat().st_size <= 200 for p in tmp_path.iterdir())
    assert path.read_text().splitlines()[-1].endswith("message number 39")


def test_writer_never_raises_on_unwritable_path(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("")
    writer = RosoutLogWriter(tmp_path / "file" / "rosout.log")
    writer.write(1, 0, 2, "/n", "f", 1, "g", [], "m")
    assert writer.errors >= 1
