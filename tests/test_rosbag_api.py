"""rosbag's Bag API as scripts see it: the same printed answers under Debian's rosbag and `rostui python`.

The probes below print what rosbag returns or raises for each call: a bag read while it is written, a closed
bag, the message tuples and their time stamps (type and ``repr()``), connection headers, raw tuples, file
objects, appending, reindexing a bag whose index is missing, and the errors. Each runs under both and the
outputs must be equal. Appending continues the file in place: the bytes before the old index stay as they were.
"""

from __future__ import annotations

import io
import os
import struct
import textwrap
from pathlib import Path

import pytest

from conftest import need_peer
from test_rosbag_shim import WRITE_BAG, _ours, _real, _rosbag_ok

API_PROBE = textwrap.dedent('''
import io, os, sys, rosbag, genpy
from std_msgs.msg import Int32, String


def attempt(label, f):
    try:
        print(label, 'ok', repr(f()))
    except Exception as e:
        print(label, type(e).__name__, e)


def show(bag, **kw):
    return [(m.topic, m.message, m.timestamp) for m in bag.read_messages(**kw)]


# a bag being written answers questions about what it holds so far
bag = rosbag.Bag('w.bag', 'w')
attempt('empty start', bag.get_start_time)
attempt('empty end', bag.get_end_time)
attempt('empty compression', bag.get_compression_info)
attempt('empty count', bag.get_message_count)
attempt('empty info', bag.get_type_and_topic_info)
attempt('empty read', lambda: show(bag))
bag.write('/a', Int32(5), genpy.Time(3, 4))
bag.write('/b', String('x'), genpy.Time(2, 4))
attempt('written read', lambda: show(bag))
attempt('written count', bag.get_message_count)
attempt('written span', lambda: (bag.get_start_time(), bag.get_end_time()))
bag.write('/a', Int32(6), genpy.Time(5, 4))
attempt('written read2', lambda: show(bag, topics='/a'))
bag.write('/a', Int32(7), genpy.Time(6))
bag.close()
bag.close()
attempt('closed size', lambda: bag.size)
attempt('closed read', lambda: show(bag))
attempt('closed write', lambda: bag.write('/a', Int32(1), genpy.Time(1)))
attempt('closed flush', bag.flush)
attempt('closed count', bag.get_message_count)
attempt('closed start', bag.get_start_time)

with rosbag.Bag('w.bag') as bag:
    first = next(iter(bag))
    print(type(first).__name__, type(first).__module__, first._fields, type(first.timestamp).__module__,
          type(first.timestamp).__name__, repr(first.timestamp))
    print(repr(first))
    attempt('read-only write', lambda: bag.write('/a', Int32(1), genpy.Time(1)))
    attempt('compression', bag.get_compression_info)
    attempt('options', lambda: bag.options)
    attempt('mode', lambda: bag.mode)
    m = next(bag.read_messages(return_connection_header=True))
    print(type(m).__name__, m._fields, sorted(m.connection_header.items()))
    m = next(bag.read_messages(raw=True))
    print(m.message[0], m.message[1], m.message[2], m.message[3], m.message[4]._type)
    seen = []
    print(show(bag, connection_filter=lambda topic, datatype, md5sum, msg_def, header:
                    seen.append(sorted(header.items())) or datatype == 'std_msgs/Int32'))
    print(sorted(seen))
    print(show(bag, topics=['/a/', '//b']))

# file objects: a named file, a stream with no name
with open('w.bag', 'rb') as f:
    bag = rosbag.Bag(f)
    print(bag.filename, bag.get_message_count(), show(bag, topics='/b'))
    bag.close()
    print('stream closed by close():', f.closed)
with open('fobj.bag', 'wb') as f:
    with rosbag.Bag(f, 'w') as bag:
        bag.write('/f', Int32(1), genpy.Time(1))
        bag.write('/f', Int32(2), genpy.Time(2))
    print('written through a file object, closed:', f.closed)
with rosbag.Bag('fobj.bag') as bag:
    print(show(bag))
attempt('text-mode write', lambda: rosbag.Bag(open('text.bag', 'w'), 'w'))

# appending: read what was there, write more, read all of it
with rosbag.Bag('w.bag', 'a') as bag:
    attempt('append read', lambda: show(bag))
    bag.write('/c', Int32(7), genpy.Time(9))
    bag.write('/a', Int32(8), genpy.Time(1, 5))
    attempt('append read2', lambda: [(m.topic, m.timestamp) for m in bag.read_messages()])
    attempt('append count', bag.get_message_count)
    bag.write('/c', Int32(9), genpy.Time(10))
with rosbag.Bag('w.bag') as bag:
    print(show(bag))
    topics = bag.get_type_and_topic_info().topics
    print(sorted((k, (v.msg_type, v.message_count, v.connections)) for k, v in topics.items()))

# compression and chunk size changed while writing
with rosbag.Bag('set.bag', 'w') as bag:
    bag.write('/s', Int32(1), genpy.Time(1))
    bag.compression = 'bz2'
    bag.write('/s', Int32(2), genpy.Time(2))
    bag.chunk_threshold = 0
    bag.write('/s', Int32(3), genpy.Time(3))
    bag.write('/s', Int32(4), genpy.Time(4))
    print(bag.options)
with rosbag.Bag('set.bag') as bag:
    print(bag.get_compression_info().compression, show(bag))

# errors
if os.path.exists('missing_a.bag'):
    os.remove('missing_a.bag')
attempt('append to a missing file', lambda: rosbag.Bag('missing_a.bag', 'a'))
print('left behind:', os.path.exists('missing_a.bag'), os.path.getsize('missing_a.bag'))
attempt('missing', lambda: rosbag.Bag('nope.bag'))
attempt('bad mode', lambda: rosbag.Bag('x.bag', 'x'))
attempt('bad compression', lambda: rosbag.Bag('x.bag', 'w', compression='zstd'))
attempt('empty name', lambda: rosbag.Bag(''))
attempt('options not a dict', lambda: rosbag.Bag('x.bag', 'w', options=[1]))
attempt('negative threshold', lambda: rosbag.Bag('x.bag', 'w', chunk_threshold=-1))
open('text.txt', 'w').write('hello\\n')
attempt('not a bag', lambda: rosbag.Bag('text.txt'))
open('empty.bag', 'w').close()
attempt('empty file', lambda: rosbag.Bag('empty.bag'))
attempt('raw of wrong length', lambda: rosbag.Bag('y.bag', 'w').write('/a', (1, 2, 3), genpy.Time(1), raw=True))
''')

