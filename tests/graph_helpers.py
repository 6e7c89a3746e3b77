"""Helpers for the `rostui graph` tests: the book's turtlesim system as real processes, and app runners.

``book_system`` starts `rostui run turtlesim turtlesim_node --headless` and
the agitr ``pubvel`` program renamed ``teleop_turtle`` (it publishes
turtlesim/Velocity on /turtle1/command_velocity at 2 Hz, as the book's
teleop node would while a key is held), then waits until the master holds
every registration of Figure 2.4, so an app started afterwards sees the
whole graph in its first poll.
"""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any, Awaitable, Callable

from conftest import until
from live_helpers import Program, start_headless_sim, wait_until

from rostui.apps.graph.app import GraphApp
from rostui.core.xmlrpc import call_sync, ros_result
from rostui.models.graph.model import RosGraph

#: (publisher, topic, subscriber or None) of the book's turtlesim graph.
BOOK_EDGES = (
    ("/teleop_turtle", "/turtle1/command_velocity", "/turtlesim"),
    ("/turtlesim", "/turtle1/pose", None),
    ("/turtlesim", "/turtle1/color_sensor", None),
)


def master_graph(env: dict[str, str]) -> RosGraph | None:
    """The registrations of the master in ``env`` (None when it does not answer)."""
    uri = env["ROS_MASTER_URI"]
    try:
        state = ros_result(call_sync(uri, "getSystemState", "/graph_test", timeout=5.0))
        types = ros_result(call_sync(uri, "getTopicTypes", "/graph_test", timeout=5.0))
    except Exception:
        return None
    return RosGraph.from_wire(state, types)


def has_edges(env: dict[str, str], edges: tuple[tuple[str, str, str | None], ...]) -> bool:
    """True when the master holds every (publisher, topic, subscriber) registration."""
    graph = master_graph(env)
    if graph is None:
        return False
    for pub, topic, sub in edges:
        if pub not in graph.publishers.get(topic, ()):
            return False
        if sub is not None and sub not in graph.subscribers.get(topic, ()):
            return False
    return True


def book_system(env: dict[str, str], tmp: Path) -> list[Program]:
    """Headless turtlesim and teleop_turtle (pubvel), registered; the caller stops them."""
    programs = [start_headless_sim(env, tmp),
                Program(env, tmp, "agitr", "pubvel", "__name:=teleop_turtle", label="teleop_turtle")]
    try:
        wait_until(lambda: has_edges(env, BOOK_EDGES), "the book's turtlesim graph to register")
    except BaseException:
        stop_programs(programs)
        raise
    return programs


def stop_programs(programs: list[Program]) -> None:
    """Stop every program (Ctrl-C, then SIGKILL)."""
    for program in reversed(programs):
        program.stop()



def shown_names(app: GraphApp) -> set[str]:
    """Names of the vertices drawn now."""
    return {v.name for v in app.shown.vertices.values()} if app.shown is not None else set()


def status(app: GraphApp) -> str:
    """The status line's text."""
    return str(app.query_one("#status").render())


def banner(app: GraphApp) -> str:
    """The red problem line's text ("" when hidden)."""
    widget = app.query_one("#banner")
    return str(widget.render()) if widget.display else ""


def empty_screen(app: GraphApp) -> str:
    """The explanation shown in place of an empty drawing ("" when hidden)."""
    widget = app.query_one("#empty")
    return str(widget.render()) if widget.display else ""


def details(app: GraphApp) -> str:
    """The details pane's text ("" when hidden)."""
    if not app.query_one("#details-pane").display:
        return ""
    return str(app.query_one("#details").render())


def screen_text(app: GraphApp) -> str:
    """The whole graph drawing as text."""
    canvas = app.graph_view.canvas
    return canvas.text() if canvas is not None else ""


async def settled(app: GraphApp, what: str = "the drawing to show the current view") -> None:
    """Wait until the app has polled once and draws the current view."""
    await until(lambda: app.polls >= 1 and app.settled, what)


def run_graph(app: GraphApp, scenario: Callable[[Any, GraphApp], Awaitable[None]],
              size: tuple[int, int] = (120, 32)) -> None:
    """Run ``app`` headless, wait for its first drawing, then play ``scenario(pilot, app)``."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await settled(app, "the first graph")
            await scenario(pilot, app)

    asyncio.run(main())
