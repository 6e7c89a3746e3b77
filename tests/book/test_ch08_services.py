"""Chapter 8, Services: rosservice list/node/info/call and rossrv show against turtlesim, Mikey spawned from
the command line (and refused the second time), the client spawn_turtle and the server pubvel_toggle.
"""

from __future__ import annotations

import re

import pytest

from book_helpers import Desk, cli, desk, lines, log_lines, ok, poll, start_core, start_turtlesim_view

__all__ = ["desk"]

pytestmark = pytest.mark.timeout(300)  # one chapter, start to end, on a busy machine

BOOK_SERVICES = ["/clear", "/kill", "/reset", "/rosout/get_loggers", "/rosout/set_logger_level", "/spawn",
                 "/turtle1/set_pen", "/turtle1/teleport_absolute", "/turtle1/teleport_relative",
                 "/turtlesim/get_loggers", "/turtlesim/set_logger_level"]


def test_services_of_chapter_8(desk: Desk) -> None:
    env = desk.env
    start_core(desk)
    sim = start_turtlesim_view(desk)

    # 8.2: listing services, by node, the node offering one, a service's type and its data type.
    assert lines(ok("service list", env)) == BOOK_SERVICES
    services = ok("node info /turtlesim", env).split("Services:")[1].split("\n\n")[0]
    assert sorted(lines(services)) == sorted(f"* {name}" for name in BOOK_SERVICES if not name.startswith("/rosout"))
    assert ok("service node /spawn", env) == "/turtlesim\n"
    assert ok("service node /rosout/get_loggers", env) == "/rosout\n"
    assert re.fullmatch(r"Node: /turtlesim\nURI: rosrpc://[\w.]+:\d+\nType: turtlesim/Spawn\nArgs: x y theta name\n",
                        ok("service info /spawn", env))
    assert ok("srv show turtlesim/Spawn", env) == "float32 x\nfloat32 y\nfloat32 theta\nstring name\n---\nstring name\n\n"
    assert ok("service type /reset", env) == "std_srvs/Empty\n"

    # Calling /spawn: Mikey appears with his own topics and services; a second Mikey is an error.
    shell = desk.terminal("shell")
    shell.run("rostui service call /spawn 3 3 0 Mikey")
    assert shell.exit_status() == 0
    shell.wait_for(r'^name: "Mikey"$')
    assert {"/Mikey/command_velocity", "/Mikey/pose", "/Mikey/color_sensor"} <= set(lines(ok("topic list", env)))
    assert {"/Mikey/set_pen", "/Mikey/teleport_absolute", "/Mikey/teleport_relative"} <= set(
        lines(ok("service list", env)))
    sim.keys("Tab")
    sim.wait_for(r"Mikey x 3\.00 y 3\.00 \S 0\.00")
    shell.run("rostui service call /spawn 3 3 0 Mikey")
    assert shell.exit_status() == 1
    shell.wait_for(r"^ERROR: service \[/spawn\] responded with an error: .*$")

    # 8.3: the client program spawns Leo at (2, 3) facing up, once.
    shell.run("rostui run agitr spawn_turtle")
    assert shell.exit_status() == 0
    assert log_lines(shell.screen(50), "INFO")[-1:] == ["Spawned a turtle named Leo"]
    pose = ok("topic echo -n 1 /Leo/pose", env)
    assert re.search(r"^x: 2\.0\ny: 3\.0\ntheta: 1\.57079", pose, re.MULTILINE), pose
    shell.run("rostui run agitr spawn_turtle")
    assert shell.exit_status() == 0
    assert log_lines(shell.screen(50), "ERROR")[-1:] == ["Failed to spawn."]

    # 8.4: the server program pubvel_toggle; each call of toggle_forward switches forward and rotate.
    toggle = desk.terminal("toggle")
    toggle.run("rostui run agitr pubvel_toggle")
    poll(lambda: "/toggle_forward" in lines(ok("service list", env)), "the toggle_forward service")
    assert ok("service node /toggle_forward", env) == "/pubvel_toggle\n"

    def latest_command() -> tuple[str, str]:
        text = ok("topic echo -n 1 /turtle1/command_velocity", env)
        return re.search(r"^linear: (\S+)\nangular: (\S+)$", text, re.MULTILINE).groups()  # type: ignore[union-attr]
    poll(lambda: latest_command() == ("1.0", "0.0"), "forward commands")
    assert ok("service call /toggle_forward", env) == "\n"
    toggle.wait_for(r"^\[ INFO\] \[\d+\.\d+\]: Now sending rotate commands\.$")
    poll(lambda: latest_command() == ("0.0", "1.0"), "rotate commands")
    assert toggle.interrupt() == 0
    assert cli("service call /toggle_forward", env).returncode != 0  # the server is gone
