"""What rosbag users also reach for, against Debian's own tools on the same bags: `topic echo -b` (rostopic echo -b),
`bag filter` (rosbag filter), `bag compress` / `bag decompress` (rosbag compress / decompress), and the progress
bar those rewrites show on a terminal (and only there)."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from rostui.core.bag.files import open_reader, open_writer

from cli_helpers import interrupted_import, rostui
from conftest import SYSTEM_PYTHON, need_command, need_peer
from tmux_helpers import shell_pane

#: A bag of several shapes written by real rosbag: strings, ints, a stamped pose, uint8[] (bytes in genpy), arrays
#: of strings and floats, and a second, latched publisher (its own callerid) on /chatter; small chunks. With
#: ``per-topic`` the messages are written one topic after another, so rosbag's tools (which read in time order)
#: and the file's order differ.
MAKE = """
import sys, rosbag, rospy
from std_msgs.msg import String, Int32, UInt8MultiArray
from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import JointState
other = {"callerid": "/talker2", "topic": "/chatter", "type": String._type, "md5sum": String._md5sum,
         "message_definition": String._full_text, "latching": "1"}
rows = []
for i in range(int(sys.argv[2])):
    t = rospy.Time(100 + i, 250000000)
    rows.append(("/chatter", String(data="hello %d" % i), t, None))
    rows.append(("/count", Int32(data=i), t + rospy.Duration(0, 1000), None))
    p = PoseStamped()
    p.header.stamp = rospy.Time(50 + i, 7)
    p.header.frame_id = "map"
    p.pose.position.x = i * 1.5
    rows.append(("/pose", p, t + rospy.Duration(0, 2000), None))
    rows.append(("/bytes", UInt8MultiArray(data=bytes([i % 256, 2, 3])), t + rospy.Duration(0, 3000), None))
    j = JointState(name=["a", "b"], position=[0.5 * i, 1.0])
    j.header.stamp = rospy.Time(60 + i)
    rows.append(("/joints", j, t + rospy.Duration(0, 4000), None))
    if i % 2:
        rows.append(("/chatter", String(data="other %d" % i), t + rospy.Duration(0, 5000), other))
if sys.argv[3] == "per-topic":  # as a tool that writes one topic after another: file order is not time order
    rows.sort(key=lambda row: (row[0], row[3] is not None))
with rosbag.Bag(sys.argv[1], "w", chunk_threshold=4096) as bag:
    for topic, msg, t, header in rows:
        bag.write(topic, msg, t, connection_header=header)
"""

#: Every message of a bag as rosbag's Python API reads it: topic, time, callerid, latching, type, bytes.
DUMP = """
import sys, rosbag
with rosbag.Bag(sys.argv[1]) as bag:
    for topic, raw, t, header in bag.read_messages(raw=True, return_connection_header=True):
        print(topic, t.to_nsec(), header.get("callerid", ""), header.get("latching", "0"), raw[0], raw[1].hex())
