"""Reading rosout.log files for `rostui console PATH`: written by real rosout, by rostui core, by hand.

The live-written files come from a rospy node logging at every level under a
real roscore and under `rostui core` (each with a private ROS_HOME); the
reader must give back each message's fields.  Malformed, binary, missing and
unreadable files must produce one line naming the file (and the line).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from rostui.core.log import RosoutLogWriter
from rostui.core.log.rosout_read import (
    MalformedLine, RosoutEntry, RosoutLogError, entries_text, parse_rosout_lines, read_rosout_log,
)

from cli_helpers import rostui
from conftest import SYSTEM_PYTHON, need_peer, have_rospy, stop_process

DEADLINE = 30.0

LOGGER = r'''
import time
import rospy
rospy.init_node("console_logger")
time.sleep(1.0)  # rosout connects to our /rosout
rospy.loginfo("info %d", 1)
rospy.logwarn("first line\nsecond line")
rospy.logerr("error with [brackets] and topics: inside")
rospy.logfatal(u"fatal \u00fcn\u00efcode")
rospy.loginfo("END-MARKER")
time.sleep(2.0)
'''


def wait_for_text(path: Path, text: str, timeout: float = DEADLINE) -> str:
    """The file's content once it contains ``text``."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if path.exists():
            content = path.read_text(errors="replace")
            if text in content:
                return content
        time.sleep(0.1)
    raise AssertionError(f"{path} never contained {text!r}")


