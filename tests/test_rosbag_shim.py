"""`rostui python`'s rosbag: real bag scripts give the same output as under Debian's rosbag, on the same bags.

The input bag is written by Debian's rosbag (/usr/bin/python3); bags written by rostui's rosbag are
checked with Debian's `rosbag check` and read back with Debian's rosbag. An MCAP copy is read by the
shim only: Debian's rosbag cannot read MCAP.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_peer

REAL = REPO / "tests" / "python_compat" / "rosbag_real"

# Writes a bag through whichever rosbag the interpreter has: several topics, types, equal time stamps,
# a type with a header, and a custom type whose package no one has (only the bag's definition knows it).
WRITE_BAG = textwrap.dedent('''
    import sys, rosbag, genpy
    from std_msgs.msg import Int32, String, Header
    from geometry_msgs.msg import PoseStamped
    compression = sys.argv[2] if len(sys.argv) > 2 else rosbag.Compression.NONE
    with rosbag.Bag(sys.argv[1], 'w', compression=compression) as bag:
        for i in range(30):
            bag.write('/chatter', String(data='hello %d' % i), genpy.Time(1000 + i * 0.1))
            bag.write('/numbers', Int32(data=i * 7), genpy.Time(1000 + i * 0.25))
            pose = PoseStamped()
            pose.header.seq = i
            pose.header.stamp = genpy.Time(1000, i)
            pose.header.frame_id = 'map'
            pose.pose.position.x = i / 3.0
            pose.pose.orientation.w = 1.0
            bag.write('/pose', pose, genpy.Time(1000 + i * 0.5))
''')

# A bag of types no package on this machine has (their classes come from the definitions in the bag only):
# Debian's genpy builds the classes from the text, as rosbag itself does when it reads such a bag.
WRITE_CUSTOM_BAG = textwrap.dedent('''
    import sys, rosbag, genpy, genpy.dynamic
    from std_msgs.msg import Int32
    definition = """Header header
    Reading[] readings
    string label
    ================================================================================
    MSG: std_msgs/Header
    uint32 seq
    time stamp
    string frame_id
    ================================================================================
    MSG: lab_sensors/Reading
    float64 value
    uint8 quality
    uint8 GOOD=1
    """
    classes = genpy.dynamic.generate_dynamic('lab_sensors/Sample', definition)
    Sample, Reading = classes['lab_sensors/Sample'], classes['lab_sensors/Reading']
    with rosbag.Bag(sys.argv[1], 'w') as bag:
        for i in range(12):
            s = Sample(label='s%d' % i, readings=[Reading(value=i * 0.5 + k, quality=k) for k in range(i % 3)])
            s.header.seq, s.header.stamp, s.header.frame_id = i, genpy.Time(50, i), 'lab'
            bag.write('/samples', s, genpy.Time(50 + i * 0.2))
            bag.write('/numbers', Int32(data=i), genpy.Time(50 + i * 0.3))
''')

# rosbag's own calls, printed: counts, topic info, times, filters, raw tuples, a rewrite into a new bag.
SUMMARY = textwrap.dedent('''
    import sys, rosbag, genpy
    with rosbag.Bag(sys.argv[1]) as bag:
        print(bag.get_message_count(), bag.get_message_count('/numbers'), bag.get_message_count(['/pose', '/x']))
        info = bag.get_type_and_topic_info()
        print(sorted(info.msg_types.items()))
        for topic, t in sorted(info.topics.items()):
            print(topic, t.msg_type, t.message_count, t.connections, t.frequency)
        print(bag.get_type_and_topic_info('/chatter'))
        print('%.9f %.9f' % (bag.get_start_time(), bag.get_end_time()))
        print([m.message.data for m in bag.read_messages('/numbers', genpy.Time(1001), genpy.Time(1002.5))])
        print([t.to_nsec() for _, _, t in bag.read_messages(topics=['/chatter', '/pose'], end_time=genpy.Time(1000.5))])
        print(len(list(bag.read_messages(start_time=genpy.Time(0), end_time=genpy.Time(0)))))
        sel = bag.read_messages(connection_filter=lambda topic, datatype, md5sum, msg_def, header:
                                datatype == 'geometry_msgs/PoseStamped')
        print([(m.topic, m.message.header.seq) for m in sel][:5])
        for topic, raw, t in bag.read_messages(raw=True):
            datatype, data, md5sum, position, pytype = raw
            print(topic, datatype, data.hex(), md5sum, pytype._type, t.secs, t.nsecs)
            break
        with rosbag.Bag(sys.argv[2], 'w') as out:
            for topic, msg, t in bag.read_messages():
                if topic == '/pose':
                    out.write('/pose_copy', msg, msg.header.stamp if msg._has_header else t)
                elif topic == '/numbers':
                    out.write(topic, msg, t)
''')


def _env() -> dict[str, str]:
    return {k: v for k, v in os.environ.items()
            if k not in ("PYTHONPATH", "ROS_PACKAGE_PATH") and not k.startswith("ROSTUI_PYTHON")}


def _rosbag_ok() -> bool:
    return Path(SYSTEM_PYTHON).exists() and subprocess.run(
        [SYSTEM_PYTHON, "-c", "import rosbag, genpy, std_msgs.msg, geometry_msgs.msg"],
        capture_output=True).returncode == 0


def _real(args: list[str], cwd: Path) -> str:
    r = subprocess.run([SYSTEM_PYTHON, *args], env=_env(), cwd=cwd, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    return r.stdout


def _ours(args: list[str], cwd: Path) -> str:
    r = subprocess.run([sys.executable, "-m", "rostui", "python", "--rostui", *args], env=_env(), cwd=cwd,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    return r.stdout


@pytest.fixture
def bags(tmp_path: Path) -> Path:
    """A directory holding ``real.bag``, written by Debian's rosbag, and the scripts above."""
    need_peer(_rosbag_ok(), "Debian's rosbag under /usr/bin/python3 (python3-rosbag, python3-geometry-msgs)")
    (tmp_path / "write_bag.py").write_text(WRITE_BAG)
    (tmp_path / "summary.py").write_text(SUMMARY)
    (tmp_path / "write_custom.py").write_text(WRITE_CUSTOM_BAG)
    _real(["write_bag.py", "real.bag"], tmp_path)
    return tmp_path


