"""Debian's tf2 (tf2_py.BufferCore, the C++ buffer every tf2_ros listener holds) answering lookups, as a reference.

Usage (system python): tf2_lookups.py < SCENARIO.json
SCENARIO: {"edges": [[parent, child], ...], "lookups": [[target, source], ...]}; every edge is a static
identity transform. Prints one JSON object: "answers" (per lookup, "ok" or the first line of tf2's error)
and "maxrss_mb" (the process's peak resident memory).
"""

import json
import sys

import rospy
import tf2_py
from geometry_msgs.msg import TransformStamped


def peak_rss_mb():
    """This process's peak resident memory in MB: /proc's VmHWM, which starts afresh at exec (ru_maxrss
    carries over the memory of the process that started this one)."""
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) for line in status if line.startswith("VmHWM:")) / 1024


def main() -> int:
    scenario = json.load(sys.stdin)
    core = tf2_py.BufferCore(rospy.Duration(10))
    for parent, child in scenario["edges"]:
        t = TransformStamped()
        t.header.frame_id, t.child_frame_id, t.header.stamp = parent, child, rospy.Time(1)
        t.transform.rotation.w = 1.0
        core.set_transform_static(t, "tf2_lookups")
    answers = []
    for target, source in scenario["lookups"]:
        try:
            core.lookup_transform_core(target, source, rospy.Time(0))
            answers.append("ok")
        except tf2_py.TransformException as exc:
            answers.append(str(exc).splitlines()[0])
    print(json.dumps({"answers": answers, "maxrss_mb": peak_rss_mb()}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
