"""The loggers app driven with Textual's pilot: node list, selection, loggers, levels by key, Enter and mouse,
and what the user sees when a node dies, a node hangs, or the master goes away and comes back.

Every test runs the real :class:`LoggersApp` against a real `rostui core` on a
free port; the nodes it shows are real rostui nodes, in this process (on the
app's loop) or started as programs.
"""

from __future__ import annotations

import asyncio
import re
import signal
import subprocess
import xmlrpc.client
from pathlib import Path
from typing import Any, Iterator

import pytest
from conftest import start_rostui_core, stop_process
from live_helpers import Program
from loggers_helpers import (
    highlight_node, listed_nodes, marked_level, notice, quick_app, run_app, select_logger, select_node, shown_levels,
    until,
)
from textual.pilot import Pilot

from rostui.apps.loggers.app import LoggersApp
from rostui.apps.loggers.panels import LevelList, LoggerTable, NodeList
from rostui.core.log import Level
from rostui.core.node import AsyncNode
from rostui.models.loggers import LEVEL_NAMES


async def package_node(name: str, *extra_loggers: tuple[str, str]) -> AsyncNode:
    """A rostui node of package agitr on this loop, with extra loggers at their own levels."""
    node = await AsyncNode(name, argv=[], package="agitr").start()
    for logger, level in extra_loggers:
        node.log.tree.set_level(logger, level)
    return node


def test_node_list_follows_the_master(rostui_core: Any) -> None:
    """Nodes that serve get_loggers appear and vanish as they start and shut down; the count is shown."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        await until(lambda: listed_nodes(app) == ["/rosout"], "rostui core's /rosout alone")
        assert notice(app, "nodes") == ("1 node serves get_loggers", "info")
        alpha = await package_node("alpha")
        beta = await package_node("beta")
        await until(lambda: listed_nodes(app) == ["/alpha", "/beta", "/rosout"], "/alpha and /beta listed")
        assert notice(app, "nodes") == ("3 nodes serve get_loggers", "info")
        await beta.shutdown()
        await until(lambda: listed_nodes(app) == ["/alpha", "/rosout"], "/beta gone from the list")
        await alpha.shutdown()

    run_app(quick_app(), scenario)


def test_selecting_a_node_shows_its_loggers_and_levels(rostui_core: Any) -> None:
    """Down selects a node: its loggers with their levels, ros.<package> preselected, its level marked."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        alpha = await package_node("alpha", ("ros.agitr.motor", "WARN"))
        try:
            await select_node(pilot, app, "/alpha")
            assert shown_levels(app) == {"ros": "INFO", "ros.agitr": "INFO", "ros.agitr.motor": "WARN"}
            assert app.logger == "ros.agitr"
            assert marked_level(app) == "INFO"
            assert app.query_one("#loggers-panel").border_title == "Loggers · /alpha"
            assert notice(app, "loggers") == ("3 loggers", "info")
            await select_logger(pilot, app, "ros.agitr.motor")
            assert marked_level(app) == "WARN"
            assert app.query_one("#levels-panel").border_title == "Level · ros.agitr.motor"
            await select_logger(pilot, app, "ros")
            assert marked_level(app) == "INFO"
        finally:
            await alpha.shutdown()

    run_app(quick_app(), scenario)