@pytest.mark.parametrize("topics", [[], ["/numbers", "/pose"]])
def test_ros_readbagfile_same_output(bags: Path, topics: list[str]) -> None:
    script = str(REAL / "ros_readbagfile.py")
    real = _real([script, "real.bag", *topics], bags)
    assert "# Total messages found:" in real and "frame_id: \"map\"" in real or topics == ["/numbers"]
    assert _ours([script, "real.bag", *topics], bags) == real


REWRITES = [("topic_extracter.py", ["/numbers", "/pose"]), ("topic_deleter.py", ["/chatter"]),
            ("crop_bag.py", ["10", "25"]), ("remove_first_x_second_of_bag_.py", ["3"])]


@pytest.mark.parametrize("script,args", REWRITES, ids=[name for name, _ in REWRITES])
def test_real_rewrite_scripts_write_the_same_bags(bags: Path, script: str, args: list[str]) -> None:
    """Each script rewrites the same input under both; what it prints and what its new bag holds agree."""
    readback = str(REAL / "ros_readbagfile.py")
    runs = {}
    for who, run in (("debian", _real), ("rostui", _ours)):
        where = bags / who
        where.mkdir()
        (where / "in.bag").write_bytes((bags / "real.bag").read_bytes())
        printed = run([str(REAL / script), "in.bag", "out.bag", *args], where)
        runs[who] = printed, _real([readback, "out.bag"], where), _ours([readback, "out.bag"], where)
    assert runs["rostui"] == runs["debian"]
    def total(text: str) -> str:
        return next(line for line in text.splitlines() if line.startswith("# Total messages found:"))

    assert 0 < int(total(runs["debian"][1]).split()[-1]) < 90  # the script kept some messages, not all


def test_types_known_only_from_the_bag(bags: Path) -> None:
    """Messages of a package no one has decode through the bag's definitions, print and rewrite the same."""
    _real(["write_custom.py", "custom.bag"], bags)
    script = str(REAL / "ros_readbagfile.py")
    real = _real([script, "custom.bag"], bags)
    assert "label: \"s11\"" in real and "quality: 1" in real
    assert _ours([script, "custom.bag"], bags) == real
    rewrite = textwrap.dedent('''
        import sys, rosbag
        with rosbag.Bag(sys.argv[1]) as bag, rosbag.Bag(sys.argv[2], 'w') as out:
            for topic, msg, t in bag.read_messages(topics='/samples'):
                print(msg._type, msg._md5sum, len(msg.readings), msg.readings[0].GOOD if msg.readings else '-')
                out.write('/copy', msg, t)
            for topic, raw, t in bag.read_messages(topics=['/numbers'], raw=True):
                out.write('/raw_numbers', raw, t, raw=True)
    ''')
    (bags / "rewrite.py").write_text(rewrite)
    real_rewrite = _real(["rewrite.py", "custom.bag", "copy.bag"], bags)
    real_copy = _real([script, "copy.bag"], bags)
    assert _ours(["rewrite.py", "custom.bag", "copy.bag"], bags) == real_rewrite
    assert _real([script, "copy.bag"], bags) == real_copy  # rostui's copy, read by Debian's rosbag


def test_summary_and_rewrite_same_output(bags: Path) -> None:
    readback = str(REAL / "ros_readbagfile.py")
    real = _real(["summary.py", "real.bag", "out.bag"], bags)
    real_out = _real([readback, "out.bag"], bags)
    (bags / "out.bag").rename(bags / "debian_out.bag")
    assert _ours(["summary.py", "real.bag", "out.bag"], bags) == real
    assert _ours([readback, "out.bag"], bags) == real_out
    assert _real([readback, "out.bag"], bags) == real_out


