"""rospy peer: call a std_srvs/SetBool service once.

Usage (system python): rospy_setbool_client.py SERVICE true|false [ROS args]
Prints "success=<True/False> message=<text>", or "ServiceException: <text>"
and exits 1 when the call fails.
"""

import sys

import rospy
from std_srvs.srv import SetBool


def main() -> int:
    service, value = rospy.myargv()[1:3]
    rospy.init_node("rospy_setbool_client", anonymous=True)
    rospy.wait_for_service(service, timeout=20)
    proxy = rospy.ServiceProxy(service, SetBool)
    try:
        resp = proxy(value.lower() == "true")
    except rospy.ServiceException as exc:
        print(f"ServiceException: {exc}", flush=True)
        return 1
    print(f"success={resp.success} message={resp.message}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
