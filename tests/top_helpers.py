"""What the `rostui top` tests share: a rospy node and a roscpp node on the test's master, found by their names,
and a node registered from an address that is not this host's (192.0.2.1, a documentation network nothing
answers on)."""

from __future__ import annotations

from typing import Any

from conftest import wait_until
from interop_helpers import Peer, Spawn, rospy_peer

REMOTE_NODE = "/far_away_driver"
REMOTE_URI = "http://192.0.2.1:45100/"


def master_nodes(env: dict[str, str]) -> set[str]:
    """Every node the master lists."""
    from rostui.core.xmlrpc import call_sync, ros_result

    state = ros_result(call_sync(env["ROS_MASTER_URI"], "getSystemState", "/top_test", timeout=5.0))
    return {node for kind in state for _name, nodes in kind for node in nodes}


def node_named(env: dict[str, str], prefix: str) -> str:
    """The one node whose name starts with ``prefix`` (anonymous names end with numbers)."""
    found: list[str] = []

    def listed() -> bool:
        found[:] = sorted(node for node in master_nodes(env) if node.startswith(prefix))
        return len(found) == 1

    wait_until(listed, f"one node named {prefix}*")
    return found[0]


def start_nodes(spawn: Spawn, roscpp_peer_bin: Any, env: dict[str, str]) -> tuple[Peer, str, Peer, str]:
    """A rospy SetBool server and a roscpp one, both running until stopped; each with its node name."""
    rospy_node = spawn(rospy_peer("rospy_setbool_server.py", "/rospy_toggle"), label="rospy server")
    rospy_node.wait_for("^ready$")
    roscpp_node = spawn([str(roscpp_peer_bin), "serve", "/roscpp_toggle"], label="roscpp server")
    return (rospy_node, node_named(env, "/rospy_setbool_server"), roscpp_node, node_named(env, "/roscpp_peer"))


def register_remote_node(env: dict[str, str]) -> None:
    """Register :data:`REMOTE_NODE` as a publisher whose slave API is at :data:`REMOTE_URI`."""
    from rostui.core.xmlrpc import call_sync, ros_result

    ros_result(call_sync(env["ROS_MASTER_URI"], "registerPublisher", REMOTE_NODE, "/far_away_scan",
                         "sensor_msgs/LaserScan", REMOTE_URI, timeout=5.0))