@pytest.mark.parametrize("compression", ["none", "bz2", "lz4"])
def test_shim_written_bag_checks_and_reads_in_real_rosbag(bags: Path, compression: str) -> None:
    _ours(["write_bag.py", "ours.bag", compression], bags)
    check = subprocess.run(["rosbag", "check", "ours.bag"], env=_env(), cwd=bags, capture_output=True, text=True,
                           timeout=120)
    assert check.returncode == 0 and "does not need any migrations" in check.stdout, check.stdout + check.stderr
    info = subprocess.run(["rosbag", "info", "ours.bag"], env=_env(), cwd=bags, capture_output=True, text=True,
                          timeout=120)
    fields = dict(line.split(":", 1) for line in info.stdout.splitlines() if ":" in line and line[0] != " ")
    assert info.returncode == 0 and fields["messages"].strip() == "90", info.stdout + info.stderr
    if compression != "none":
        assert fields["compression"].split()[0] == compression, info.stdout
    script = str(REAL / "ros_readbagfile.py")
    expected = _real([script, "real.bag"], bags), _real(["summary.py", "real.bag", "o.bag"], bags)
    (bags / "real.bag").rename(bags / "debian.bag")
    (bags / "ours.bag").rename(bags / "real.bag")
    assert (_real([script, "real.bag"], bags), _real(["summary.py", "real.bag", "o.bag"], bags)) == expected


def test_mcap_reads_like_the_bag(bags: Path) -> None:
    """rostui's rosbag on an MCAP copy prints what Debian's rosbag prints for the .bag (it cannot read MCAP)."""
    script = str(REAL / "ros_readbagfile.py")
    expected = _real([script, "real.bag"], bags), _real(["summary.py", "real.bag", "o.bag"], bags)
    _ours(["write_bag.py", "ours.mcap"], bags)
    assert (bags / "ours.mcap").read_bytes()[:8] == b"\x89MCAP0\r\n"
    (bags / "ours.mcap").replace(bags / "real.bag")  # the same name: the script prints it
    assert _ours([script, "real.bag"], bags) == expected[0]
    assert _ours(["summary.py", "real.bag", "o.bag"], bags) == expected[1]


def test_errors_and_modes(bags: Path) -> None:
    probe = textwrap.dedent('''
        import rosbag
        from std_msgs.msg import Int32
        for args in [('missing.bag',), ('summary.py',), ('empty.bag',), ('unindexed.bag',)]:
            try:
                rosbag.Bag(*args)
            except (rosbag.ROSBagException, OSError) as e:
                print(type(e).__name__, isinstance(e, rosbag.ROSBagException))
        try:
            rosbag.Bag('x.bag', 'q')
        except ValueError:
            print('ValueError')
        with rosbag.Bag('real.bag', 'a') as bag:
            bag.write('/added', Int32(data=5))
        with rosbag.Bag('real.bag') as bag:
            print(bag.mode, bag.filename, bag.size > 0, bag.get_message_count(), bag.get_message_count('/added'))
        b = rosbag.Bag('real.bag')
        b.close()
        try:
            b.write('/x', Int32())
        except ValueError:
            print('closed')
    ''')
    (bags / "probe.py").write_text(probe)
    (bags / "empty.bag").write_bytes(b"")
    # a bag cut short before its index, as a recorder killed mid-way leaves it (rosbag says: unindexed)
    data = (bags / "real.bag").read_bytes()
    (bags / "unindexed.bag").write_bytes(data[:data.rindex(b"op=\x07") - 64])
    ours = _ours(["probe.py"], bags)
    appended = _real(["-c", "import rosbag; print(rosbag.Bag('real.bag').get_message_count('/added'))"], bags)
    assert appended == "1\n"  # the bag rostui's rosbag appended to reads in Debian's
    _real(["write_bag.py", "real.bag"], bags)
    assert ours == _real(["probe.py"], bags)
    assert ours.splitlines()[-2:] == ["r real.bag True 91 1", "closed"]


def test_a_real_rosbag_wins_by_default(bags: Path) -> None:
    """Debian's python3 with shell-env's path gets Debian's rosbag, one line on stderr saying so; the script's
    output is what `rostui python --rostui` prints with rostui's."""
    script = bags / "which_rosbag.py"
    script.write_text("import rosbag\nprint(rosbag.__file__)\n")
    readbag = str(REAL / "ros_readbagfile.py")
    exports = subprocess.run([sys.executable, "-m", "rostui", "shell-env"], env=_env(), cwd=REPO,
                             capture_output=True, text=True, timeout=60).stdout
    runs = [subprocess.run(["bash", "-c", f'{exports}\nexec "$0" "$@"', SYSTEM_PYTHON, *cmd], env=_env(),
                           cwd=bags, capture_output=True, text=True, timeout=120)
            for cmd in ([str(script)], [readbag, "real.bag"])]
    for r in runs:
        assert r.returncode == 0, r.stderr
        assert len(r.stderr.splitlines()) == 1 and "gets the real ROS at " in r.stderr, r.stderr
    assert "/dist-packages/rosbag/" in runs[0].stdout and "/rostui/" not in runs[0].stdout
    assert _ours([readbag, "real.bag"], bags) == runs[1].stdout
    assert "/rostui/compat/pylib/rosbag/" in _ours([str(script)], bags)
