"""The rospy-like sync API in a real script: timers, shutdown hooks, waits, params."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from typing import Any

SCRIPT = textwrap.dedent("""
    import threading
    from rostui import client as ros

    String = ros.msg("std_msgs/String")
    Empty = ros.srv("std_srvs/Empty")
    ros.init_node("sync_api", argv=["sync_api.py", "_gain:=2.5", "chatter:=talk"])
    print("name", ros.get_name(), "gain", ros.get_param("~gain"), "remapped", ros.resolve_name("chatter"))
    ticks = []
    ros.Timer(0.05, lambda event: ticks.append(event.current_real))
    ros.Timer(0.05, lambda event: print("oneshot fired", flush=True), oneshot=True)
    ros.on_shutdown(lambda: print("hook ran", flush=True))
    pub = ros.Publisher("chatter", String, queue_size=1, latch=True)
    pub.publish("latched")
    print("waited for", ros.wait_for_message("/talk", String, timeout=10).data, flush=True)
    ros.Service("ping", Empty, lambda req: Empty._response_class())
    ros.wait_for_service("ping", timeout=10)
    ros.ServiceProxy("ping", Empty)()
    try:
        ros.wait_for_service("absent", timeout=0.2)
    except ros.ROSException as exc:
        print("timeout:", exc)
    ros.sleep(0.3)
    print("ticks >= 3:", len(ticks) >= 3)
    ros.set_param("/sync/value", [1, 2])
    print("search", ros.search_param("gain"), "has", ros.has_param("/sync/value"))
    ros.signal_shutdown("done")
    print("ok", ros.ok(), "is_shutdown", ros.is_shutdown())
""")


def test_sync_api_in_a_script(rostui_core: Any, ros_env: dict[str, str]) -> None:
    done = subprocess.run([sys.executable, "-c", SCRIPT], env=ros_env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == "name /sync_api gain 2.5 remapped /talk"
    assert "waited for latched" in lines
    assert "oneshot fired" in lines
    assert "timeout: timeout exceeded while waiting for service /absent" in lines
    assert "ticks >= 3: True" in lines
    assert "search /sync_api/gain has True" in lines
    assert lines[-2:] == ["hook ran", "ok False is_shutdown True"]


INTERRUPTED = textwrap.dedent("""
    import atexit, os, signal, threading
    from rostui import client as ros

    def engines_left():
        print("engines at exit:", [t.name for t in threading.enumerate() if t.name == "rostui-engine" and t.is_alive()],
              flush=True)

    atexit.register(engines_left)  # before the node's: runs after its hooks
    Pose = ros.msg("turtlesim/Pose")
    ros.init_node("interrupted")
    got = threading.Event()
    count = []
    def pose(msg):
        count.append(msg)
        if len(count) == 20:
            got.set()
    ros.Subscriber("turtle1/pose", Pose, pose)
    pub = ros.Publisher("turtle1/pose", Pose, queue_size=10)
    ros.Timer(0.002, lambda event: pub.publish(Pose(x=1.0)))
    got.wait(20)
    os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C while messages arrive
    ros.spin()
    print("spun", flush=True)
""")


def test_ctrl_c_while_messages_arrive_stops_the_engine_before_exit(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """A node interrupted while messages arrive exits 0 with its engine's loop thread ended: a loop thread left
    running while the interpreter finalizes can crash the process on its way out (it did, once, in CI: 139)."""
    done = subprocess.run([sys.executable, "-c", INTERRUPTED], env=ros_env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["spun", "engines at exit: []"], done.stdout


LATE_HOOK = textwrap.dedent("""
    import atexit
    from rostui import client as ros

    def late():  # registered before the node: runs after its shutdown and its engine's stop
        try:
            ros.Publisher("late", ros.msg("std_msgs/String"), queue_size=1)
        except Exception as exc:
            print("late call:", type(exc).__name__, exc, flush=True)

    atexit.register(late)
    ros.init_node("late_hook")
""")


def test_a_call_after_the_engine_stopped_fails_at_once(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """An exit hook that advertises after the node's shutdown gets an error, not a wait for ever."""
    done = subprocess.run([sys.executable, "-c", LATE_HOOK], env=ros_env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["late call: RuntimeError the node's engine has stopped"], done.stdout
