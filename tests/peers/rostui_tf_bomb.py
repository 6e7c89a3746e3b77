"""rostui client peer: a tf chain DEPTH frames deep (f0 -> f1 -> ... -> fDEPTH) and a loop (l0 -> l1 -> l2 -> l0).

Usage: rostui_tf_bomb.py DEPTH HZ [ROS args]
The chain goes out once, latched, on /tf_static, in one message (as a static_transform_publisher's
would); the loop on /tf at HZ. Prints "broadcasting" after the first round.
"""

import sys

from rostui import client as ros

TFMessage = ros.msg("tf2_msgs/TFMessage")
TransformStamped = ros.msg("geometry_msgs/TransformStamped")
LOOP = ["l0", "l1", "l2"]


def stamped(parent, child, stamp):
    t = TransformStamped()
    t.header.stamp, t.header.frame_id, t.child_frame_id = stamp, parent, child
    t.transform.rotation.w = 1.0
    return t


def main() -> int:
    depth, hz = int(ros.myargv()[1]), float(ros.myargv()[2])
    ros.init_node("rostui_tf_bomb")
    static_pub = ros.Publisher("/tf_static", TFMessage, queue_size=1, latch=True)
    pub = ros.Publisher("/tf", TFMessage, queue_size=10)
    now = ros.Time.now()
    static_pub.publish(TFMessage(transforms=[stamped(f"f{i}", f"f{i + 1}", now) for i in range(depth)]))
    rate = ros.Rate(hz)
    said = False
    while not ros.is_shutdown():
        now = ros.Time.now()
        pub.publish(TFMessage(transforms=[stamped(LOOP[i], LOOP[(i + 1) % 3], now) for i in range(3)]))
        if not said:
            print("broadcasting", flush=True)
            said = True
        rate.sleep()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except ros.ROSInterruptException:
        sys.exit(0)
