"""The turtlesim app driven with Textual's pilot: keys, selection, quitting, colours, resizing.

Each test runs the real :class:`TurtlesimApp` (turtlesim and teleop nodes on
Textual's loop) against a `rostui core` master or, with no master at
ROS_MASTER_URI, against the embedded one the app starts itself.
"""

from __future__ import annotations

import asyncio
import socket
import subprocess
import sys
from typing import Any, Awaitable, Callable

import pytest
from rich.color import Color, ColorSystem
from rich.style import Style
from textual.geometry import Region
from textual.pilot import Pilot

from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node.node import AsyncNode
from rostui.models.contrast import MINIMUM, RGB, contrast_ratio
from rostui.turtlesim.app import TurtlesimApp
from rostui.turtlesim.render import TurtleView, ViewLayout
from rostui.turtlesim.world import DEFAULT_PEN, UPDATE_PERIOD

from cli_helpers import rostui
from colour_modes import MODES, force_mode, shown
from conftest import REPO, master_port, until

DEADLINE = 30.0
Scenario = Callable[[Pilot, TurtlesimApp], Awaitable[None]]



def run_app(app: TurtlesimApp, scenario: Scenario, size: tuple[int, int] = (80, 24)) -> None:
    """Run ``app`` headless, wait until its nodes run, then play ``scenario``."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await asyncio.wait_for(app.started.wait(), DEADLINE)
            await scenario(pilot, app)

    asyncio.run(main())


async def node_list() -> list[str]:
    """`rostui node list` run as a separate process while this loop keeps serving."""
    proc = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "rostui", "node", "list", cwd=REPO,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    out, err = await asyncio.wait_for(proc.communicate(), DEADLINE)
    assert proc.returncode == 0, err.decode()
    return out.decode().split()


def port_open(port: int) -> bool:
    """True when something accepts connections on 127.0.0.1:port."""
    try:
        with socket.create_connection(("127.0.0.1", port), timeout=1.0):
            return True
    except OSError:
        return False


def status_text(app: TurtlesimApp) -> str:
    """What the status line shows."""
    return str(app.query_one("#status").render())


def test_arrow_keys_drive_the_turtle_and_publish_both_topics(rostui_core: Any) -> None:
    """Up drives turtle1 forward, Left turns it; each key goes out as Twist and as the book's Velocity."""
    velocities: list[Any] = []

    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        assert app.embedded is None  # rostui core answered: reused, not replaced
        listener = await AsyncNode("listener").start()
        try:
            await listener.subscribe("/turtle1/command_velocity", get_message_class("turtlesim/Velocity"),
                                     velocities.append)
            turtle = app.sim.world.turtles["turtle1"]
            x0, theta0 = turtle.x, turtle.theta
            await pilot.press("up")
            await until(lambda: turtle.x > x0 + 0.5, "turtle1 to move forward (east)")
            await until(lambda: turtle.linear_x == 0.0, "the command to expire after 1 s")
            await pilot.press("left")
            await until(lambda: turtle.theta > theta0 + 0.5, "turtle1 to turn left")
            await until(lambda: any(v.angular == 2.0 for v in velocities), "a Velocity with angular 2.0")
            assert "turtle1 x" in status_text(app)
        finally:
            await listener.shutdown()

    run_app(TurtlesimApp(), scenario)
    assert any(v.linear == 2.0 and v.angular == 0.0 for v in velocities)


def test_embedded_master_when_none_answers_and_gone_after_q(ros_env: dict[str, str]) -> None:
    """No master: the app starts one; `rostui node list` shows the book's nodes; q stops it all."""
    port = master_port(ros_env)
    assert not port_open(port)
    listed: list[str] = []

    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        assert app.embedded is not None
        assert "embedded master" in status_text(app)
        listed.extend(await node_list())
        turtle = app.sim.world.turtles["turtle1"]
        y0 = turtle.y
        await pilot.press("left")
        await until(lambda: turtle.theta > 0.5, "turtle1 to turn left")
        await pilot.press("up")
        await until(lambda: turtle.y > y0 + 0.3, "turtle1 to move up after turning left")
        await pilot.press("q")

    app = TurtlesimApp()
    run_app(app, scenario)
    assert listed == ["/rosout", "/teleop_turtle", "/turtlesim"]
    assert app.return_code == 0
    assert not port_open(port), "the embedded master still listens after q"


