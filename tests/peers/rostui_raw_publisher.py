"""rostui client peer: publish the bytes of a file as messages of a given type, at a rate.

Usage: rostui_raw_publisher.py TOPIC TYPE FILE HZ [ROS args]
FILE holds one serialized message, as a hostile test crafted it (no class of rostui's builds it: a
ten-million-range scan would take seconds to build that way). The connection header carries TYPE's
md5sum and definition as rostui knows them. Prints "publishing" once the first message is sent.
"""

import sys

from rostui import client as ros
from rostui.core.msg import full_text, md5sum
from rostui.core.node import AnyMsg


def main() -> int:
    topic, type_name, path, hz = ros.myargv()[1:5]
    raw_class = type("Raw", (AnyMsg,), {"__slots__": (), "_type": type_name, "_md5sum": md5sum(type_name),
                                        "_full_text": full_text(type_name)})
    with open(path, "rb") as f:
        data = f.read()
    ros.init_node("raw_publisher", anonymous=True)
    pub = ros.Publisher(topic, raw_class, queue_size=1)
    rate = ros.Rate(float(hz))
    said = False
    while not ros.is_shutdown():
        pub.publish(raw_class(data))
        if not said:
            print("publishing", flush=True)
            said = True
        rate.sleep()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except ros.ROSInterruptException:
        sys.exit(0)