REINDEX_PROBE = textwrap.dedent('''
import sys, rosbag

for mode in ('r', 'a'):
    try:
        rosbag.Bag(sys.argv[1], mode)
    except rosbag.ROSBagUnindexedException as e:
        print(mode, type(e).__name__, e)
bag = rosbag.Bag(sys.argv[1], 'a', allow_unindexed=True)
print('chunks at', list(bag.reindex()))
bag.close()
with rosbag.Bag(sys.argv[1]) as bag:
    print(bag.get_message_count(), bag.get_start_time(), bag.get_end_time())
    for topic, msg, t in bag.read_messages():
        print(topic, t, str(msg).replace('\\n', ' '))
''')

# What a reader of the bag sees: counts, times and every message (Debian's rosbag runs it too).
READ_ALL = textwrap.dedent('''
    import sys, rosbag
    with rosbag.Bag(sys.argv[1]) as bag:
        print(bag.get_message_count(), bag.get_start_time(), bag.get_end_time())
        for topic, msg, t in bag.read_messages():
            print(topic, repr(t), str(msg).replace('\\n', ' '))
''')

# Appends the same messages to whichever bag it is given (a .bag or an MCAP file).
APPEND = textwrap.dedent('''
    import sys, rosbag, genpy
    from std_msgs.msg import Int32, String
    with rosbag.Bag(sys.argv[1], 'a') as bag:
        before = bag.get_message_count()
        for i in range(5):
            bag.write('/numbers', Int32(data=1000 + i), genpy.Time(999 + i * 2))
        bag.write('/late', String(data='appended'), genpy.Time(2000))
        unflushed = bag.get_message_count()  # rosbag counts the closed chunks only
        late = [m.message.data for m in bag.read_messages('/late')]  # reading writes the open chunk out
        print(before, unflushed, late, bag.get_message_count())
        # rosbag writes its index where the last read left the file: a write after reading puts it at the end
        bag.write('/numbers', Int32(data=2000), genpy.Time(3000))
''')


def _index_pos(path: Path) -> int:
    data = path.read_bytes()
    at = data.index(b"index_pos=") + len(b"index_pos=")
    return int(struct.unpack("<Q", data[at:at + 8])[0])


@pytest.fixture
def work(tmp_path: Path) -> Path:
    need_peer(_rosbag_ok(), "Debian's rosbag under /usr/bin/python3 (python3-rosbag, python3-geometry-msgs)")
    for name, text in (("api_probe.py", API_PROBE), ("reindex_probe.py", REINDEX_PROBE), ("read_all.py", READ_ALL),
                       ("append.py", APPEND), ("write_bag.py", WRITE_BAG)):
        (tmp_path / name).write_text(text)
    return tmp_path


def _in(where: Path) -> Path:
    where.mkdir()
    return where


