"""rospy peer: subscribe to topics with their real message classes and print every message received.

Usage (system python): rospy_typed_listener.py TOPIC=pkg/Type ... [ROS args]
Prints "subscribed" once every subscriber is registered, then for each message one line
"<topic> <type> <md5sum> <hex of the message serialized again by rospy>"; runs until interrupted.
"""

import importlib
import io
import sys

import rospy


def message_class(type_name):
    """The generated rospy class of ``pkg/Type``, imported from ``pkg.msg``."""
    package, name = type_name.split("/")
    return getattr(importlib.import_module(package + ".msg"), name)


def main() -> int:
    pairs = [arg.split("=", 1) for arg in rospy.myargv()[1:]]
    rospy.init_node("rospy_typed_listener", anonymous=True)

    def callback(msg, topic):
        out = io.BytesIO()
        msg.serialize(out)
        print(f"{topic} {msg._type} {msg._md5sum} {out.getvalue().hex()}", flush=True)

    for topic, type_name in pairs:
        rospy.Subscriber(topic, message_class(type_name), callback, callback_args=topic)
    print("subscribed", flush=True)
    rospy.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
