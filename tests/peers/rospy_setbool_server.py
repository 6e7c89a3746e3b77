"""rospy peer: a std_srvs/SetBool server.

Usage (system python): rospy_setbool_server.py SERVICE [--fail TEXT] [ROS args]
Answers success=True, message "got true" / "got false"; with --fail, the
handler raises an exception carrying TEXT instead.  Prints "ready" when served.
"""

import sys

import rospy
from std_srvs.srv import SetBool, SetBoolResponse


def main() -> int:
    args = rospy.myargv()[1:]
    service = args[0]
    fail = args[args.index("--fail") + 1] if "--fail" in args else None

    def handle(req):
        print(f"request data={req.data}", flush=True)
        if fail is not None:
            raise RuntimeError(fail)
        return SetBoolResponse(success=True, message="got true" if req.data else "got false")

    rospy.init_node("rospy_setbool_server", anonymous=True)
    rospy.Service(service, SetBool, handle)
    print("ready", flush=True)
    rospy.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
