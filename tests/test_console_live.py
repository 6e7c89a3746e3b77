"""The console against live systems: a real rospy node under real roscore, and masters that go away.

The app runs headless on the test's loop; the master (real `roscore` or
`rostui core`) and the rospy node are separate processes with a private
ROS_HOME on a free port.
"""

from __future__ import annotations

import asyncio
import subprocess
from pathlib import Path
from typing import Any

import pytest
from conftest import (
    SYSTEM_PYTHON, core_argv, have_rospy, master_port, need_command, need_peer, stop_process, until, wait_for_port,
)
from console_helpers import DEADLINE, log_until_seen
from textual.pilot import Pilot

from rostui.apps.console.app import ConsoleApp
from rostui.core.node.node import AsyncNode
from rostui.models.console.model import ConsoleOptions

ROSPY_LOGGER = r'''
import rospy
rospy.init_node("console_rospy")
n = 0
rate = rospy.Rate(5)
while not rospy.is_shutdown():
    rospy.loginfo("rospy says %d", n)
    if n % 3 == 0:
        rospy.logwarn("rospy warns %d", n)
    n += 1
    rate.sleep()
'''


def status(app: ConsoleApp) -> str:
    """The status line's text."""
    return app.status_bar.plain


def run(app: ConsoleApp, scenario: Any, size: tuple[int, int] = (140, 30)) -> None:
    """Run ``app`` headless and play ``scenario``."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await scenario(pilot, app)

    asyncio.run(main())


def test_a_rospy_nodes_messages_appear_under_real_roscore(real_roscore: Any, ros_env: dict[str, str],
                                                          tmp_path: Path) -> None:
    """rospy logs INFO and WARN under roscore; the console shows them with the node, file and topics."""
    need_peer(have_rospy(), "rospy (Debian python3-rospy)")
    script = tmp_path / "console_rospy.py"
    script.write_text(ROSPY_LOGGER)
    proc = subprocess.Popen([SYSTEM_PYTHON, str(script)], env=ros_env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)

    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        def rospy_messages() -> list[Any]:
            return [e for _, e in app.model.shown() if e.node == "/console_rospy"]

        await until(lambda: len({e.level for e in rospy_messages()}) == 2, "rospy's INFO and WARN messages")
        entry = next(e for e in rospy_messages() if e.level == 4)
        assert entry.message.startswith("rospy warns ")
        assert (entry.file, entry.function, entry.line) == ("console_rospy.py", "<module>", 9)
        assert "/rosout" in entry.topics
        await until(lambda: any("rospy warns" in line and "WARN  /console_rospy" in line
                                for line in app.table.visible_texts()), "a rospy warning drawn in the table")
        await pilot.press("3")  # hide WARN
        assert {e.level for e in rospy_messages()} == {2}

    try:
        run(ConsoleApp(ConsoleOptions()), scenario)
    finally:
        stop_process(proc)


def start_master(kind: str, env: dict[str, str]) -> subprocess.Popen:
    """Start `rostui core` or a real `roscore` on the environment's port and wait for it."""
    port = master_port(env)
    proc = subprocess.Popen(core_argv(kind, port), env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    wait_for_port(port, timeout=DEADLINE, proc=proc)
    return proc


@pytest.mark.parametrize("kind", ["rostui", "roscore"])
def test_master_going_away_and_coming_back(kind: str, ros_env: dict[str, str]) -> None:
    """The master stops: the app says so and keeps running; a new master starts: messages flow again."""
    if kind == "roscore":
        need_command("roscore")
    masters = [start_master(kind, ros_env)]

    async def talker_seen(app: ConsoleApp, text: str) -> None:
        node = AsyncNode("comeback_talker")
        node.log.console = None
        await node.start()
        try:
            await log_until_seen(app, node, text)
        finally:
            await node.shutdown()

    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await until(lambda: status(app).endswith(f"master {app.master_uri}"), "the console to connect")
        await talker_seen(app, "before the restart")
        # watched while the master stops: its stop can outlast the notification's six seconds on a busy machine
        stopping = asyncio.get_running_loop().run_in_executor(None, stop_process, masters[0])
        await until(lambda: "gone: waiting for it to come back" in status(app)
                    and any(n.title == "master" and "gone" in n.message for n in app._notifications),
                    "the 'master gone' message and its notification")
        await stopping
        assert app.is_running
        masters.append(await asyncio.get_running_loop().run_in_executor(None, start_master, kind, ros_env))
        await until(lambda: status(app).endswith(f"master {app.master_uri}"), "the console to reconnect")
        await talker_seen(app, "after the restart")
        assert app.source is not None and app.source.subscriptions >= 2
        assert [e.message for _, e in app.model.shown()].count("before the restart") >= 1

    try:
        run(ConsoleApp(ConsoleOptions()), scenario)
    finally:
        for proc in masters:
            stop_process(proc)
