#!/usr/bin/env python3
"""toggle_client: call the ``toggle`` service (std_srvs/SetBool) once.

::

    python examples/toggle_client.py          # data: true
    python examples/toggle_client.py false    # data: false
    python examples/toggle_client.py true toggle:=/robot/toggle

Prints ``success=<True/False> message=<text>``; exits 1 when the call fails.
"""

import sys

from rostui import client as ros

SetBool = ros.srv("std_srvs/SetBool")


def main() -> int:
    ros.init_node("toggle_client", anonymous=True)
    args = ros.myargv()[1:]
    value = not (args and args[0].lower() in ("false", "0", "off", "no"))
    try:
        ros.wait_for_service("toggle", timeout=10)
        toggle = ros.ServiceProxy("toggle", SetBool)
        resp = toggle(value)
    except (ros.ROSException, ros.ServiceException) as exc:
        print(f"toggle failed: {exc}", file=sys.stderr)
        return 1
    print(f"success={resp.success} message={resp.message}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