def test_level_keys_set_the_selected_logger(rostui_core: Any) -> None:
    """d, w, e, f, i each change the node's logger at once; table, mark and notice follow."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        alpha = await package_node("alpha", ("ros.agitr.motor", "WARN"))
        try:
            await select_node(pilot, app, "/alpha")
            for key, level in (("d", "DEBUG"), ("w", "WARN"), ("e", "ERROR"), ("f", "FATAL"), ("i", "INFO")):
                await pilot.press(key)
                await until(lambda: notice(app, "levels") == (f"ros.agitr set to {level}", "ok"),
                            f"the notice for {level}")
                assert alpha.log.tree.effective_level("ros.agitr") == Level[level]
                assert shown_levels(app)["ros.agitr"] == level
                assert marked_level(app) == level
            assert shown_levels(app)["ros.agitr.motor"] == "WARN", "a logger with its own level keeps it"
        finally:
            await alpha.shutdown()

    run_app(quick_app(), scenario)


def test_a_level_is_refused_only_when_the_master_still_lacks_set_logger_level(rostui_core: Any) -> None:
    """A node listed while it served get_loggers alone: w asks the master again before refusing, so a node that
    has registered set_logger_level since the app's last look gets its level (a node announces one service after
    the other, and a poll may fall between them)."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        from rostui.core.msg import get_service_class

        half = await AsyncNode("half", argv=[], package="agitr").start(announce=False)
        link = half.logging
        try:
            await half.advertise_service("~get_loggers", get_service_class("roscpp/GetLoggers"), link.get_loggers)
            await pilot.press("r")  # the app looks at the master now, and then not for 60 s
            await select_node(pilot, app, "/half")
            await select_logger(pilot, app, "ros.agitr")
            await pilot.press("w")
            await until(lambda: notice(app, "levels") == ("/half does not serve set_logger_level", "error"),
                        "the refusal while the service is missing", app=app)
            await half.advertise_service("~set_logger_level", get_service_class("roscpp/SetLoggerLevel"),
                                         link.set_logger_level)
            await pilot.press("w")  # before the app's next look at the master (every 60 s here)
            await until(lambda: notice(app, "levels") == ("ros.agitr set to WARN", "ok"), "the level set", app=app)
            assert half.log.tree.effective_level("ros.agitr") == Level.WARN
        finally:
            await half.shutdown()

    run_app(quick_app(node_period=60.0), scenario)


def test_enter_walks_node_logger_and_level_lists(rostui_core: Any) -> None:
    """Enter on a node goes to its loggers, Enter on a logger to the levels, Enter on a level sets it."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        alpha = await package_node("alpha")
        try:
            await until(lambda: "/alpha" in listed_nodes(app), "/alpha listed")
            await pilot.press("down", "enter")
            await until(lambda: app.node == "/alpha" and app.logger == "ros.agitr", "/alpha's loggers", app=app)
            assert app.focused is app.query_one(LoggerTable)
            await pilot.press("enter")
            assert app.focused is app.query_one(LevelList)
            await pilot.press("down", "down", "enter")  # INFO -> WARN -> ERROR
            await until(lambda: alpha.log.tree.effective_level("ros.agitr") == Level.ERROR, "ros.agitr at ERROR")
            await until(lambda: marked_level(app) == "ERROR", "ERROR marked")
        finally:
            await alpha.shutdown()

    run_app(quick_app(), scenario)


def test_mouse_selects_node_logger_and_level(rostui_core: Any) -> None:
    """Clicks do what keys do: a node, then a logger row, then a level."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        alpha = await package_node("alpha", ("ros.agitr.motor", "WARN"))
        try:
            await until(lambda: "/alpha" in listed_nodes(app), "/alpha listed")
            assert await pilot.click(NodeList, offset=(2, listed_nodes(app).index("/alpha")))
            await until(lambda: app.node == "/alpha" and len(app.loggers) == 3, "/alpha's loggers after a click",
                        app=app)
            row = app.query_one(LoggerTable).logger_names.index("ros.agitr.motor")
            assert await pilot.click(LoggerTable, offset=(2, 1 + row))  # row 0 is the header
            await until(lambda: app.logger == "ros.agitr.motor", "the clicked logger selected")
            assert marked_level(app) == "WARN"
            assert await pilot.click(LevelList, offset=(4, LEVEL_NAMES.index("ERROR")))
            await until(lambda: alpha.log.tree.effective_level("ros.agitr.motor") == Level.ERROR,
                        "ros.agitr.motor at ERROR after the click")
            await until(lambda: shown_levels(app).get("ros.agitr.motor") == "ERROR", "the table to show ERROR")
        finally:
            await alpha.shutdown()

    run_app(quick_app(), scenario)


