#!/usr/bin/env python3
"""One library's logging cost: ``log_peer.py rospy|rostui N``.

Times N calls of loginfo (enabled: console + /rosout + log file) and N calls of
logdebug (disabled at the default INFO level) in a node registered with the
master at ROS_MASTER_URI, and prints ``enabled_per_s=... disabled_ns=...``.
rospy runs under the system python, rostui under the project venv; the code is
the same because rostui's client mirrors rospy's.
"""

import sys
import time

LIBRARY = sys.argv.pop(1) if len(sys.argv) > 1 else ""
if LIBRARY == "rospy":
    import rospy as ros
elif LIBRARY == "rostui":
    from rostui import client as ros
else:
    sys.exit("usage: log_peer.py rospy|rostui N")


def main() -> None:
    n = int(sys.argv[1])
    ros.init_node(LIBRARY + "_log_bench", anonymous=True)
    time.sleep(1.0)  # let rosout connect to our /rosout
    t0 = time.perf_counter()
    for i in range(n):
        ros.loginfo("enabled message %d", i)
    enabled = time.perf_counter() - t0
    t0 = time.perf_counter()
    for i in range(n * 10):
        ros.logdebug("disabled message %d", i)
    disabled = time.perf_counter() - t0
    sys.stderr.write("enabled_per_s=%.1f disabled_ns=%.1f\n" % (n / enabled, disabled / (n * 10) * 1e9))
    ros.signal_shutdown("done")


main()