@pytest.mark.parametrize("master", ["rostui", "roscore"])
def test_reads_the_rosout_log_that_rosout_wrote(master: str, request: pytest.FixtureRequest,
                                                ros_env: dict[str, str], tmp_path: Path) -> None:
    """A rospy node logs at every level; the reader returns its messages with level, node, location, topics."""
    need_peer(have_rospy(), "rospy (Debian python3-rospy)")
    request.getfixturevalue("rostui_core" if master == "rostui" else "real_roscore")
    script = tmp_path / "console_logger.py"
    script.write_text(LOGGER)
    proc = subprocess.Popen([SYSTEM_PYTHON, str(script)], env=ros_env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        log_path = Path(ros_env["ROS_HOME"]) / "log" / "latest" / "rosout.log"
        wait_for_text(log_path, "END-MARKER")
    finally:
        stop_process(proc)
    log = read_rosout_log(log_path)
    assert log.malformed_count == 0, log.malformed_summary()
    mine = [e for e in log.entries if e.node == "/console_logger"]
    assert [(e.level_name, e.message) for e in mine] == [
        ("INFO", "info 1"),
        ("WARN", "first line\nsecond line"),
        ("ERROR", "error with [brackets] and topics: inside"),
        ("FATAL", "fatal \u00fcn\u00efcode"),
        ("INFO", "END-MARKER"),
    ]
    first = mine[0]
    assert (first.file, first.function, first.line) == ("console_logger.py", "<module>", 6)
    assert first.location == "console_logger.py:<module>:6"
    assert "/rosout" in first.topics
    assert first.stamp > 1_000_000_000 * 1_000_000_000
    assert all(e.source_line > 0 for e in mine)


def test_reads_what_rostuis_writer_wrote_field_for_field(tmp_path: Path) -> None:
    """RosoutLogWriter's lines (the file `rostui core` writes) come back as the same fields."""
    path = tmp_path / "rosout.log"
    writer = RosoutLogWriter(path, clock=lambda: 1_700_000_000_000_000_000)
    writer.write(1700000001, 5, 2, "/a", "a.py", 3, "main", ["/rosout", "/chatter"], "hello")
    writer.write(1700000002, 999999999, 1, "/ns/b", "b.cpp", 40, "int main(int, char**)", [], "debug")
    writer.write(1700000003, 0, 3, "/c", "", 0, "", [], "odd level three")
    writer.write(1700000004, 0, 8, "", "c.py", 1, "f", ["/x"], "multi\n\nline")
    writer.close()
    log = read_rosout_log(path)
    assert log.malformed_count == 0
    assert log.entries == [
        RosoutEntry(1700000001_000000005, 2, "/a", "hello", "a.py", 3, "main", ("/rosout", "/chatter"), 4),
        RosoutEntry(1700000002_999999999, 1, "/ns/b", "debug", "b.cpp", 40, "int main(int, char**)", (), 5),
        RosoutEntry(1700000003_000000000, 3, "/c", "odd level three", "", 0, "", (), 6),
        RosoutEntry(1700000004_000000000, 8, "", "multi\n\nline", "c.py", 1, "f", ("/x",), 7),
    ]
    assert log.entries[2].level_name == "3"
    again = tmp_path / "again.log"
    again.write_text(entries_text(log.entries))
    assert [e[:8] for e in read_rosout_log(again).entries] == [e[:8] for e in log.entries]


def test_reads_the_layouts_of_older_rosout_and_omit_topics() -> None:
    """Pre-Indigo rosout wrote no node name and no ']' after the location; omit_topics drops the topics."""
    lines = [
        "",
        "",
        "1371234567.123456789  Node Startup",
        "1371234567.223456789 WARN [count.cpp:12(int main(int, char**)) [topics: /rosout, /count] Count is 7",
        "1371234568.5 INFO /talker [talker.py:9(talk)] no topics [here]",
    ]
    first, second = parse_rosout_lines(lines)
    assert first == RosoutEntry(1371234567_223456789, 4, "", "Count is 7", "count.cpp", 12, "int main(int, char**)",
                                ("/rosout", "/count"), 4)
    assert second == RosoutEntry(1371234568_500000000, 2, "/talker", "no topics [here]", "talker.py", 9, "talk", (), 5)


def test_malformed_lines_are_reported_with_their_line_and_the_rest_is_read(tmp_path: Path) -> None:
    """Good messages survive bad lines; each bad line is counted and the first is named path:line."""
    path = tmp_path / "rosout.log"
    path.write_text(
        "\n\n1700000000.000000000  Node Startup\n"
        "1700000001.000000000 INFO /a [a.py:1(f)] [topics: ] good one\n"
        "1700000002.000000000 INFO /a [broken line without location\n"
        "1700000003.000000000 NOTALEVEL /a [a.py:1(f)] [topics: ] bad level\n"
        "1700000004.000000000 WARN /b [b.py:2(g)] [topics: ] good two\n"
        "  continued text\n"
    )
    log = read_rosout_log(path)
    assert [(e.message, e.source_line) for e in log.entries] == [("good one", 4), ("good two\n  continued text", 7)]
    assert log.malformed_count == 2
    assert log.malformed_summary() == (f"2 malformed lines (first: {path}:5: expected '<secs>.<nsecs> <LEVEL> <node> "
                                       "[<file>:<line>(<function>)] [topics: ...] <message>')")
    assert log.malformed[1] == MalformedLine(6, "1700000003.000000000 NOTALEVEL /a [a.py:1(f)] [topics: ] bad level",
                                             "unknown level 'NOTALEVEL'")


def test_keep_and_min_level_bound_what_is_read(tmp_path: Path) -> None:
    """Only the newest ``keep`` messages at or above the level stay; the others are counted."""
    path = tmp_path / "rosout.log"
    path.write_text("".join(f"{1700000000 + n}.000000000 {'DEBUG' if n % 2 else 'INFO'} /a [a.py:1(f)] "
                            f"[topics: ] m{n}\n" for n in range(10)))
    log = read_rosout_log(path, min_level=2, keep=3)
    assert [e.message for e in log.entries] == ["m4", "m6", "m8"]
    assert (log.dropped, log.below_level) == (2, 5)


def test_a_file_with_no_rosout_line_is_an_error_naming_its_first_line(tmp_path: Path) -> None:
    """A text file that is no rosout.log, and a binary file, fail with path:line."""
    text = tmp_path / "notes.txt"
    text.write_text("shopping list\nmilk\n")
    with pytest.raises(RosoutLogError) as info:
        read_rosout_log(text)
    assert str(info.value) == (f"{text}:1: not a rosout.log line (no message line before it) (not a rosout.log)")
    binary = tmp_path / "data.bag"
    binary.write_bytes(b"#ROSBAG V2.0\n\x00\x01\x02\xff\xfe\n")
    with pytest.raises(RosoutLogError, match=rf"^{binary}:1: "):
        read_rosout_log(binary)
    empty = tmp_path / "empty.log"
    empty.write_text("")
    assert read_rosout_log(empty).entries == []


def test_missing_directory_and_unreadable_paths_are_one_line_errors(tmp_path: Path) -> None:
    """No file, a directory, a file without read permission: RosoutLogError with the reason."""
    with pytest.raises(RosoutLogError, match="cannot read: No such file or directory"):
        read_rosout_log(tmp_path / "missing.log")
    with pytest.raises(RosoutLogError, match="is a directory"):
        read_rosout_log(tmp_path)
    if os.geteuid() != 0:  # root reads everything
        locked = tmp_path / "locked.log"
        locked.write_text("1700000001.000000000 INFO /a [a.py:1(f)] [topics: ] x\n")
        locked.chmod(0)
        with pytest.raises(RosoutLogError, match="cannot read: Permission denied"):
            read_rosout_log(locked)


def test_cli_rejects_bad_files_and_options_with_one_line_and_exit_1(tmp_path: Path, ros_env: dict[str, str]) -> None:
    """`rostui console PATH` says what is wrong with PATH in one line on stderr and exits 1."""
    garbage = tmp_path / "garbage.log"
    garbage.write_text("hello\n")
    good = tmp_path / "rosout.log"
    good.write_text("1700000001.000000000 INFO /a [a.py:1(f)] [topics: ] x\n")
    cases = [
        (["console", str(tmp_path / "missing.log")],
         f"ERROR: {tmp_path / 'missing.log'}: cannot read: No such file or directory"),
        (["console", str(tmp_path)], f"ERROR: {tmp_path}: is a directory, not a rosout.log"),
        (["console", str(garbage)],
         f"ERROR: {garbage}:1: not a rosout.log line (no message line before it) (not a rosout.log)"),
        (["console", "--min-level", "loud", str(good)],
         "ERROR: --min-level: unknown log level 'loud' (use debug, info, warn, error or fatal)"),
        (["console", "--max", "0", str(good)], "ERROR: --max must be at least 1, got 0"),
        (["console", str(good)],
         "ERROR: rostui console draws in a terminal: stdin and stdout must be a TTY "
         "(use `rostui topic echo /rosout_agg` without one)"),
    ]
    for args, message in cases:
        result = rostui(args, ros_env)
        assert result.returncode == 1, (args, result.stderr)
        assert result.stderr.strip() == message
        assert result.stdout == ""


def test_cli_module_does_not_import_textual() -> None:
    """Loading the command line (and the console command) leaves Textual unloaded."""
    code = ("import sys, rostui.cli.main, rostui.cli.console_cmd; "
            "print(any(m == 'textual' or m.startswith('textual.') for m in sys.modules))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=DEADLINE)
    assert result.stdout.strip() == "False", result.stderr
