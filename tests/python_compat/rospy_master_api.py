"""rospy's master proxy, parameters before init_node, get_ros_root, error_handler and disable_rostime.

Run under Debian's rospy and under `rostui python`; its `=` lines must match.
"""

import sys
import warnings

import rospy
from std_srvs.srv import Empty, EmptyResponse


def say(*items):
    print("=", *items, flush=True)


try:
    rospy.Time.now()
except rospy.ROSInitException as exc:
    say("before init", exc)
rospy.set_param("/use_sim_time", True)
say("params before init", rospy.get_param("/use_sim_time"), rospy.has_param("/use_sim_time"),
    rospy.get_param("/absent", "dflt"), rospy.search_param("use_sim_time"), "/use_sim_time" in rospy.get_param_names())
master = rospy.get_master()
say("master", type(master).__name__, master is rospy.get_master(), isinstance(master, rospy.MasterProxy))
code, _, uri = master.lookupNode("/rosout")
say("lookupNode", code, uri.startswith("http://"))
say("getParam", master.getParam("/use_sim_time")[0::2], master["/use_sim_time"], "/use_sim_time" in master,
    "/absent" in master)
master["/master_api/x"] = {"a": 1}
say("set through master", rospy.get_param("/master_api"), master.search_param("master_api"))
del master["/master_api"]
try:
    master["/master_api"]
except KeyError as exc:
    say("deleted", repr(exc))
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    root = rospy.get_ros_root(env={"ROS_ROOT": "ros_root_given"})
say("get_ros_root", root, rospy.get_ros_root(env={}), [w.category.__name__ for w in caught])
try:
    rospy.get_ros_root(required=True, env={})
except rospy.ROSException as exc:
    say("required", exc)

rospy.init_node("master_api", disable_rostime=True, disable_signals=True)
say("disable_rostime", rospy.rostime.is_wallclock(), rospy.get_time() > 1e9, rospy.Time.now().secs > 10 ** 9)
say("private through master", master.getParam("~missing")[0], rospy.resolve_name("~x"))
master.setParam("~x", 7)
say("private set", rospy.get_param("~x"), master.get_param_cached("~x"), sorted(n for n in master if "master_api" in n))


def broken(req):
    raise ValueError("boom")


def on_error(exc, exc_type, value, tb):
    say("error_handler", type(exc).__name__, exc, exc_type.__name__, value is exc, tb is not None)


rospy.Service("broken", Empty, broken, error_handler=on_error)
rospy.Service("fine", Empty, lambda req: EmptyResponse(), error_handler=on_error)
rospy.wait_for_service("broken", 10)
try:
    rospy.ServiceProxy("broken", Empty)()
except rospy.ServiceException:
    say("caller got ServiceException")
say("fine", type(rospy.ServiceProxy("fine", Empty)()).__name__)
rate = rospy.Rate(100, reset=True)
say("rate", type(rate.remaining()).__name__)
rate.sleep()
timer = rospy.Timer(rospy.Duration(0.01), lambda event: say("timer", type(event.current_real).__name__), oneshot=True,
                    reset=True)
timer.join(10)
say("timer done", timer.is_alive())
rospy.delete_param("/use_sim_time")
rospy.signal_shutdown("done")
