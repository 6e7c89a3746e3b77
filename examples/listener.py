#!/usr/bin/env python3
"""listener: print every std_msgs/String heard on the ``chatter`` topic.

The classic ROS listener, written against rostui's client API::

    python examples/listener.py
    python examples/listener.py chatter:=greetings __name:=ears

Each message is logged at INFO as ``[ INFO] [<time>]: I heard: <data>``.
"""

from rostui import client as ros

String = ros.msg("std_msgs/String")


def callback(msg) -> None:
    """Runs on the client's engine thread for every message received."""
    ros.loginfo("I heard: %s", msg.data)


def main() -> None:
    ros.init_node("listener", anonymous=True)
    ros.Subscriber("chatter", String, callback)
    ros.spin()


if __name__ == "__main__":
    main()
