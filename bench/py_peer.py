#!/usr/bin/env python3
"""Python side of the pub/sub benchmarks, for rospy and for rostui: the same code.

``py_peer.py rospy MODE ...`` runs on rospy (use the SYSTEM python,
/usr/bin/python3); ``py_peer.py rostui MODE ...`` runs on rostui's client API
(the project venv).  rostui's client mirrors rospy's, so only the imports
differ.  Same modes and output as bench/roscpp_peer.cpp:

  flood TOPIC SIZE SECONDS   publish SIZE-byte std_msgs/String as fast as possible
                             (queue_size=1000) once subscribed, for SECONDS
  count TOPIC SECONDS        subscribe (tcp_nodelay), count messages and payload bytes during
                             SECONDS after the first message; print "count=N bytes=B seconds=S"
  pong IN OUT                echo every std_msgs/String from IN to OUT
  ping OUT IN N              N timed round trips after a warm-up; print "timing" when they
                             start, then "n=N p50_us=X p99_us=Y mean_us=M min_us=A max_us=B cpu_us=C"
                             (cpu_us: this process's CPU time per timed round trip)

Written the way a rospy user would: callbacks on the library's receive thread,
the main thread publishing and waiting.  ROS remaps (from:=to) are accepted.
"""

import sys
import threading
import time

LIBRARY = sys.argv.pop(1) if len(sys.argv) > 1 else ""
if LIBRARY == "rospy":
    import rospy as ros
    from std_msgs.msg import String
elif LIBRARY == "rostui":
    from rostui import client as ros
    String = ros.msg("std_msgs/String")
else:
    sys.exit("usage: py_peer.py rospy|rostui MODE ARGS...")


def usage():
    sys.stderr.write(__doc__)
    return 2


def wait_until(pred, timeout=30.0):
    end = time.monotonic() + timeout
    while not ros.is_shutdown() and not pred():
        if time.monotonic() > end:
            return False
        time.sleep(0.005)
    return not ros.is_shutdown()


def flood(topic, size, seconds):
    pub = ros.Publisher(topic, String, queue_size=1000)
    if not wait_until(lambda: pub.get_num_connections() > 0):
        return 1
    msg = String(data="x" * size)
    sent = 0
    end = time.monotonic() + seconds
    while time.monotonic() < end and not ros.is_shutdown():
        pub.publish(msg)
        sent += 1
    sys.stderr.write("flood: published %d messages\n" % sent)
    return 0


def count(topic, seconds):
    state = {"t0": None, "n": 0, "bytes": 0}
    started = threading.Event()

    def on_msg(msg):
        now = time.monotonic()
        if state["t0"] is None:
            state["t0"] = now
            started.set()
        elif now - state["t0"] > seconds:
            return
        state["n"] += 1
        state["bytes"] += len(msg.data)

    ros.Subscriber(topic, String, on_msg, tcp_nodelay=True)
    while not started.wait(0.1):
        if ros.is_shutdown():
            return 1
    time.sleep(max(0.0, state["t0"] + seconds - time.monotonic()))
    print("count=%d bytes=%d seconds=%.3f" % (state["n"], state["bytes"], time.monotonic() - state["t0"]),
          flush=True)
    return 0


def pong(topic_in, topic_out):
    pub = ros.Publisher(topic_out, String, queue_size=1000)
    ros.Subscriber(topic_in, String, pub.publish, tcp_nodelay=True)
    ros.spin()
    return 0


def ping(topic_out, topic_in, n):
    pub = ros.Publisher(topic_out, String, queue_size=1000)
    got = threading.Event()
    last = [None]

    def on_msg(msg):
        last[0] = msg.data
        got.set()

    sub = ros.Subscriber(topic_in, String, on_msg, tcp_nodelay=True)
    if not wait_until(lambda: pub.get_num_connections() > 0 and sub.get_num_connections() > 0):
        sys.stderr.write("ping: peers never connected\n")
        return 1
    for _ in range(300):  # until the echo path works end to end
        got.clear()
        pub.publish(String(data="warmup"))
        if got.wait(0.1) and last[0] == "warmup":
            break
    else:
        sys.stderr.write("ping: no echo\n")
        return 1
    warm = max(100, n // 10)
    rtt = []
    cpu0 = 0.0
    for i in range(warm + n):
        if i == warm:
            print("timing", flush=True)  # the timed round trips start (bench_pubsub reads the echo's CPU here)
            cpu0 = time.process_time()
        text = "ping %d" % i
        msg = String(data=text)
        t0 = time.perf_counter()
        got.clear()
        pub.publish(msg)
        while last[0] != text:
            if not got.wait(5.0):
                sys.stderr.write("ping: reply %d lost\n" % i)
                return 1
            got.clear()
        if i >= warm:
            rtt.append((time.perf_counter() - t0) * 1e6)
    print_latency(rtt, (time.process_time() - cpu0) / n * 1e6)
    return 0


def print_latency(rtt, cpu_us):
    rtt.sort()
    k = len(rtt)
    pct = lambda p: rtt[min(k - 1, int(p * k))]  # noqa: E731
    print("n=%d p50_us=%.1f p99_us=%.1f mean_us=%.1f min_us=%.1f max_us=%.1f cpu_us=%.1f"
          % (k, pct(0.50), pct(0.99), sum(rtt) / k, rtt[0], rtt[-1], cpu_us), flush=True)


def main():
    args = ros.myargv(sys.argv)[1:]
    modes = {"flood": (3, lambda a: flood(a[0], int(a[1]), float(a[2]))),
             "count": (2, lambda a: count(a[0], float(a[1]))),
             "pong": (2, lambda a: pong(a[0], a[1])),
             "ping": (3, lambda a: ping(a[0], a[1], int(a[2])))}
    if not args or args[0] not in modes or len(args) != modes[args[0]][0] + 1:
        return usage()
    ros.init_node(LIBRARY + "_peer", argv=sys.argv, anonymous=True)
    try:
        return modes[args[0]][1](args[1:])
    finally:
        ros.signal_shutdown("done")


if __name__ == "__main__":
    sys.exit(main())