def test_first_node_selected_at_start(rostui_core: Any) -> None:
    """Without any key, the first listed node is selected and its loggers shown (d without one: see below)."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        await until(lambda: "/rosout" in listed_nodes(app), "/rosout listed")
        await until(lambda: app.node == listed_nodes(app)[0] and bool(app.loggers), "the first node's loggers")
        assert app.query_one(NodeList).highlighted_name == app.node
        assert app.logger and notice(app, "levels")[0] == "d i w e f or Enter: set level"

    run_app(quick_app(), scenario)


def test_node_killed_while_selected(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """SIGKILL the selected node (it cannot unregister): a red line in the loggers panel, no crash."""
    count = Program(ros_env, tmp_path, "agitr", "count")
    try:
        async def scenario(pilot: Pilot, app: LoggersApp) -> None:
            await select_node(pilot, app, "/count_and_log")
            assert app.logger == "ros.agitr"
            count.proc.send_signal(signal.SIGKILL)
            await until(lambda: notice(app, "loggers")[1] == "error", "an error under the loggers")
            text = notice(app, "loggers")[0]
            assert re.fullmatch(r"node /count_and_log does not answer \(connection (refused|lost: .*)\): "
                                r"it has probably died", text), text
            assert shown_levels(app) == {} and marked_level(app) is None
            await pilot.press("d")
            assert notice(app, "levels") == ("select a node and a logger first", "error")
            assert "/count_and_log" in listed_nodes(app), "the master still lists a killed node"
            zeta = await package_node("zeta")  # the list changes: the dead node is not selected again by it
            await until(lambda: "/zeta" in listed_nodes(app), "/zeta listed")
            await pilot.pause()
            assert app.node == "" and notice(app, "loggers") == (text, "error")
            await zeta.shutdown()
            await pilot.press("r")
            await pilot.pause()
            assert app.is_running

        run_app(quick_app(), scenario)
    finally:
        count.stop()


def test_a_node_too_slow_at_first_shows_its_loggers_once_it_answers(rostui_core: Any, ros_env: dict[str, str],
                                                                    tmp_path: Path) -> None:
    """The first get_loggers times out (the node is stopped, as a busy machine can stall it): the timeout is said;
    once the node answers again its loggers appear with no key pressed (a loaded CI machine found this)."""
    count = Program(ros_env, tmp_path, "agitr", "count")
    try:
        async def scenario(pilot: Pilot, app: LoggersApp) -> None:
            await until(lambda: "/count_and_log" in listed_nodes(app), "/count_and_log listed")
            count.proc.send_signal(signal.SIGSTOP)
            await highlight_node(pilot, app, "/count_and_log")
            await until(lambda: notice(app, "loggers")[1] == "error", "the stopped node's timeout said", app=app)
            assert app.loggers == {}
            count.proc.send_signal(signal.SIGCONT)
            await until(lambda: app.node == "/count_and_log" and app.logger == "ros.agitr",
                        "its loggers, once it answers", app=app)
            assert notice(app, "loggers")[1] == "info"

        run_app(quick_app(timeout=1.0), scenario)
    finally:
        count.proc.send_signal(signal.SIGCONT)
        count.stop()


def test_node_shut_down_while_selected(rostui_core: Any) -> None:
    """The selected node shuts down (unregisters): it leaves the list and the loggers panel says so."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        beta = await package_node("beta")
        await select_node(pilot, app, "/beta")
        await beta.shutdown()
        await until(lambda: "/beta" not in listed_nodes(app), "/beta gone from the list")
        await until(lambda: notice(app, "loggers")[1] == "error", "an error under the loggers")
        assert notice(app, "loggers")[0] == "node /beta is gone: the master no longer lists it"
        assert shown_levels(app) == {} and app.node == ""
        await select_node(pilot, app, "/rosout")
        await pilot.press("w")
        await until(lambda: notice(app, "levels")[1] == "ok", "the level set on /rosout")

    run_app(quick_app(), scenario)


def test_a_node_that_shuts_down_between_look_up_and_call_is_gone_not_dead(
        rostui_core: Any, ros_env: dict[str, str]) -> None:
    """/ghost's get_loggers was looked up while it was registered; when our call connects it has unregistered
    and drops the connection: the master no longer lists it, so it shut down (CI once said "probably died")."""
    import socket
    import struct
    import threading

    from rostui.models.loggers import LoggerLevels, NodeGoneError

    master = xmlrpc.client.ServerProxy(ros_env["ROS_MASTER_URI"])
    services = socket.socket()
    services.bind(("127.0.0.1", 0))
    services.listen(4)
    service_uri, api = f"rosrpc://127.0.0.1:{services.getsockname()[1]}", "http://127.0.0.1:1/"

    def shut_down_on_first_call() -> None:
        conn, _ = services.accept()
        for service in ("get_loggers", "set_logger_level"):
            master.unregisterService("/ghost", f"/ghost/{service}", service_uri)
        conn.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))  # reset, as a closed port
        conn.close()

    for service in ("get_loggers", "set_logger_level"):
        assert master.registerService("/ghost", f"/ghost/{service}", service_uri, api)[0] == 1
    threading.Thread(target=shut_down_on_first_call, daemon=True).start()

    async def main() -> None:
        levels = await LoggerLevels(ros_env["ROS_MASTER_URI"], timeout=5.0).start()
        try:
            with pytest.raises(NodeGoneError, match="^node /ghost is gone: the master no longer lists it$"):
                await levels.loggers("/ghost")
            assert master.registerService("/dead", "/dead/get_loggers", service_uri, api)[0] == 1
            services.close()  # still listed, nothing listening: a node that died
            with pytest.raises(NodeGoneError, match=r"^node /dead does not answer \(connection refused\)"):
                await levels.loggers("/dead")
        finally:
            await levels.close()

    asyncio.run(main())


