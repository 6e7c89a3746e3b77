"""Chapter 5, Graph resource names: global, relative (default namespace from __ns or ROS_NAMESPACE),
private (~max_vel of /sim1/pubvel) and anonymous names, as a reader sees them in the node, topic and
parameter lists.
"""

from __future__ import annotations

import re

import pytest

from book_helpers import Desk, desk, dot_edges, lines, ok, poll, start_core

__all__ = ["desk"]

pytestmark = pytest.mark.timeout(300)  # one chapter, start to end, on a busy machine


def test_names_resolve_as_the_book_says(desk: Desk) -> None:
    env = desk.env
    start_core(desk)

    # 5.2: a default namespace from __ns pushes the node and its relative topic names down.
    sim1 = desk.terminal("sim1")
    sim1.run("rostui run turtlesim turtlesim_node --headless __ns:=sim1")
    poll(lambda: "/sim1/turtlesim" in lines(ok("node list", env)), "/sim1/turtlesim to register")
    topics = set(lines(ok("topic list", env)))
    assert {"/sim1/turtle1/pose", "/sim1/turtle1/command_velocity", "/sim1/turtle1/color_sensor"} <= topics
    assert "/turtle1/pose" not in topics

    # ... or from ROS_NAMESPACE, which __ns overrides.
    sim2 = desk.terminal("sim2")
    sim2.run("ROS_NAMESPACE=sim2 rostui run turtlesim turtlesim_node --headless")
    sim3 = desk.terminal("sim3")
    sim3.run("ROS_NAMESPACE=sim2 rostui run turtlesim turtlesim_node --headless __ns:=/a/b/c/d/e/f")
    poll(lambda: {"/sim2/turtlesim", "/a/b/c/d/e/f/turtlesim"} <= set(lines(ok("node list", env))),
         "/sim2/turtlesim and /a/b/c/d/e/f/turtlesim to register")
    assert "/sim2/turtle1/pose" in lines(ok("topic list", env))

    # Tools resolve relative names the same way: turtle1/pose in namespace /sim1 is /sim1/turtle1/pose,
    # g/h/i/j/k/l in /a/b/c/d/e/f is /a/b/c/d/e/f/g/h/i/j/k/l.
    shell = desk.terminal("shell")
    shell.run("ROS_NAMESPACE=sim1 rostui topic echo -n 1 turtle1/pose")
    assert shell.exit_status() == 0
    shell.wait_for(r"^x: 5\.544444\d*\ny: 5\.544444\d*\ntheta: 0\.0\n")
    shell.run("ROS_NAMESPACE=/a/b/c/d/e/f rostui topic pub g/h/i/j/k/l std_msgs/String hello")
    shell.wait_for(r"publishing and latching message")
    assert ok("topic info /a/b/c/d/e/f/g/h/i/j/k/l", env).startswith("Type: std_msgs/String\n")
    assert shell.interrupt() == 0

    # 5.3: a private name ~max_vel of node /sim1/pubvel is /sim1/pubvel/max_vel.
    pubvel = desk.terminal("pubvel")
    pubvel.run("rostui run agitr pubvel_with_max __ns:=sim1 __name:=pubvel _max_vel:=1")
    poll(lambda: "/sim1/pubvel" in lines(ok("node list", env)), "/sim1/pubvel to register")
    assert ok("param get /sim1/pubvel/max_vel", env).strip() in ("1", "1.0")
    poll(lambda: ("/sim1/pubvel", "/sim1/turtlesim", "/sim1/turtle1/command_velocity")
         in dot_edges(ok("graph --dot", env)), "pubvel to drive /sim1's turtle")

    # 5.4: anonymous names; start as many copies as you like.
    first, second = desk.terminal("anon1"), desk.terminal("anon2")
    first.run("rostui run agitr anon")
    second.run("rostui run agitr anon")
    pattern = r"^\[ INFO\] \[\d+\.\d+\]: This message is from (/anon_\d+_\d+)$"
    names = {first.wait_for(pattern)[1], second.wait_for(pattern)[1]}
    assert len(names) == 2
    assert names <= set(lines(ok("node list", env)))
    for terminal in (first, second):
        assert terminal.interrupt() == 0
    assert not any(re.match(r"/anon_", name) for name in lines(ok("node list", env)))