def test_q_unregisters_both_nodes(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """After q, the master no longer knows /turtlesim or /teleop_turtle (the master itself stays)."""
    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        assert "/turtlesim" in await node_list()
        await pilot.press("q")

    app = TurtlesimApp()
    run_app(app, scenario)
    result = rostui(["node", "list"], ros_env)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["/rosout"]


def test_tab_selects_a_spawned_turtle_and_keys_drive_it(rostui_core: Any) -> None:
    """Spawn turtle2 through /spawn; Tab selects it (status shows it); Up moves turtle2, not turtle1."""
    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        caller = await AsyncNode("spawner").start()
        try:
            reply = await caller.service_proxy("/spawn", get_service_class("turtlesim/Spawn")).call(
                x=2.0, y=2.0, theta=0.0, name="turtle2")
            assert reply.name == "turtle2"
        finally:
            await caller.shutdown()
        assert app.selected == "turtle1"
        await pilot.press("tab")
        assert app.selected == "turtle2"
        assert app.query_one(TurtleView).selected == "turtle2"
        await until(lambda: status_text(app).startswith("turtle2 x 2.00 y 2.00"), "turtle2 in the status line")
        world = app.sim.world
        t1, t2 = world.turtles["turtle1"], world.turtles["turtle2"]
        x1, x2 = t1.x, t2.x
        await pilot.press("up")
        await until(lambda: t2.x > x2 + 0.5, "turtle2 to move")
        assert t1.x == x1
        await pilot.press("tab")
        assert app.selected == "turtle1"

    run_app(TurtlesimApp(), scenario)


def test_hitting_the_wall_shows_the_warning(rostui_core: Any) -> None:
    """Driving into the east wall: the status line shows turtlesim's WARN, as its terminal would."""
    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        world = app.sim.world
        world.teleport_absolute("turtle1", 10.8, 5.5, 0.0)
        turtle = world.turtles["turtle1"]
        await pilot.press("up")
        await until(lambda: "[WARN] Oh no! I hit the wall!" in status_text(app), "the wall WARN in the status line")
        assert turtle.x <= 11.09

    run_app(TurtlesimApp(), scenario)


def test_ros_args_reach_the_turtlesim_node(rostui_core: Any) -> None:
    """`__ns:=sim1` puts both nodes and the turtle's topics in /sim1; the keys still drive turtle1."""
    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        assert await node_list() == ["/rosout", "/sim1/teleop_turtle", "/sim1/turtlesim"]
        turtle = app.sim.world.turtles["turtle1"]
        x0 = turtle.x
        await pilot.press("up")
        await until(lambda: turtle.x > x0 + 0.5, "turtle1 to move in /sim1")

    run_app(TurtlesimApp(["__ns:=sim1"]), scenario)


def test_without_teleop_keys_do_not_drive(rostui_core: Any) -> None:
    """teleop=False (turtlesim_node with a renderer): no /teleop_turtle, arrow keys move nothing."""
    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        assert await node_list() == ["/rosout", "/turtlesim"]
        turtle = app.sim.world.turtles["turtle1"]
        x0 = turtle.x
        await pilot.press("up")
        await asyncio.sleep(0.3)
        assert turtle.x == x0
        assert "drive" not in status_text(app)

    run_app(TurtlesimApp(teleop=False), scenario)


def test_unreachable_remote_master_is_one_error(monkeypatch: pytest.MonkeyPatch, ros_env: dict[str, str]) -> None:
    """A master URI on another machine with nothing answering: exit status 1, nothing started."""
    monkeypatch.setenv("ROS_MASTER_URI", "http://192.0.2.1:11311")
    monkeypatch.delenv("ROS_IP", raising=False)
    app = TurtlesimApp()

    async def main() -> None:
        async with app.run_test(size=(80, 24)) as pilot:
            await until(lambda: app.return_code is not None, "the app to give up", timeout=DEADLINE)
            await pilot.pause()

    asyncio.run(main())
    assert app.return_code == 1
    assert app.embedded is None


def test_no_terminal_is_one_error_line(ros_env: dict[str, str]) -> None:
    """`rostui turtlesim` with stdin/stdout not a TTY: one line on stderr, exit status 1."""
    result = rostui(["turtlesim"], ros_env)
    assert result.returncode == 1
    assert result.stderr.strip().splitlines() == [
        "ERROR: turtlesim draws in a terminal: stdin and stdout must be a TTY "
        "(use `rostui run turtlesim turtlesim_node --headless` without one)"]


def test_teleop_takes_one_topic(ros_env: dict[str, str]) -> None:
    """`rostui teleop a b`: one error line naming the extra topics."""
    result = rostui(["teleop", "a", "b"], ros_env)
    assert result.returncode == 1
    assert result.stderr.strip() == "ERROR: rostui teleop takes one TOPIC, got 2: a b"


def drive_model(app: TurtlesimApp, linear: float, angular: float, steps: int) -> None:
    """Drive turtle1 through the model (no wall clock involved)."""
    world = app.sim.world
    for _ in range(steps):
        world.command("turtle1", linear, 0.0, angular)
        world.update(UPDATE_PERIOD)
    world.command("turtle1", 0.0, 0.0, 0.0)


#: Glyphs of the turtle sprites (shell, legs, heads).
SPRITE_GLYPHS = frozenset("@()/\\" + "→↗↑↖←↙↓↘")


def rendered_world(view: TurtleView, system: ColorSystem) -> list[tuple[str, RGB | None, RGB | None, bool]]:
    """Every cell of the square world as the widget renders it: glyph, shown text colour, shown background, bold."""
    width, height = view.size
    layout = ViewLayout.fit(width, height)
    cells = []
    for y, line in enumerate(view.render_lines(Region(0, 0, width, height))):
        x = 0
        for segment in line:
            style = segment.style or Style.null()
            fg, bg = shown(style.color, system, True), shown(style.bgcolor, system, False)
            for char in segment.text:
                if layout.left <= x < layout.left + layout.size and layout.top <= y < layout.top + layout.rows:
                    cells.append((char, fg, bg, bool(style.bold)))
                x += 1
    return cells


def assert_contrast_on_screen(view: TurtleView, system: ColorSystem) -> None:
    """On the rendered cells: every turtle glyph (the selected one bold) and every trail colour keeps contrast >= 3
    against the background under it, as the terminal in ``system`` shows them."""
    background = shown(Color.from_rgb(*view.world.background), system, False)
    assert background is not None
    cells = rendered_world(view, system)
    glyphs = [c for c in cells if c[0] in SPRITE_GLYPHS]
    assert any(bold for *_, bold in glyphs), "no selected turtle drawn"
    assert any(not bold for *_, bold in glyphs), "no other turtle drawn"
    for glyph, fg, bg, bold in glyphs:
        assert fg is not None and bg == background
        assert contrast_ratio(fg, bg) >= MINIMUM, (glyph, fg, bg, bold)
    trails: set[RGB | None] = set()
    for glyph, fg, bg, _ in cells:
        trails |= {fg, bg} if glyph == "▀" else {bg} if glyph == " " else set()
    trails -= {None, background}
    assert trails, "no trail drawn"
    for trail in trails:
        assert trail is not None and contrast_ratio(trail, background) >= MINIMUM, (trail, background)


#: The book's backgrounds: turtlesim's default blue, chapter 7's yellow, white and black.
BOOK_BACKGROUNDS = [(69, 86, 255), (255, 255, 0), (255, 255, 255), (0, 0, 0)]


@pytest.mark.parametrize("system", list(MODES), ids=lambda m: m.name.lower())
def test_turtles_and_trails_keep_contrast_on_the_books_backgrounds(
        rostui_core: Any, monkeypatch: pytest.MonkeyPatch, system: ColorSystem) -> None:
    """In 16, 256 and truecolor mode, on each of the book's backgrounds, the rendered cells of the selected turtle,
    another turtle and their trails (default pen, and a red pen) have contrast >= 3 against the background; each
    turtle stands on its own trail."""
    name = force_mode(monkeypatch, system)

    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        assert app.console.color_system == name
        view = app.query_one(TurtleView)
        world = app.sim.world
        await app.sim.spawn("turtle2", 2.5, 2.5, 0.0)
        world.set_pen("turtle2", 255, 0, 0, 3, False)
        app.select("turtle1")
        for background in BOOK_BACKGROUNDS:
            world.clear(background)
            for turtle in ("turtle1", "turtle2"):
                for _ in range(60):
                    world.command(turtle, 1.5, 0.0, 0.6)
                    world.update(UPDATE_PERIOD)
                world.command(turtle, 0.0, 0.0, 0.0)
                assert world.color_under(turtle) == world.turtles[turtle].pen.rgb  # standing on its trail
            view.draw_frame()
            assert_contrast_on_screen(view, system)

    run_app(TurtlesimApp(), scenario)


@pytest.mark.parametrize("system", [ColorSystem.STANDARD, ColorSystem.EIGHT_BIT], ids=["standard", "256"])
def test_trails_and_turtles_stay_visible_in_few_colours(
        rostui_core: Any, monkeypatch: pytest.MonkeyPatch, system: ColorSystem) -> None:
    """On 16- and 256-colour terminals trails keep contrast even when the background is set so close to the pen
    colour that both would become the same terminal colour."""
    force_mode(monkeypatch, system)
    close_to_pen = (170, 178, 250)
    number = Color.from_rgb(*DEFAULT_PEN.rgb).downgrade(system).number
    assert Color.from_rgb(*close_to_pen).downgrade(system).number == number

    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        view = app.query_one(TurtleView)
        await app.sim.spawn("turtle2", 2.5, 2.5, 0.0)
        app.select("turtle1")
        drive_model(app, 2.0, 0.0, 60)
        view.draw_frame()
        assert_contrast_on_screen(view, system)
        node = app.sim.node
        for channel, value in zip("rgb", close_to_pen):
            await node.set_param(f"/background_{channel}", value)
        await pilot.press("c")
        await until(lambda: app.sim.world.background == close_to_pen, "the clear with the new background")
        drive_model(app, 0.0, 0.0, 1)
        drive_model(app, 2.0, 0.0, 40)
        view.draw_frame()
        assert_contrast_on_screen(view, system)

    run_app(TurtlesimApp(), scenario)


def world_box(view: TurtleView) -> tuple[int, int, int, int]:
    """Columns and rows (first, last) of the cells painted in the background colour."""
    background = view.world.background
    spots = [(x, y) for y in range(view.size.height) for x, cell in enumerate(view.cells(y))
             if cell[2] == background and cell[0] == " "]
    xs, ys = [x for x, _ in spots], [y for _, y in spots]
    return min(xs), max(xs), min(ys), max(ys)


def find_glyph(view: TurtleView, glyph: str) -> tuple[int, int]:
    """The cell of the first ``glyph`` on screen."""
    for y in range(view.size.height):
        for x, cell in enumerate(view.cells(y)):
            if cell[0] == glyph:
                return x, y
    raise AssertionError(f"{glyph!r} is not drawn")


def test_world_stays_square_and_centred_on_resize(rostui_core: Any) -> None:
    """Resizing the terminal re-fits the square world at once; turtle1 stays at its centre."""
    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        view = app.query_one(TurtleView)
        for width, height in ((80, 24), (120, 40), (50, 30), (40, 12)):
            await pilot.resize_terminal(width, height)
            await until(lambda: view.size.width == width, f"the view to be {width} wide")
            view.draw_frame()
            x0, x1, y0, y1 = world_box(view)
            cells_wide = x1 - x0 + 1
            rows = y1 - y0 + 1
            side = min(width, 2 * view.size.height)
            assert cells_wide == side
            assert rows == (side + 1) // 2
            gx, gy = find_glyph(view, "@" if side >= 40 else "→")
            assert abs(gx - (x0 + x1) / 2) <= 1 and abs(gy - (y0 + y1) / 2) <= 1

    run_app(TurtlesimApp(), scenario)


def test_a_moving_turtle_repaints_only_the_changed_cells(rostui_core: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    """Frames repaint a few one-row spans around the turtle, never the whole widget."""
    regions: list[Any] = []

    async def scenario(pilot: Pilot, app: TurtlesimApp) -> None:
        view = app.query_one(TurtleView)
        view.draw_frame()
        original = view.refresh

        def record(*args: Any, **kwargs: Any) -> Any:
            regions.append(args)
            return original(*args, **kwargs)

        monkeypatch.setattr(view, "refresh", record)
        for _ in range(10):
            drive_model(app, 2.0, 1.0, 4)
            view.draw_frame()
        monkeypatch.undo()

    run_app(TurtlesimApp(), scenario)
    assert regions, "nothing was repainted while the turtle moved"
    assert all(len(args) == 1 for args in regions), "a frame asked for a full repaint"
    for (region,) in regions:
        assert region.height == 1 and region.width <= 12
