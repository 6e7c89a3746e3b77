#!/usr/bin/env python3
"""toggle_server: a std_srvs/SetBool service that switches a flag on and off.

Like the book's pubvel_toggle: while the flag is on, the node publishes the
current state on ``toggle_state`` (std_msgs/Bool) at 2 Hz.  Try it with::

    python examples/toggle_server.py
    python examples/toggle_client.py false        # or: rosservice call /toggle "data: false"
"""

import threading

from rostui import client as ros

Bool = ros.msg("std_msgs/Bool")
SetBool = ros.srv("std_srvs/SetBool")

_lock = threading.Lock()
_enabled = True


def handle_toggle(req):
    """Service handler: runs in a worker thread, returns the response."""
    global _enabled
    with _lock:
        _enabled = bool(req.data)
    ros.loginfo("toggle: now %s", "on" if req.data else "off")
    return SetBool._response_class(success=True, message=f"got {'true' if req.data else 'false'}")


def main() -> None:
    ros.init_node("toggle_server")
    ros.Service("toggle", SetBool, handle_toggle)
    pub = ros.Publisher("toggle_state", Bool, queue_size=1)
    rate = ros.Rate(2)
    while not ros.is_shutdown():
        with _lock:
            on = _enabled
        if on:
            pub.publish(Bool(data=True))
        rate.sleep()


if __name__ == "__main__":
    try:
        main()
    except ros.ROSInterruptException:
        pass
