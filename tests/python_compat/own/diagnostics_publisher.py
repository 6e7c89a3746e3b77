"""A robot driver's diagnostics as its node publishes them with diagnostic_updater (tests/diagnostics_helpers.py).

Three tasks under one hardware id: a laser that is fine, a motor that runs hot and a battery that is low, each
with key/values. The updater sends every 0.3 s (force_update), so an aggregator and the tools see news soon.
"""

import diagnostic_updater
import rospy
from diagnostic_msgs.msg import DiagnosticStatus


def laser(stat):
    stat.summary(DiagnosticStatus.OK, "Scanning")
    stat.add("frequency", "10.0")
    stat.add("frame_id", "laser")
    return stat


def motor(stat):
    stat.summary(DiagnosticStatus.WARN, "Running hot")
    stat.add("temperature", "71.5")
    return stat


def battery(stat):
    stat.summary(DiagnosticStatus.ERROR, "Charge low")
    stat.add("voltage", "10.9")
    stat.add("percentage", "7")
    return stat


rospy.init_node("robot_driver")
updater = diagnostic_updater.Updater()
updater.setHardwareID("robot-1")
updater.add("laser connection", laser)
updater.add("motor temperature", motor)
updater.add("battery charge", battery)
print("publishing diagnostics", flush=True)
while not rospy.is_shutdown():
    updater.force_update()
    rospy.sleep(0.3)
