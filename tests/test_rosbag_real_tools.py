"""rosbag's own bag scripts (ros_comm tools/rosbag/scripts), unmodified, under Debian's rosbag and `rostui python`.

Each script runs on the same input bag (written by Debian's rosbag) under both; what it prints must be the
same, and every bag it writes must pass Debian's `rosbag check`, show the same topics, types and counts in
Debian's `rosbag info`, and hold the same messages (topic, type, md5sum, time stamp, serialised bytes, in
order) when Debian's rosbag reads it. rostui also runs the scripts that only read on an MCAP copy of the input
(Debian's rosbag cannot read MCAP): their output must be what Debian printed for the .bag.
"""

from __future__ import annotations

import subprocess
import textwrap
from pathlib import Path
from typing import Any

import pytest

from conftest import need_peer
from test_rosbag_shim import REAL, WRITE_BAG, _env, _ours, _real, _rosbag_ok

# Every message of a bag as Debian's rosbag reads it, and the connections per topic.
DUMP = textwrap.dedent('''
    import sys, rosbag
    with rosbag.Bag(sys.argv[1]) as bag:
        for topic, (datatype, data, md5sum, _pos, pytype), t in bag.read_messages(raw=True):
            print(topic, datatype, md5sum, t.to_nsec(), data.hex())
        for topic, info in sorted(bag.get_type_and_topic_info().topics.items()):
            print(topic, info.msg_type, info.message_count, info.connections)
''')

@pytest.fixture
def inputs(tmp_path: Path) -> Path:
    """``in.bag`` written by Debian's rosbag, ``in.mcap`` (the same messages) by rostui's, and the dump script."""
    need_peer(_rosbag_ok(), "Debian's rosbag under /usr/bin/python3 (python3-rosbag, python3-geometry-msgs)")
    (tmp_path / "write_bag.py").write_text(WRITE_BAG)
    (tmp_path / "dump.py").write_text(DUMP)
    _real(["write_bag.py", "in.bag"], tmp_path)
    _ours(["write_bag.py", "in.mcap"], tmp_path)
    return tmp_path


def _checked(bag: Path) -> tuple[str, list[str]]:
    """The bag's messages as Debian's rosbag reads them, and `rosbag info`'s topic and type lines; `rosbag check`
    must pass."""
    check = subprocess.run(["rosbag", "check", bag.name], env=_env(), cwd=bag.parent, capture_output=True,
                           text=True, timeout=120)
    assert check.returncode == 0 and "does not need any migrations" in check.stdout, check.stdout + check.stderr
    info = subprocess.run(["rosbag", "info", bag.name], env=_env(), cwd=bag.parent, capture_output=True, text=True,
                          timeout=120)
    assert info.returncode == 0, info.stderr
    keep = ("messages:", "types:", "topics:", " ")
    lines = [line.split(":", 1)[1].strip() if ":" in line else line.strip()
             for line in info.stdout.splitlines() if line.startswith(keep)]
    return _real([str(bag.parent.parent / "dump.py"), bag.name], bag.parent), lines


def _run_both(inputs: Path, script: str, args: list[str], outputs: list[str]) -> dict[str, tuple[str, list[Any]]]:
    runs: dict[str, tuple[str, list[Any]]] = {}
    for who, run in (("debian", _real), ("rostui", _ours)):
        where = inputs / who
        where.mkdir()
        (where / "in.bag").write_bytes((inputs / "in.bag").read_bytes())
        printed = run([str(REAL / script), *args], where)
        runs[who] = printed, [_checked(where / name) for name in outputs]
    return runs


def test_fastrebag_copies_every_message(inputs: Path) -> None:
    runs = _run_both(inputs, "fastrebag.py", ["in.bag", "out.bag"], ["out.bag"])
    assert runs["rostui"] == runs["debian"]
    dump, info = runs["debian"][1][0]
    assert len(dump.splitlines()) == 90 + 3 and "90" in info


def test_bagsort_prints_the_schedule_and_writes_in_time_order(inputs: Path) -> None:
    runs = _run_both(inputs, "bagsort.py", ["in.bag", "sorted.bag"], ["sorted.bag"])
    assert runs["rostui"] == runs["debian"]
    assert runs["debian"][0].startswith("[0, 1, 2, ")


def test_topic_renamer_renames_one_topic(inputs: Path) -> None:
    runs = _run_both(inputs, "topic_renamer.py", ["/numbers", "in.bag", "/renamed", "out.bag"], ["out.bag"])
    assert runs["rostui"] == runs["debian"]
    dump = runs["debian"][1][0][0]
    assert "/renamed std_msgs/Int32 30 1" in dump and "/numbers" not in dump


def test_fix_md5sums_rewrites_in_place_and_keeps_the_original(inputs: Path) -> None:
    runs = _run_both(inputs, "fix_md5sums.py", ["in.bag"], ["in.bag", "in.bag.old"])
    assert runs["rostui"] == runs["debian"]
    assert "Migration successful.  Original stored as: in.bag.old" in runs["debian"][0]
    (new, _), (old, _) = runs["debian"][1]
    assert new == old


@pytest.mark.parametrize("args", [["-b", "{bag}", "geometry_msgs/PoseStamped"], ["std_msgs/Header"],
                                  ["-b", "{bag}", "std_msgs/String"]])
def test_savemsg_prints_definitions(inputs: Path, args: list[str]) -> None:
    script = str(REAL / "savemsg.py")
    real = _real([script, *[a.format(bag="in.bag") for a in args]], inputs)
    assert real.startswith(f"[{args[-1]}]:\n") and len(real.splitlines()) > 2
    assert _ours([script, *[a.format(bag="in.bag") for a in args]], inputs) == real
    if "{bag}" in args:
        assert _ours([script, *[a.format(bag="in.mcap") for a in args]], inputs) == real


def test_scripts_read_mcap_and_write_bags_debian_reads(inputs: Path) -> None:
    """fastrebag and topic_renamer read the MCAP copy under rostui; the .bag files they write hold what
    Debian's rosbag wrote from the .bag."""
    for script, args in (("fastrebag.py", ["{src}", "out.bag"]),
                         ("topic_renamer.py", ["/pose", "{src}", "/moved", "out.bag"])):
        where = {"debian": inputs / f"d-{script}", "rostui": inputs / f"r-{script}"}
        for who, src in (("debian", "in.bag"), ("rostui", "in.mcap")):
            where[who].mkdir()
            (where[who] / src).write_bytes((inputs / src).read_bytes())
            run = _real if who == "debian" else _ours
            run([str(REAL / script), *[a.format(src=src) for a in args]], where[who])
        assert _checked(where["rostui"] / "out.bag") == _checked(where["debian"] / "out.bag")
