"""Node names: a second node with the same name replaces the first (both masters)."""

from __future__ import annotations

from interop_helpers import example, rospy_peer, spawn, wait_for_node  # noqa: F401


def test_same_name_replaces_rostui_node(any_master, spawn, ros_env):
    first = spawn(example("listener.py", "__name:=dup"), label="first rostui listener")
    wait_for_node(ros_env, "/dup")
    second = spawn(example("listener.py", "__name:=dup"), label="second rostui listener")
    first.wait_exit()
    assert "new node registered with same name" in first.output, first.describe()
    assert second.proc.poll() is None, second.describe()
    wait_for_node(ros_env, "/dup")


def test_same_name_rospy_replaces_rostui_node(any_master, rospy_available, spawn, ros_env):
    first = spawn(example("listener.py", "__name:=dup"), label="rostui listener")
    wait_for_node(ros_env, "/dup")
    spawn(rospy_peer("rospy_listener.py", "/chatter", "1", "__name:=dup"), label="rospy listener")
    first.wait_exit()
    assert "new node registered with same name" in first.output, first.describe()
