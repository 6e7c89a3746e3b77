"""Log directories, the latest link, sizes, roscore's disk warning, per-node log files."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from rostui.core.log import (
    DISK_WARNING_BYTES, Level, LogRecord, NodeLogFile, dir_size, disk_usage_warning, log_root,
    node_log_filename, run_log_dir, update_latest_link,
)


def test_log_root_precedence(tmp_path: Path) -> None:
    assert log_root({"ROS_LOG_DIR": "/a", "ROS_HOME": "/b"}) == Path("/a")
    assert log_root({"ROS_HOME": "/b"}) == Path("/b/log")
    assert log_root({"ROS_LOG_DIR": "", "ROS_HOME": "/b"}) == Path("/b/log")
    assert log_root({"HOME": "/ignored"}) == Path(os.path.expanduser("~")) / ".ros" / "log"


def test_run_log_dir_creates_under_ros_log_dir(tmp_path: Path) -> None:
    env = {"ROS_LOG_DIR": str(tmp_path / "logs"), "ROS_HOME": str(tmp_path / "home")}
    run = run_log_dir("f91f7f78-e66a-11f1-85e6-02fc00000001", env)
    assert run == tmp_path / "logs" / "f91f7f78-e66a-11f1-85e6-02fc00000001" and run.is_dir()
    assert not (tmp_path / "home").exists()
    with pytest.raises(ValueError):
        run_log_dir("../x", env)


def test_latest_link_is_absolute_and_replaced(tmp_path: Path) -> None:
    first = run_log_dir("run1", {"ROS_HOME": str(tmp_path)})
    second = run_log_dir("run2", {"ROS_HOME": str(tmp_path)})
    assert update_latest_link(first)
    assert os.readlink(tmp_path / "log" / "latest") == str(first)
    assert update_latest_link(second)
    assert os.readlink(tmp_path / "log" / "latest") == str(second)
    assert sorted(p.name for p in (tmp_path / "log").iterdir()) == ["latest", "run1", "run2"]


def test_latest_that_is_a_real_directory_is_left_alone(tmp_path: Path) -> None:
    (tmp_path / "latest").mkdir()
    run = tmp_path / "run"
    run.mkdir()
    assert update_latest_link(run) is False
    assert (tmp_path / "latest").is_dir() and not (tmp_path / "latest").is_symlink()


@pytest.mark.skipif(shutil.which("du") is None, reason="needs du")
def test_dir_size_is_du_sb(tmp_path: Path) -> None:
    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "x.log").write_bytes(b"x" * 12345)
    (tmp_path / "b.log").write_bytes(b"y" * 10)
    os.link(tmp_path / "b.log", tmp_path / "hard.log")
    os.symlink(tmp_path / "a", tmp_path / "link")
    du = int(subprocess.run(["du", "-sb", str(tmp_path)], capture_output=True, text=True).stdout.split()[0])
    assert dir_size(tmp_path) == du
    assert dir_size(tmp_path / "missing") == 0


def test_disk_warning_text_matches_roscore(tmp_path: Path) -> None:
    root = tmp_path / "log"
    (root / "old").mkdir(parents=True)
    assert disk_usage_warning(root) is None
    with open(root / "old" / "big.log", "wb") as f:  # sparse: apparent size counts, as roscore measures
        f.truncate(DISK_WARNING_BYTES + 1)
    assert disk_usage_warning(root) == (
        f"WARNING: disk usage in log directory [{root}] is over 1GB.\n"
        "It's recommended that you use the 'rosclean' command.")
    assert disk_usage_warning(root, tool="rostui clean").endswith("use the 'rostui clean' command.")
    assert disk_usage_warning(tmp_path / "missing") is None


def test_node_log_filename_like_rospy() -> None:
    assert node_log_filename("/talker") == "talker.log"
    assert node_log_filename("/ns/sub/talker") == "ns_sub_talker.log"
    with pytest.raises(ValueError):
        node_log_filename("/")


def test_node_log_file_appends_rospy_style_lines(tmp_path: Path) -> None:
    sink = NodeLogFile.for_node("/ns/count", tmp_path / "run")
    assert sink.path == tmp_path / "run" / "ns_count.log"
    stamp = 1_795_347_562_721_450_000
    sink(LogRecord(Level.INFO, "hello info", "/ns/count", "ros.agitr", stamp=stamp))
    sink(LogRecord(Level.WARN, "multi\nline", "/ns/count", "ros.agitr", stamp=stamp))
    sink.close()
    sink(LogRecord(Level.FATAL, "after reopen", "/ns/count", "ros.agitr", stamp=stamp))
    sink.close()
    lines = sink.path.read_text().splitlines()
    assert re.fullmatch(r"\[ros\.agitr\]\[INFO\] \d{4}-\d\d-\d\d \d\d:\d\d:\d\d,721: hello info", lines[0])
    assert lines[1].startswith("[ros.agitr][WARNING] ") and lines[2] == "line"
    assert lines[3].startswith("[ros.agitr][CRITICAL] ") and lines[3].endswith(": after reopen")
    assert NodeLogFile.for_node("/x", tmp_path, remapped=str(tmp_path / "y-1.log")).path == tmp_path / "y-1.log"


def test_node_log_file_never_raises(tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("")
    sink = NodeLogFile(blocker / "sub" / "n.log")  # parent is a file
    sink(LogRecord(Level.INFO, "m", "/n", "ros.x"))
    sink(LogRecord(Level.INFO, "m", "/n", "ros.x"))