@pytest.fixture
def hung_node(rostui_core: Any, ros_env: dict[str, str]) -> Iterator[str]:
    """/hung: alive (its slave API answers getPid) but its logger services accept and never answer."""
    import socket
    import threading
    from xmlrpc.server import SimpleXMLRPCServer

    services = socket.socket()
    services.bind(("127.0.0.1", 0))
    services.listen(16)
    slave = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
    slave.register_function(lambda caller_id: [1, "", 4242], "getPid")
    threading.Thread(target=slave.serve_forever, daemon=True).start()
    master = xmlrpc.client.ServerProxy(ros_env["ROS_MASTER_URI"])
    api = f"http://127.0.0.1:{slave.server_address[1]}/"
    for service in ("get_loggers", "set_logger_level"):
        code, message, _ = master.registerService("/hung", f"/hung/{service}",
                                                  f"rosrpc://127.0.0.1:{services.getsockname()[1]}", api)
        assert code == 1, message
    try:
        yield "/hung"
    finally:
        slave.shutdown()
        slave.server_close()
        services.close()


def test_node_that_never_answers_times_out_in_place(hung_node: str) -> None:
    """A node whose get_loggers hangs: after the timeout a red line says so; the rest keeps working."""
    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        await until(lambda: hung_node in listed_nodes(app), "/hung listed")
        node_list = app.query_one(NodeList)
        node_list.focus()
        node_list.highlighted = listed_nodes(app).index(hung_node)
        await until(lambda: notice(app, "loggers")[1] == "error", "a timeout under the loggers")
        assert notice(app, "loggers")[0] == "/hung/get_loggers did not answer within 1 s"
        await asyncio.sleep(1.5)  # pings go on (it answers them): the message stays
        assert notice(app, "loggers") == ("/hung/get_loggers did not answer within 1 s", "error")
        assert app.is_running
        await select_node(pilot, app, "/rosout")
        assert notice(app, "loggers")[1] == "info"

    run_app(quick_app(timeout=1.0), scenario)


def test_master_away_at_start_then_back_then_gone_then_back(ros_env: dict[str, str]) -> None:
    """No master: a red master line and no nodes; the master starts: nodes appear; it stops and restarts: same."""
    cores: list[subprocess.Popen] = []

    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        uri = app.client.master_uri
        await until(lambda: notice(app, "master")[1] == "error", "the master line to turn red")
        assert notice(app, "master")[0] == f"Unable to communicate with master at {uri}; retrying every 0.3 s"
        assert notice(app, "nodes") == ("no master", "error") and listed_nodes(app) == []
        cores.append(await asyncio.to_thread(start_rostui_core, ros_env))
        await until(lambda: notice(app, "master") == (f"master {uri} is answering again", "ok"), "the master back")
        await select_node(pilot, app, "/rosout")
        await asyncio.to_thread(stop_process, cores[-1])
        await until(lambda: notice(app, "master")[1] == "error", "the master line red again")
        await until(lambda: notice(app, "loggers")[1] == "error", "the loggers panel to say the master is gone")
        assert listed_nodes(app) == [] and app.node == ""
        cores.append(await asyncio.to_thread(start_rostui_core, ros_env))
        await until(lambda: notice(app, "master")[1] == "ok", "the master back again")
        await select_node(pilot, app, "/rosout")
        await pilot.press("d")
        await until(lambda: notice(app, "levels")[1] == "ok", "a level set after the master came back")

    try:
        run_app(quick_app(), scenario)
    finally:
        for proc in cores:
            stop_process(proc)


def test_q_quits_with_status_zero(rostui_core: Any) -> None:
    """q leaves the app with exit status 0."""
    app = quick_app()

    async def scenario(pilot: Pilot, app: LoggersApp) -> None:
        await until(lambda: "/rosout" in listed_nodes(app), "/rosout listed")
        await pilot.press("q")

    run_app(app, scenario)
    assert app.return_code == 0