def test_api_answers_as_rosbag(work: Path) -> None:
    real = _real([str(work / "api_probe.py")], _in(work / "debian"))
    assert "written read ok [('/b', data: \"x\", rospy.Time[2000000004])" in real
    assert "append count ok 6" in real and "closed size ValueError I/O operation on closed bag" in real
    assert _ours([str(work / "api_probe.py")], _in(work / "rostui")) == real


def test_append_continues_the_file_in_place(work: Path) -> None:
    """rostui appends after the last chunk: the old chunks are not rewritten (same file, same bytes); Debian's
    rosbag reads the result as it reads the bag it appended to itself."""
    _real(["write_bag.py", "debian.bag"], work)
    _real(["write_bag.py", "ours.bag"], work)
    old = (work / "ours.bag").read_bytes()
    chunks_end = _index_pos(work / "ours.bag")
    inode = os.stat(work / "ours.bag").st_ino
    printed = _real(["append.py", "debian.bag"], work)
    assert printed == "90 90 ['appended'] 96\n"
    assert _ours(["append.py", "ours.bag"], work) == printed
    new = (work / "ours.bag").read_bytes()
    assert os.stat(work / "ours.bag").st_ino == inode
    header_end = len(b"#ROSBAG V2.0\n") + 4 + 4096 + 4
    assert new[header_end:chunks_end] == old[header_end:chunks_end]
    assert _real(["read_all.py", "ours.bag"], work) == _real(["read_all.py", "debian.bag"], work)


def test_append_to_mcap_reads_like_the_bag(work: Path) -> None:
    """Appending to an MCAP file (rostui only) gives the messages appending to the .bag gives."""
    _real(["write_bag.py", "debian.bag"], work)
    _ours(["write_bag.py", "ours.mcap"], work)
    printed = _real(["append.py", "debian.bag"], work)
    assert _ours(["append.py", "ours.mcap"], work) == printed
    assert (work / "ours.mcap").read_bytes()[:8] == b"\x89MCAP0\r\n"
    # messages and counts agree; the span does not: rosbag's start is its first chunk's, in file order (1000.0,
    # though the appended chunk starts earlier), where an MCAP file's is its earliest message (999.0)
    expected = _real(["read_all.py", "debian.bag"], work).splitlines()
    ours = _ours(["read_all.py", "ours.mcap"], work).splitlines()
    assert ours[1:] == expected[1:] and ours[0].split()[0] == expected[0].split()[0] == "97"
    assert ours[0].split()[1:] == ["999.0", "3000.0"]


def test_reindex_an_unindexed_bag(work: Path) -> None:
    """A bag whose index was never written (a recorder killed after its last chunk): both refuse it without
    allow_unindexed, reindex it in 'a' mode and then read every message; Debian's rosbag checks rostui's."""
    _real(["write_bag.py", "whole.bag"], work)
    data = (work / "whole.bag").read_bytes()
    cut = data[:_index_pos(work / "whole.bag")]
    (work / "debian.bag").write_bytes(cut)
    (work / "ours.bag").write_bytes(cut)
    real = _real(["reindex_probe.py", "debian.bag"], work)
    assert real.startswith("r ROSBagUnindexedException Unindexed bag\na ROSBagUnindexedException Unindexed bag\n")
    assert "\n90 " in real
    assert _ours(["reindex_probe.py", "ours.bag"], work) == real
    assert _real(["read_all.py", "ours.bag"], work) == _real(["read_all.py", "whole.bag"], work)


def test_stream_without_a_name(work: Path) -> None:
    """rostui's rosbag reads and writes an io.BytesIO too (Debian's rosbag needs a file with a ``mode``)."""
    script = textwrap.dedent('''
        import io, rosbag, genpy
        from std_msgs.msg import Int32
        with open('ours.bag', 'rb') as f:
            data = f.read()
        bag = rosbag.Bag(io.BytesIO(data))
        print(bag.filename, bag.get_message_count(), [m.message.data for m in bag.read_messages('/numbers')][:3])
        bag.close()

        class Keep(io.BytesIO):
            def close(self):
                self.kept = self.getvalue()
                super().close()
        out = Keep()
        with rosbag.Bag(out, 'w') as bag:
            bag.write('/n', Int32(data=3), genpy.Time(5))
        with open('from_stream.bag', 'wb') as f:
            f.write(out.kept)
    ''')
    (work / "stream.py").write_text(script)
    _real(["write_bag.py", "ours.bag"], work)
    assert _ours(["stream.py"], work) == "None 90 [0, 7, 14]\n"
    assert _real(["read_all.py", "from_stream.bag"], work) == "1 5.0 5.0\n/n rospy.Time[5000000000] data: 3\n"
