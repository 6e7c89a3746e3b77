"""rospy peer: log "debug N" at DEBUG and "info N" at INFO every 0.1 s (N counts up from 0).

Usage (system python): rospy_debug_logger.py [ROS args]
The node is /rospy_debug_logger (change with __name:=).  rospy starts at
INFO, so only the INFO lines reach /rosout until someone sets the ``rosout``
logger to DEBUG through ~set_logger_level.  Prints "ready" once initialised.
"""

import sys

import rospy


def main() -> int:
    rospy.init_node("rospy_debug_logger")
    print("ready", flush=True)
    rate = rospy.Rate(10)
    count = 0
    while not rospy.is_shutdown():
        rospy.logdebug("debug %d", count)
        rospy.loginfo("info %d", count)
        count += 1
        rate.sleep()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except rospy.ROSInterruptException:
        sys.exit(0)
