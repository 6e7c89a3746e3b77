#!/usr/bin/env python3
"""talker: publish "hello world N" on the ``chatter`` topic at 10 Hz.

The classic ROS talker, written against rostui's client API::

    python examples/talker.py                      # forever (Ctrl-C stops it)
    python examples/talker.py --count 5            # five messages, then exit
    python examples/talker.py chatter:=greetings   # remap the topic

With ``--count N`` the talker first waits until a subscriber is connected
(``--subscribers K``: until K are), so that all N messages are heard.
"""

import argparse

from rostui import client as ros

String = ros.msg("std_msgs/String")


def main() -> None:
    ros.init_node("talker", anonymous=True)
    parser = argparse.ArgumentParser(description="Publish std_msgs/String on chatter.")
    parser.add_argument("--count", type=int, default=0, help="exit after N messages (0: forever)")
    parser.add_argument("--rate", type=float, default=10.0, help="messages per second")
    parser.add_argument("--subscribers", type=int, default=1,
                        help="with --count: wait until this many subscribers are connected")
    args = parser.parse_args(ros.myargv()[1:])

    pub = ros.Publisher("chatter", String, queue_size=10)
    rate = ros.Rate(args.rate)
    if args.count:
        while pub.get_num_connections() < args.subscribers and not ros.is_shutdown():
            rate.sleep()
    n = 0
    while not ros.is_shutdown() and (args.count == 0 or n < args.count):
        text = f"hello world {n}"
        ros.loginfo(text)
        pub.publish(String(data=text))
        n += 1
        rate.sleep()
    if args.count:
        ros.sleep(0.5)  # let the last message leave before the connections close


if __name__ == "__main__":
    try:
        main()
    except ros.ROSInterruptException:
        pass
