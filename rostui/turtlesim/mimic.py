"""mimic: make one turtle copy another's motion.

Behaves like ROS turtlesim's ``mimic`` tutorial node (``turtle_mimic``): for
every ``turtlesim/Pose`` on ``input/pose`` it publishes the pose's velocities
as a command on ``output/cmd_vel`` (``geometry_msgs/Twist``: linear.x =
linear_velocity, angular.z = angular_velocity) and, for the book's
groovy-era turtlesim, on ``output/command_velocity`` (``turtlesim/Velocity``).

``input`` and ``output`` are namespaces that are remapped as a whole, as
roscpp does for a node handle's namespace::

    rostui run turtlesim mimic input:=turtle1 output:=turtle2
"""

from __future__ import annotations

import sys
from typing import Any

__all__ = ["main"]


def main(argv: list[str] | None = None) -> int:
    """The ``turtle_mimic`` node; ``argv`` is the full command line (default ``sys.argv``)."""
    from rostui import client as ros

    Pose = ros.msg("turtlesim/Pose")
    Twist = ros.msg("geometry_msgs/Twist")
    Velocity = ros.msg("turtlesim/Velocity")

    try:
        ros.init_node("turtle_mimic", argv=sys.argv if argv is None else argv)
    except ros.ROSInterruptException:
        return 0
    # Resolving the namespaces first lets `input:=turtle1` move every topic under it.
    input_ns = ros.resolve_name("input")
    output_ns = ros.resolve_name("output")
    twist_pub = ros.Publisher(f"{output_ns}/cmd_vel", Twist, queue_size=1)
    velocity_pub = ros.Publisher(f"{output_ns}/command_velocity", Velocity, queue_size=1)

    def copy_motion(pose: Any) -> None:
        twist: Any = Twist()  # a generated class: its fields are not known statically
        twist.linear.x = pose.linear_velocity
        twist.angular.z = pose.angular_velocity
        twist_pub.publish(twist)
        velocity_pub.publish(Velocity(linear=pose.linear_velocity, angular=pose.angular_velocity))

    ros.Subscriber(f"{input_ns}/pose", Pose, copy_motion, queue_size=1)
    ros.spin()
    return 0
