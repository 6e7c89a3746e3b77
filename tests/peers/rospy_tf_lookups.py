"""rospy peer: a tf2_ros listener (Debian's) answering lookups on the live /tf and /tf_static.

Usage (system python): rospy_tf_lookups.py TARGET SOURCE [TARGET SOURCE ...] [ROS args]
Listens until every frame named has come (or 20 s), asks each lookup at the latest common time, and
prints one JSON line: "answers" ("ok" or the first line of tf2's error), "frames" known and "maxrss_mb".
"""

import json
import sys
import time

import rospy
import tf2_ros


def peak_rss_mb():
    """This process's peak resident memory in MB: /proc's VmHWM, which starts afresh at exec (ru_maxrss
    carries over the memory of the process that started this one)."""
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) for line in status if line.startswith("VmHWM:")) / 1024


def main() -> int:
    words = rospy.myargv()[1:]
    pairs = list(zip(words[0::2], words[1::2]))
    rospy.init_node("tf_lookups", anonymous=True)
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    wanted = {frame for pair in pairs for frame in pair}
    deadline = time.monotonic() + 20.0
    while time.monotonic() < deadline and not all(buffer._frameExists(f) for f in wanted):
        time.sleep(0.1)
    answers = []
    for target, source in pairs:
        try:
            buffer.lookup_transform(target, source, rospy.Time(0))
            answers.append("ok")
        except tf2_ros.TransformException as exc:
            answers.append(str(exc).splitlines()[0])
    frames = len(buffer.all_frames_as_string().splitlines())
    print(json.dumps({"answers": answers, "frames": frames,
                      "maxrss_mb": round(peak_rss_mb(), 1)}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
