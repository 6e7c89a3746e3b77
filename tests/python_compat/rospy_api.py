"""rospy's public API, exercised; run under Debian's rospy and under `rostui python`, its `=` lines must match."""

import sys
import threading

import genpy
import rospy
from rospy_tutorials.srv import AddTwoInts, AddTwoIntsRequest, AddTwoIntsResponse
from std_msgs.msg import String


def say(*items):
    # one write per line: at DEBUG, rospy's own threads log to stdout too ("connecting to ..."), and print()'s
    # separate writes of items, spaces and newline let such a line land inside ours
    sys.stdout.write(" ".join(["=", *map(str, items)]) + "\n")
    sys.stdout.flush()


say("before", rospy.get_name(), rospy.get_caller_id(), rospy.get_namespace())
rospy.init_node("api", argv=sys.argv, anonymous=False, log_level=rospy.DEBUG, disable_signals=True)
say("name", rospy.get_name(), rospy.get_namespace(), rospy.names.resolve_name("chatter"), rospy.resolve_name("~p"))
say("remapped", rospy.resolve_name("from_here"), rospy.names.get_caller_id())
say("myargv", rospy.myargv())
say("mappings", rospy.names.get_mappings(), rospy.names.remap_name("/from_here"), rospy.names.remap_name("other"),
    rospy.names.ns_join("/a", "b"), rospy.names.make_global_ns("x"), rospy.Header._type)
say("time", repr(rospy.Time(3, 5)), repr(rospy.Duration(2)), isinstance(rospy.Time.now(), genpy.Time),
    type(rospy.get_rostime()).__name__, repr(rospy.Time(5) - rospy.Time(3)), rospy.get_time() > 0)

rospy.set_param("~gain", 2.5)
rospy.set_param("/api_test/nested", {"a": 1, "b": "x"})
say("param", rospy.get_param("~gain"), rospy.get_param("/api_test/nested/b"), rospy.has_param("/api_test/nested"),
    rospy.get_param("/missing", "dflt"), rospy.get_param("/api_test/nested"))
say("cached", rospy.get_param_cached("~gain"), rospy.get_param_cached("~gain"))
say("search", rospy.search_param("nested"), rospy.search_param("nowhere"))
say("names", sorted(n for n in rospy.get_param_names() if n.startswith("/api")))
rospy.delete_param("/api_test")
try:
    rospy.get_param("/api_test/nested/a")
except KeyError:
    say("deleted")


def add(req):
    return AddTwoIntsResponse(req.a + req.b)


def bad(req):
    raise rospy.ServiceException("no")


rospy.Service("api_add", AddTwoInts, add)
rospy.Service("api_bad", AddTwoInts, bad)
rospy.wait_for_service("api_add", timeout=10)
proxy = rospy.ServiceProxy("api_add", AddTwoInts, persistent=True)
say("calls", proxy(1, 2).sum, proxy(a=3, b=4).sum, proxy.call(AddTwoIntsRequest(5, 6)).sum)
proxy.close()
try:
    rospy.wait_for_service("nothing_here", timeout=0.3)
except rospy.ROSException as exc:
    say("wait timeout", type(exc).__name__)
try:
    rospy.ServiceProxy("api_bad", AddTwoInts)(1, 1)
except rospy.ServiceException:
    say("service error")

pub = rospy.Publisher("api_chatter", String, queue_size=1, latch=True)
pub.publish(String(data="latched"))
say("wait_for_message", rospy.wait_for_message("api_chatter", String, timeout=10).data)
got = []
heard = threading.Event()


def callback(msg, extra):
    got.append((msg.data, extra))
    heard.set()


sub = rospy.Subscriber("api_chatter", String, callback, callback_args="extra", queue_size=1, buff_size=1 << 16)
heard.wait(10)
say("callback_args", got[0], sub.resolved_name, pub.resolved_name, pub.get_num_connections() >= 1)
say("published", ["/api_chatter", "std_msgs/String"] in rospy.get_published_topics())
sub.unregister()

fired = threading.Event()
events = []


def tick(event):
    events.append(event)
    fired.set()


rospy.Timer(rospy.Duration(0.05), tick, oneshot=True)
fired.wait(10)
say("timer", type(events[0].current_real).__name__, type(events[0].current_expected).__name__, events[0].last_real)
rate = rospy.Rate(100)
rate.sleep()
rospy.sleep(rospy.Duration(0, 1000))
for _ in range(3):
    rospy.loginfo_once("once")
    rospy.logwarn_throttle(60, "throttled")
    rospy.logdebug("debug %s", 1)
say("exceptions", issubclass(rospy.ROSInterruptException, rospy.ROSException),
    issubclass(rospy.ROSTimeMovedBackwardsException, rospy.ROSInterruptException),
    rospy.exceptions.ROSException is rospy.ROSException, rospy.get_node_uri().startswith("http://"))
rospy.on_shutdown(lambda: say("hook ran"))
say("is_shutdown", rospy.is_shutdown())
rospy.signal_shutdown("done")
say("is_shutdown", rospy.is_shutdown())
