"""Random tf trees, fed to a tf2 buffer and asked every kind of question; prints what the buffer answered.

Written only against the public tf2_ros / tf2_py / tf2_geometry_msgs / rospy API, so it runs unchanged
under Debian's real tf2 (``/usr/bin/python3``) and under ``rostui python``; tests/test_tf2_buffer.py
compares the two outputs. Usage: ``buffer_scenarios.py SEED TREES``. Each line of output is one JSON
answer: ``{"q": question, "ok": value}`` or ``{"q": question, "err": [exception class, text]}``.
No master is needed: the buffers are made without the debug service and nothing waits.
"""

import json
import math
import random
import sys

import rospy
import tf2_geometry_msgs  # noqa: F401 (registers the stamped geometry types for Buffer.transform)
import tf2_py
import tf2_ros
from geometry_msgs.msg import PointStamped, PoseStamped, TransformStamped, Vector3Stamped, WrenchStamped

NS = 1000000000


def unit_quaternion(rng):
    q = [rng.gauss(0.0, 1.0) for _ in range(4)]
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]


def transform(parent, child, stamp_ns, rng):
    t = TransformStamped()
    t.header.frame_id = parent
    t.child_frame_id = child
    t.header.stamp = rospy.Time(stamp_ns // NS, stamp_ns % NS)
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = (
        rng.uniform(-5, 5) for _ in range(3))
    q = unit_quaternion(rng)
    r = t.transform.rotation
    r.x, r.y, r.z, r.w = q
    return t


def numbers_of(msg):
    """Every float of a message, walked by slot, plus its frame ids and stamp."""
    if hasattr(msg, "__slots__"):
        out = {}
        for slot in msg.__slots__:
            out[slot] = numbers_of(getattr(msg, slot))
        return out
    if hasattr(msg, "secs") and hasattr(msg, "nsecs"):
        return [int(msg.secs), int(msg.nsecs)]
    if isinstance(msg, (int, float, str)):
        return msg
    return repr(msg)


def ask(out, question, call):
    try:
        value = call()
    except Exception as exc:  # every tf2 failure is an answer to compare
        out.append({"q": question, "err": [type(exc).__name__, str(exc)]})
        return
    if isinstance(value, tuple):
        value = [int(value[0]), value[1]]
    elif hasattr(value, "__slots__") or hasattr(value, "secs"):
        value = numbers_of(value)
    out.append({"q": question, "ok": value})


def tree(rng, index, out):
    """One random forest of frames, some static, some with a single sample; then many questions."""
    buffer = tf2_ros.Buffer(cache_time=rospy.Duration(rng.choice([2, 5, 10])), debug=False)
    count = rng.randint(3, 9)
    frames = ["f%d_%d" % (index, i) for i in range(count)]
    base = rng.randint(10, 1800000000) * NS + rng.randint(0, NS - 1)
    stamps = {}
    for i, child in enumerate(frames[1:], 1):
        if rng.random() < 0.15:
            continue  # a second tree
        parent = frames[rng.randrange(i)]
        kind = rng.random()
        if kind < 0.25:
            buffer.set_transform_static(transform(parent, child, 0, rng), "static_node")
            continue
        samples = 1 if kind < 0.4 else rng.randint(2, 6)
        times = sorted({base + rng.randint(0, 4 * NS) for _ in range(samples)})
        if rng.random() < 0.3 and len(times) > 1:
            times[1] = times[0] + rng.randint(1, 3)  # nanoseconds apart: floats would merge them
        order = list(times)
        rng.shuffle(order)
        for stamp in order:
            buffer.set_transform(transform(parent, child, stamp, rng), "node_%d" % i)
        stamps[child] = times
    all_times = sorted(t for ts in stamps.values() for t in ts)
    probes = [0]
    if all_times:
        lo, hi = all_times[0], all_times[-1]
        probes += [lo, hi, lo - 1, hi + 1, (lo + hi) // 2, hi + 3 * NS, lo - 7 * NS]
        probes += [rng.randint(lo, hi) for _ in range(6)]
        probes += rng.sample(all_times, min(4, len(all_times)))
    names = frames + ["nowhere"]
    for _ in range(40):
        target, source = rng.choice(names), rng.choice(names)
        t = rng.choice(probes)
        when = rospy.Time(t // NS, t % NS)
        key = "%d lookup %s<-%s @%d" % (index, target, source, t)
        ask(out, key, lambda: buffer.lookup_transform(target, source, when))
        ask(out, key + " can", lambda: buffer.can_transform_core(target, source, when))
    for _ in range(8):
        target, source, fixed = rng.choice(frames), rng.choice(frames), rng.choice(frames)
        t1, t2 = rng.choice(probes), rng.choice(probes)
        key = "%d full %s@%d<-%s@%d via %s" % (index, target, t1, source, t2, fixed)
        a, b = rospy.Time(t1 // NS, t1 % NS), rospy.Time(t2 // NS, t2 % NS)
        ask(out, key, lambda: buffer.lookup_transform_full(target, a, source, b, fixed))
        ask(out, key + " can", lambda: buffer.can_transform_full_core(target, a, source, b, fixed))
    for _ in range(6):
        target, source = rng.choice(names), rng.choice(names)
        ask(out, "%d common %s %s" % (index, target, source), lambda: buffer.get_latest_common_time(target, source))
    for kind in (PointStamped, PoseStamped, Vector3Stamped, WrenchStamped):
        msg = kind()
        msg.header.frame_id = rng.choice(frames)
        t = rng.choice(probes)
        msg.header.stamp = rospy.Time(t // NS, t % NS)
        for slot in msg.__slots__[1:]:
            inner = getattr(msg, slot)
            for sub in inner.__slots__:
                value = getattr(inner, sub)
                if hasattr(value, "__slots__"):
                    for c in value.__slots__:
                        setattr(value, c, rng.uniform(-3, 3))
                else:
                    setattr(inner, sub, rng.uniform(-3, 3))
        if kind is PoseStamped:
            o = msg.pose.orientation
            o.x, o.y, o.z, o.w = unit_quaternion(rng)
        target = rng.choice(frames)
        ask(out, "%d transform %s %s->%s" % (index, kind.__name__, msg.header.frame_id, target),
            lambda: buffer.transform(msg, target))
    ask(out, "%d frames" % index, lambda: sorted(buffer._getFrameStrings()))
    ask(out, "%d yaml" % index, lambda: buffer.all_frames_as_yaml())
    ask(out, "%d string" % index, lambda: buffer.all_frames_as_string())


def edge_cases(out):
    """Named situations: frame id mistakes, old data, loops' absence of an answer, identity lookups."""
    rng = random.Random(7)
    core = tf2_py.BufferCore(rospy.Duration(10))
    core.set_transform(transform("map", "odom", 100 * NS, rng), "a")
    core.set_transform(transform("odom", "base", 100 * NS, rng), "a")
    core.set_transform(transform("odom", "base", 102 * NS, rng), "a")
    core.set_transform(transform("odom", "base", 80 * NS, rng), "late")  # older than the cache: refused
    core.set_transform(transform("/s1", "/s2", 100 * NS, rng), "slashes")
    for target, source, t in [("map", "base", 101), ("odom", "base", 103), ("odom", "base", 99), ("zzz", "zzz", 0),
                              ("base", "base", 0), ("base", "base", 5), ("zzz", "base", 0), ("/map", "base", 0),
                              ("", "base", 0), ("map", "", 0), ("s1", "s2", 0), ("map", "s2", 0), ("base", "map", 0),
                              ("map", "base", 0), ("map", "base", 102)]:
        when = rospy.Time(t)
        ask(out, "edge lookup %r<-%r @%d" % (target, source, t), lambda: core.lookup_transform_core(target, source, when))
        ask(out, "edge can %r<-%r @%d" % (target, source, t), lambda: core.can_transform_core(target, source, when))
    for a, b in [("map", "base"), ("map", "qq"), ("map", "s2"), ("base", "base"), ("/map", "base")]:
        ask(out, "edge common %s %s" % (a, b), lambda: core.get_latest_common_time(a, b))
    ask(out, "edge exists", lambda: [core._frameExists("s1"), core._frameExists("/s1"), core._frameExists("x")])
    ask(out, "edge time type", lambda: core.lookup_transform_core("map", "odom", 5))
    ask(out, "edge yaml", lambda: core.all_frames_as_yaml())
    ask(out, "edge dot", lambda: core._allFramesAsDot())
    ask(out, "edge dot at", lambda: core._allFramesAsDot(rospy.Time(105)))
    ask(out, "edge names", lambda: [c.__module__ + "." + c.__name__ for c in type(
        tf2_ros.LookupException("x")).__mro__[:2]] + [hasattr(tf2_ros, "Exception")])
    ask(out, "edge unregistered", lambda: tf2_ros.Buffer(debug=False).transform(TransformStamped(), "map"))


def main():
    seed, trees = int(sys.argv[1]), int(sys.argv[2])
    rng = random.Random(seed)
    out = []
    for index in range(trees):
        tree(rng, index, out)
    edge_cases(out)
    for answer in out:
        print(json.dumps(answer, sort_keys=True))


if __name__ == "__main__":
    main()
