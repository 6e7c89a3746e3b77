"""Random message streams through message_filters' Cache and synchronizers; prints what came out.

Written against the public message_filters and rospy API only, so it runs unchanged under Debian's
message_filters (/usr/bin/python3) and under `rostui python`; tests/test_message_filters.py compares the
two outputs line for line. Usage: ``scenarios.py SEED ROUNDS``. No master: ROS time is set by hand.
"""

import json
import random
import sys

import message_filters
import rospy
from geometry_msgs.msg import PointStamped
from std_msgs.msg import String


def stamped(ident, secs, nsecs):
    msg = PointStamped()
    msg.header.stamp = rospy.Time(secs, nsecs)
    msg.point.x = float(ident)
    return msg


def ident(msg):
    return int(msg.point.x)


def run_round(rng, index, out):
    inputs = [message_filters.SimpleFilter() for _ in range(rng.randint(2, 3))]
    exact = message_filters.TimeSynchronizer(inputs, rng.randint(1, 6))
    approx = message_filters.ApproximateTimeSynchronizer(inputs, rng.randint(1, 6), rng.choice([0.01, 0.05, 0.2]))
    cache = message_filters.Cache(inputs[0], rng.randint(1, 8))
    exact.registerCallback(lambda *m: out.append([index, "exact", [ident(x) for x in m]]))
    approx.registerCallback(lambda *m: out.append([index, "approx", [ident(x) for x in m[:-1]], m[-1]]), "extra")
    cache.registerCallback(lambda m: out.append([index, "cache", ident(m)]))
    now = 1000
    n = 0
    for _ in range(rng.randint(10, 60)):
        now += rng.choice([0, 1, 1, 2, -30])  # sometimes time jumps back
        rospy.rostime._set_rostime(rospy.Time(now))
        base = rng.randint(0, 20)
        which = rng.randrange(len(inputs))
        n += 1
        inputs[which].signalMessage(stamped(n, 100 + base // 10, (base % 10) * 10000000 + rng.choice([0, 0, 3000000])))
    lo, hi = rospy.Time(100, 500000000), rospy.Time(101, 200000000)
    out.append([index, "interval", [ident(m) for m in cache.getInterval(lo, hi)]])
    for t in (lo, hi, rospy.Time(99), rospy.Time(103)):
        after, before = cache.getElemAfterTime(t), cache.getElemBeforeTime(t)
        out.append([index, "after/before", None if after is None else ident(after),
                    None if before is None else ident(before)])
    for t in (cache.getLatestTime(), cache.getOldestTime(), cache.getLastestTime()):
        out.append([index, "time", None if t is None else [t.secs, t.nsecs]])
    last = cache.getLast()
    out.append([index, "last", None if last is None else ident(last)])
    out.append([index, "queues", [sorted([s.secs, s.nsecs] for s in q) for q in approx.queues]])


def main():
    seed, rounds = int(sys.argv[1]), int(sys.argv[2])
    rospy.rostime.set_rostime_initialized(True)
    rng = random.Random(seed)
    out = []
    for index in range(rounds):
        run_round(rng, index, out)
    headerless = message_filters.Cache(message_filters.SimpleFilter(), 3)
    headerless.add(String("no header"))
    out.append(["headerless", headerless.getLast()])
    for line in out:
        print(json.dumps(line))


if __name__ == "__main__":
    main()