"""


def _rosbag_api() -> None:
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import rosbag, rospy, std_msgs, geometry_msgs, sensor_msgs"],
                           capture_output=True)
    need_peer(probe.returncode == 0, "rosbag Python API with the message packages (Debian python3-rosbag)")


def make_bag(path: Path, rounds: int = 6, order: str = "per-topic") -> Path:
    """``MAKE`` run by Debian's rosbag under the system Python (``order``: ``per-topic`` or ``time``)."""
    _rosbag_api()
    made = subprocess.run([SYSTEM_PYTHON, "-c", MAKE, str(path), str(rounds), order], capture_output=True,
                          text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    return path


def dump(path: Path) -> list[str]:
    """The messages of ``path`` as real rosbag reads them (so also: real rosbag can read it)."""
    read = subprocess.run([SYSTEM_PYTHON, "-c", DUMP, str(path)], capture_output=True, text=True, timeout=120)
    assert read.returncode == 0, read.stderr
    return read.stdout.splitlines()


def our_dump(path: Path) -> list[str]:
    """The same rows read by rostui's reader (for MCAP output)."""
    reader = open_reader(str(path))
    try:
        return [f"{c.topic} {t} {c.callerid} {'1' if c.latching else '0'} {c.type} {d.hex()}"
                for c, t, d in sorted(reader.messages(), key=lambda m: m[1])]
    finally:
        reader.close()


@pytest.fixture(scope="module")
def bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The ``MAKE`` bag (per topic), and an MCAP copy of it in the same file order beside it (``shapes.mcap``)."""
    path = make_bag(tmp_path_factory.mktemp("tools") / "shapes.bag")
    reader = open_reader(str(path))
    writer = open_writer(str(path.with_suffix(".mcap")))
    for conn, t, data in reader.messages():  # file order, not time order
        if conn.id not in writer.connections:
            writer.add_connection(conn)
        writer.write(conn.id, t, data)
    writer.close()
    reader.close()
    return path


# ----------------------------------------------------------------------------- topic echo -b
ECHO_CASES = [
    ["-a"], ["-a", "-n", "7"], ["/chatter"], ["/count", "-n", "2"], ["/pose"], ["/pose/header"],
    ["/pose/pose/position/x"], ["-p", "/pose"], ["-p", "/pose/pose/position/x"], ["-p", "/chatter"],
    ["/bytes"], ["/bytes/data"], ["/bytes/data[1]"], ["-p", "/bytes/data"], ["/joints", "--noarr"],
    ["/joints", "--nostr"], ["-p", "/joints", "--noarr"], ["-p", "/joints"], ["/joints/name", "--noarr"],
    ["/joints/name[0]"], ["/joints/position[0:1]"], ["/chatter/data", "--nostr"], ["/pose", "-w", "4"],
    ["/nothing/here"], ["count"],
]


@pytest.mark.parametrize("args", ECHO_CASES, ids=lambda a: " ".join(a))
def test_echo_b_prints_what_rostopic_echo_b_prints(bag: Path, ros_env: dict[str, str], args: list[str]) -> None:
    need_command("rostopic")
    theirs = subprocess.run(["rostopic", "echo", "-b", str(bag), *args], env=ros_env, capture_output=True,
                            text=True, timeout=60)
    assert theirs.returncode == 0, theirs.stderr
    for path in (bag, bag.with_suffix(".mcap")):
        ours = rostui(["topic", "echo", "-b", str(path), *args], ros_env)
        assert ours.returncode == 0, ours.stderr
        assert ours.stdout == theirs.stdout, path.name


@pytest.mark.parametrize("args, error", [
    (["-b", "missing.bag", "/x"], "ERROR: bag file [missing.bag] does not exist"),
    (["-a"], "ERROR: Display all option is only valid when echoing from bag files"),
    (["-b", "shapes.bag", "--offset", "/count"], "ERROR: offset time option is not valid with bag files"),
    (["-b", "shapes.bag"], "ERROR: topic must be specified"),
    (["-b", "shapes.bag", "/count/data["], "ERROR: missing closing ']' in slice spec 'data['"),
])
def test_echo_b_refuses_in_one_line(bag: Path, ros_env: dict[str, str], args: list[str], error: str) -> None:
    ours = subprocess.run([sys.executable, "-m", "rostui", "topic", "echo", *args], env=ros_env, cwd=bag.parent,
                          capture_output=True, text=True, timeout=60)
    assert ours.returncode == 1
    assert ours.stderr.strip() == error
    assert ours.stdout == ""


def test_echo_b_of_a_file_that_is_no_bag_is_one_line(tmp_path: Path, ros_env: dict[str, str]) -> None:
    (tmp_path / "notes.bag").write_text("not a bag\n")
    ours = rostui(["topic", "echo", "-b", str(tmp_path / "notes.bag"), "/x"], ros_env)
    assert ours.returncode == 1
    assert ours.stderr.startswith("ERROR: unable to use bag file: ") and ours.stderr.count("\n") == 1


# ----------------------------------------------------------------------------- bag filter
FILTERS = [
    "topic == '/count'",
    "topic == '/count' and m.data % 2 == 0",
    "t.to_sec() > 102.5",
    "t.secs >= 103 and t.nsecs == 250000000",
    "topic == '/pose' and m.header.stamp.secs > 52",
    "topic == '/chatter' and m.data.startswith('other')",
    "topic in ('/joints', '/bytes') and t.to_nsec() % 2 == 0",
    "False",
]


@pytest.mark.parametrize("expr", FILTERS)
def test_filter_keeps_what_rosbag_filter_keeps(bag: Path, tmp_path: Path, ros_env: dict[str, str],
                                              expr: str) -> None:
    need_command("rosbag")
    theirs = subprocess.run(["rosbag", "filter", str(bag), str(tmp_path / "theirs.bag"), expr], env=ros_env,
                            capture_output=True, text=True, timeout=120)
    assert theirs.returncode == 0, theirs.stderr
    ours = rostui(["bag", "filter", str(bag), str(tmp_path / "ours.bag"), expr], ros_env)
    assert ours.returncode == 0, ours.stderr
    kept = dump(tmp_path / "theirs.bag")
    assert dump(tmp_path / "ours.bag") == kept  # read by real rosbag: same messages, times, headers
    info = subprocess.run(["rosbag", "info", str(tmp_path / "ours.bag")], env=ros_env, capture_output=True,
                          text=True, timeout=60)
    assert info.returncode == 0, info.stderr
    into_mcap = rostui(["bag", "filter", str(bag.with_suffix(".mcap")), str(tmp_path / "ours.mcap"), expr], ros_env)
    assert into_mcap.returncode == 0, into_mcap.stderr
    assert our_dump(tmp_path / "ours.mcap") == kept


@pytest.mark.parametrize("shown", ["topic", "repr(t)", "t.to_sec()", "m.data if topic == '/bytes' else None",
                                   "(t.secs, m.header.frame_id) if topic == '/pose' else [t.nsecs]"])
def test_filter_print_lines_are_rosbags(bag: Path, tmp_path: Path, ros_env: dict[str, str], shown: str) -> None:
    need_command("rosbag")
    args = ["topic == '/count' or t.secs > 104", "--print", shown]
    theirs = subprocess.run(["rosbag", "filter", str(bag), str(tmp_path / "theirs.bag"), *args], env=ros_env,
                            capture_output=True, text=True, timeout=120)
    assert theirs.returncode == 0, theirs.stderr
    ours = rostui(["bag", "filter", str(bag), str(tmp_path / "ours.bag"), *args], ros_env)
    assert ours.returncode == 0, ours.stderr
    # rosbag's own progress meter shares its stdout (no newline): keep only the MATCH parts
    wanted = re.findall(r"(?:NO )?MATCH [^\n\r]*?(?= \S+\.bag|$)", theirs.stdout, flags=re.M)
    assert len(wanted) == len(dump(bag))
    assert ours.stdout.splitlines() == [w.rstrip() for w in wanted]
    assert ours.stdout.count("NO MATCH") == sum(w.startswith("NO MATCH") for w in wanted) > 0


@pytest.mark.parametrize("expr, error", [
    ("m.data >", "rostui bag filter: invalid expression 'm.data >'"),
    ("m.data > 1", "rostui bag filter: the expression failed on /chatter at 100.250000000: TypeError"),
    ("m.no_such_field", "rostui bag filter: the expression failed on /chatter at 100.250000000: AttributeError"),
])
def test_a_bad_expression_is_one_line_and_leaves_no_file(bag: Path, tmp_path: Path, ros_env: dict[str, str],
                                                         expr: str, error: str) -> None:
    folder = tmp_path / "here"
    folder.mkdir()
    out = folder / "out.bag"
    ours = rostui(["bag", "filter", str(bag), str(out), expr], ros_env)
    assert ours.returncode == 1
    assert ours.stderr.startswith(error) and ours.stderr.count("\n") == 1, ours.stderr
    assert list(folder.iterdir()) == []  # neither OUT nor a partial file
    out.write_bytes(b"kept as it was")
    again = rostui(["bag", "filter", str(bag), str(out), expr], ros_env)
    assert again.returncode == 1
    assert out.read_bytes() == b"kept as it was"
    assert list(folder.iterdir()) == [out]


def test_filter_refuses_its_input_as_output(bag: Path, ros_env: dict[str, str]) -> None:
    before = bag.read_bytes()
    ours = rostui(["bag", "filter", str(bag), str(bag), "True"], ros_env)
    assert ours.returncode == 1
    assert ours.stderr == f"rostui bag filter: cannot use the same file as input and output: {bag}\n"
    assert bag.read_bytes() == before


# ----------------------------------------------------------------------------- bag compress / decompress
COMPRESSION_LINE = re.compile(r"^compression:\s+(\S+)", re.M)


def _rosbag_compression(path: Path, env: dict[str, str]) -> str:
    info = subprocess.run(["rosbag", "info", str(path)], env=env, capture_output=True, text=True, timeout=60)
    assert info.returncode == 0, info.stderr
    found = COMPRESSION_LINE.search(info.stdout)
    assert found, info.stdout
    return found.group(1)


@pytest.mark.parametrize("flags, kind", [([], "bz2"), (["-j"], "bz2"), (["--lz4"], "lz4")])
def test_compress_in_place_as_rosbag_compress(bag: Path, tmp_path: Path, ros_env: dict[str, str],
                                             flags: list[str], kind: str) -> None:
    need_command("rosbag")
    original = bag.read_bytes()
    for who in ("ours", "theirs"):
        (tmp_path / f"{who}.bag").write_bytes(original)
    theirs = subprocess.run(["rosbag", "compress", "-q", *flags, str(tmp_path / "theirs.bag")], env=ros_env,
                            capture_output=True, text=True, timeout=120)
    assert theirs.returncode == 0, theirs.stderr
    ours = rostui(["bag", "compress", *flags, str(tmp_path / "ours.bag")], ros_env)
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout == ours.stderr == ""
    assert (tmp_path / "ours.orig.bag").read_bytes() == original
    assert _rosbag_compression(tmp_path / "ours.bag", ros_env) == _rosbag_compression(tmp_path / "theirs.bag",
                                                                                       ros_env) == kind
    assert dump(tmp_path / "ours.bag") == dump(tmp_path / "theirs.bag") == dump(bag)

    # the backup exists now: skipped with rosbag's line, unless forced
    again = rostui(["bag", "decompress", str(tmp_path / "ours.bag")], ros_env)
    assert again.returncode == 0
    assert again.stderr == f"Skipping {tmp_path / 'ours.bag'}. Backup path {tmp_path / 'ours.orig.bag'} already exists.\n"
    assert _rosbag_compression(tmp_path / "ours.bag", ros_env) == kind
    forced = rostui(["bag", "decompress", "-f", str(tmp_path / "ours.bag")], ros_env)
    assert forced.returncode == 0, forced.stderr
    assert _rosbag_compression(tmp_path / "ours.bag", ros_env) == "none"
    assert _rosbag_compression(tmp_path / "ours.orig.bag", ros_env) == kind
    assert dump(tmp_path / "ours.bag") == dump(bag)


def test_decompress_a_rosbag_compressed_bag_into_another_folder(bag: Path, tmp_path: Path,
                                                                ros_env: dict[str, str]) -> None:
    need_command("rosbag")
    src = tmp_path / "in.bag"
    src.write_bytes(bag.read_bytes())
    packed = subprocess.run(["rosbag", "compress", "-q", "--lz4", str(src)], env=ros_env, capture_output=True,
                            text=True, timeout=120)
    assert packed.returncode == 0, packed.stderr
    before = src.read_bytes()
    (tmp_path / "out").mkdir()
    ours = rostui(["bag", "decompress", "--output-dir", str(tmp_path / "out"), str(src)], ros_env)
    assert ours.returncode == 0, ours.stderr
    assert src.read_bytes() == before  # another folder: no backup, the input untouched
    assert not (tmp_path / "in.orig.orig.bag").exists()
    assert _rosbag_compression(tmp_path / "out" / "in.bag", ros_env) == "none"
    assert dump(tmp_path / "out" / "in.bag") == dump(bag)


def test_mcap_compresses_with_zstd_or_lz4_and_decompresses(bag: Path, tmp_path: Path,
                                                           ros_env: dict[str, str]) -> None:
    mcap = tmp_path / "shapes.mcap"
    mcap.write_bytes(bag.with_suffix(".mcap").read_bytes())
    want = our_dump(mcap)
    for args, kind in ((["compress"], "zstd"), (["compress", "-f", "--lz4"], "lz4"), (["decompress", "-f"], None)):
        ours = rostui(["bag", *args, str(mcap)], ros_env)
        assert ours.returncode == 0, ours.stderr
        reader = open_reader(str(mcap))
        kinds = set(reader.summary().chunk_compression)
        reader.close()
        assert kinds == {kind or "none"}, args
        assert our_dump(mcap) == want
    assert (tmp_path / "shapes.orig.mcap").exists()


def test_compress_of_what_is_no_bag_is_one_line_and_the_rest_still_done(bag: Path, tmp_path: Path,
                                                                        ros_env: dict[str, str]) -> None:
    good = tmp_path / "good.bag"
    good.write_bytes(bag.read_bytes())
    (tmp_path / "bad.bag").write_text("not a bag\n")
    ours = rostui(["bag", "compress", str(tmp_path / "bad.bag"), str(tmp_path / "missing.bag"), str(good)],
                  ros_env)
    assert ours.returncode == 1
    assert ours.stderr.splitlines() == [
        f"rostui bag compress: {tmp_path / 'bad.bag'} is neither an MCAP file nor a rosbag file (unknown first bytes)",
        f"rostui bag compress: {tmp_path / 'missing.bag'}: no such file",
    ]
    assert (tmp_path / "bad.bag").read_text() == "not a bag\n" and not (tmp_path / "bad.orig.bag").exists()
    assert (tmp_path / "good.orig.bag").exists()


# ----------------------------------------------------------------------------- the progress bar
def test_no_progress_bar_when_stderr_is_no_terminal(bag: Path, tmp_path: Path, ros_env: dict[str, str]) -> None:
    for args in (["convert", str(bag), str(tmp_path / "c.mcap")], ["filter", str(bag), str(tmp_path / "f.bag"), "True"],
                 ["reindex", str(tmp_path / "f.bag")], ["compress", "-f", str(tmp_path / "f.bag")],
                 ["decompress", "-f", str(tmp_path / "c.mcap")]):
        ours = rostui(["bag", *args], ros_env)
        assert ours.returncode == 0, ours.stderr
        assert ours.stderr == "", args


@pytest.mark.parametrize("command", ["filter", "compress", "convert", "reindex"])
def test_a_progress_bar_on_a_terminal(command: str, tmp_path: Path) -> None:
    src = make_bag(tmp_path / "big.bag", rounds=3000, order="time")
    args = {"filter": ["big.bag", "out.bag", "topic != '/pose'"], "compress": ["--lz4", "big.bag"],
            "convert": ["big.bag", "out.mcap"], "reindex": ["big.bag"]}[command]
    total = len(dump(src))
    line = shlex.join([sys.executable, "-m", "rostui", "bag", command, *args]) + " > /dev/null; echo EXIT=$?"
    done = re.compile(r"^EXIT=(\d+)\s*$", re.M)
    with shell_pane("bagprogress", 160, 20) as pane:
        pane.type(f"cd {shlex.quote(str(tmp_path))} && clear")
        pane.type(line)
        pane.wait_until(lambda: done.search(pane.screen()) is not None, "the command to finish")
        screen = pane.screen()
    finished = done.search(screen)
    assert finished is not None and finished.group(1) == "0", screen
    bar = [row for row in screen.splitlines() if f"{total}/{total} msgs" in row]
    assert bar, screen
    assert "100%" in bar[-1], bar[-1]
    assert bar[-1].split()[0] == ("out.bag" if command == "filter" else "out.mcap" if command == "convert"
                                  else "big.bag"), bar[-1]


# ----------------------------------------------------------------------------- Ctrl-C
def _counts_bag(path: Path, count: int) -> None:
    """``count`` Int32 messages on /count, written by rostui (a bag big enough to be interrupted mid-way)."""
    from rostui.core.bag.model import Connection
    from rostui.core.msg import get_message_class

    Int32 = get_message_class("std_msgs/Int32")
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/count", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/counter"))
    for i in range(count):
        writer.write(0, 10**18 + i * 1000, Int32(data=i).serialize())
    writer.close()


@pytest.fixture(scope="session")
def big_counts_bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A bag of 2,000,000 Int32 messages, written once per run and shared read-only (copy it before changing it):
    filter and compress spend about 25 s on it on a quiet machine, so Ctrl-C always lands mid-way."""
    from conftest import shared_build

    return shared_build(tmp_path_factory, "counts_2m", lambda folder: _counts_bag(folder / "counts.bag",
                                                                                 2_000_000)) / "counts.bag"


@pytest.mark.parametrize("command", ["filter", "compress"])
def test_ctrl_c_leaves_no_half_file_and_the_original_as_it_was(command: str, tmp_path: Path, ros_env: dict[str, str],
                                                               big_counts_bag: Path) -> None:
    import shutil
    import signal
    import time

    from conftest import wait_until

    src = tmp_path / "counts.bag"
    shutil.copyfile(big_counts_bag, src)
    before = src.read_bytes()
    args = {"filter": [str(src), str(tmp_path / "out.bag"), "m.data % 3 == 0"], "compress": [str(src)]}[command]
    started = time.monotonic()
    proc = subprocess.Popen([sys.executable, "-m", "rostui", "bag", command, *args], env=ros_env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        wait_until(lambda: any(p.name.endswith(".partial") for p in tmp_path.iterdir()) or proc.poll() is not None,
                   "the new file to be started")
        assert proc.poll() is None, "finished before it could be interrupted"
        signalled = time.monotonic() - started
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 1, (f"Ctrl-C {signalled:.1f} s after the start: status {proc.returncode}, "
                                  f"out {out!r}, err {err!r}, files {sorted(p.name for p in tmp_path.iterdir())}")
    assert err.startswith(f"rostui bag {command}: interrupted; ") and err.count("\n") == 1, err
    assert sorted(p.name for p in tmp_path.iterdir() if p.name != "ros_home") == ["counts.bag"]
    assert src.read_bytes() == before


def test_a_ctrl_c_inside_text_run_from_a_string_still_exits_1_under_python_m(tmp_path: Path,
                                                                             ros_env: dict[str, str]) -> None:
    """CPython notes a KeyboardInterrupt that leaves ``exec``'d text even once it is handled, and a ``python -m``
    run ending with the note set killed itself with SIGINT after printing its one line (status -2, a fresh-ci
    flake when Ctrl-C landed in such text). The expression stands for any such text."""
    src = tmp_path / "counts.bag"
    _counts_bag(src, 10)
    done = subprocess.run([sys.executable, "-m", "rostui", "bag", "filter", str(src), str(tmp_path / "out.bag"),
                           'exec("raise KeyboardInterrupt")'], env=ros_env, capture_output=True, text=True,
                          timeout=60)
    assert (done.returncode, done.stderr) == (1, f"rostui bag filter: interrupted; {tmp_path / 'out.bag'} not written\n")
    assert sorted(p.name for p in tmp_path.iterdir() if p.name != "ros_home") == ["counts.bag"]


def test_ctrl_c_while_the_new_file_is_made_leaves_no_partial_file(tmp_path: Path,
                                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    """Ctrl-C after the writer made its file but before it returned (a fresh-ci run left the file behind)."""
    from rostui.tools.bag import rewrite

    class InterruptedWriter(rewrite.BagWriter):
        def __init__(self, path: str, **options: Any) -> None:
            super().__init__(path, **options)
            raise KeyboardInterrupt

    monkeypatch.setattr(rewrite, "BagWriter", InterruptedWriter)
    with pytest.raises(KeyboardInterrupt):
        with rewrite.new_file(str(tmp_path / "out.bag")):
            pass
    assert list(tmp_path.iterdir()) == []



@pytest.mark.parametrize("command", ["filter", "compress"])
def test_ctrl_c_during_a_lazy_import_is_still_an_interrupt(command: str, tmp_path: Path,
                                                           monkeypatch: pytest.MonkeyPatch,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    from rostui.cli import bag_cmd
    from rostui.tools.bag import compress, filter as bag_filter

    def interrupted_in_import(*_args: Any, **_kwargs: Any) -> None:
        raise interrupted_import()

    monkeypatch.setattr(bag_filter, "filter_bag", interrupted_in_import)
    monkeypatch.setattr(compress, "change_compression", interrupted_in_import)
    src = tmp_path / "counts.bag"
    with pytest.raises(SystemExit) as stopped:
        if command == "filter":
            bag_cmd.run_filter(str(src), str(tmp_path / "out.bag"), "True", None)
        else:
            bag_cmd.run_change_compression(command, [str(src)], "lz4", None, False, True)
    assert stopped.value.code == 1
    err = capsys.readouterr().err
    assert err.startswith(f"rostui bag {command}: interrupted; ") and err.count("\n") == 1, err

