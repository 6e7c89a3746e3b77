"""`rostui publish` and `rostui call` driven by Textual's pilot against Debian's rospy: what the form sends is
what a rospy subscriber receives (decoded here from the bytes rospy serialised again), a rospy service server
gets the request and its response is shown, nothing is registered before ctrl+s, and a form saved with ctrl+w
comes back with ctrl+o. One `rostui core` serves the module; each test has its own topics and services."""

from __future__ import annotations

import asyncio
import time
from pathlib import Path
from typing import Any, Awaitable, Callable, Iterator

import pytest
from textual.pilot import Pilot
from textual.widgets import Input, Log

from rostui.apps.form.app import FormApp
from rostui.core.msg import get_message_class

from conftest import apply_ros_env, running_core, until
from interop_helpers import Peer, graph_nodes, peers, rospy_peer

DEADLINE = 60.0


@pytest.fixture(scope="module")
def master(module_ros_env: dict[str, str]) -> Iterator[dict[str, str]]:
    """A `rostui core` the module's tests share."""
    with running_core("rostui", module_ros_env):
        yield module_ros_env


@pytest.fixture
def env(master: dict[str, str], monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Iterator[dict[str, str]]:
    """The shared master's environment, this test's own, with the current directory in tmp_path."""
    apply_ros_env(monkeypatch, master)
    monkeypatch.chdir(tmp_path)
    yield master


def received(listener: Peer, topic: str, type_name: str) -> list[Any]:
    """The messages the rospy typed listener printed for ``topic``, decoded with rostui's class."""
    cls = get_message_class(type_name)
    out = []
    for line in list(listener.lines):
        parts = line.split()
        if len(parts) == 4 and parts[0] == topic:
            out.append(cls().deserialize(bytes.fromhex(parts[3])))
    return out


def run(app: FormApp, scenario: Callable[[Pilot, FormApp], Awaitable[None]], size: tuple[int, int] = (100, 32)) \
        -> FormApp:
    """Play ``scenario`` on ``app`` once its form is ready; quit it after."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await until(app.ready.is_set, "the form app started", DEADLINE)
            await pilot.pause()
            await scenario(pilot, app)
            if app.is_running:
                await app.action_quit()

    asyncio.run(main())
    return app


async def edit(pilot: Pilot, app: FormApp, path: str, expression: str) -> None:
    """Put the cursor on ``path``, Enter, type ``expression`` over the old one, Enter."""
    table = app.table
    table.move_cursor(row=[row.path for row in table.rows_shown].index(path))
    table.focus()
    await pilot.press("enter")
    await until(lambda: isinstance(app.focused, Input) and app.focused.id == "line", "the expression editor")
    app.focused.value = ""
    await pilot.press(*expression, "enter")
    await until(lambda: app.focused is table, f"{path}'s editor to close")


async def settled(count: Callable[[], int], quiet: float = 1.0) -> None:
    """Wait until ``count()`` has not changed for ``quiet`` seconds (what was in flight has arrived), then check
    that it stays so for as long again: nothing is sent any more."""
    loop = asyncio.get_running_loop()
    last, since = count(), loop.time()
    deadline = since + DEADLINE
    while loop.time() - since < quiet:
        assert loop.time() < deadline, "messages kept arriving after the rate was stopped"
        await asyncio.sleep(0.05)
        if count() != last:
            last, since = count(), loop.time()
    await asyncio.sleep(quiet)
    assert count() == last, "a message arrived after the rate was stopped and the stream had gone quiet"


def status(app: FormApp) -> str:
    """The status line."""
    return app.query_one("#status").text  # type: ignore[attr-defined,no-any-return]


def test_a_twist_edited_and_slid_reaches_rospy_once_then_at_a_rate(env: dict[str, str]) -> None:
    with peers(env) as spawn:
        listener = spawn(rospy_peer("rospy_typed_listener.py", "/form_vel=geometry_msgs/Twist"), label="listener")
        listener.wait_for("subscribed")

        async def scenario(pilot: Pilot, app: FormApp) -> None:
            assert not any(node.startswith("/rostui_publish") for node in graph_nodes(env)), \
                "the form registered before anything was sent"
            assert "nothing is published until ctrl+s or ctrl+r" in app.query_one("#master").text  # type: ignore
            await edit(pilot, app, "linear.x", "1.5")
            app.table.move_cursor(row=5)  # angular.z
            await pilot.press("right", "right", "right", "shift+left", "shift+right", "shift+right")
            assert app.form is not None and app.form.row("angular.z").expression == "0.26"  # type: ignore
            await pilot.press("ctrl+s")
            await until(lambda: received(listener, "/form_vel", "geometry_msgs/Twist"), "the Twist at rospy",
                        DEADLINE)
            first = received(listener, "/form_vel", "geometry_msgs/Twist")[0]
            assert (first.linear.x, first.angular.z, first.linear.y) == (1.5, 0.26, 0.0)
            assert "published one geometry_msgs/Twist on /form_vel (latched)" in status(app)
            assert "#1 on /form_vel: linear: x: 1.5" in "\n".join(app.query_one("#log", Log).lines)
            await edit(pilot, app, "linear.y", "i")
            app.query_one("#rate", Input).value = "20"
            await pilot.press("ctrl+r")
            await until(lambda: len(received(listener, "/form_vel", "geometry_msgs/Twist")) >= 8,
                        "seven more Twists at 20 Hz", DEADLINE)
            assert "publishing /form_vel at 20 Hz" in app.query_one("#master").text  # type: ignore
            await pilot.press("ctrl+s")
            assert status(app) == "publishing /form_vel at a rate: ctrl+r stops it first"
            await pilot.press("ctrl+r")
            assert "stopped after" in status(app)
            await settled(lambda: len(received(listener, "/form_vel", "geometry_msgs/Twist")))
            repeated = received(listener, "/form_vel", "geometry_msgs/Twist")[1:]
            assert [msg.linear.y for msg in repeated] == [float(i) for i in range(1, len(repeated) + 1)]
            assert all(msg.linear.x == 1.5 for msg in repeated)

        run(FormApp("publish", name="/form_vel", type_name="geometry_msgs/Twist"), scenario)
    assert not any(node.startswith("/rostui_publish") for node in graph_nodes(env)), "left registered after quit"


def test_a_header_is_stamped_now_and_a_bare_word_is_text(env: dict[str, str]) -> None:
    with peers(env) as spawn:
        listener = spawn(rospy_peer("rospy_typed_listener.py", "/form_goal=geometry_msgs/PoseStamped"),
                         label="listener")
        listener.wait_for("subscribed")

        async def scenario(pilot: Pilot, app: FormApp) -> None:
            await edit(pilot, app, "header.frame_id", "map")
            await edit(pilot, app, "pose.position.x", "2 * pi")
            await edit(pilot, app, "pose.orientation.w", "cos(pi / 8)")
            await pilot.press("ctrl+s")
            await until(lambda: received(listener, "/form_goal", "geometry_msgs/PoseStamped"), "the goal at rospy",
                        DEADLINE)

        before = time.time()
        run(FormApp("publish", name="/form_goal", type_name="geometry_msgs/PoseStamped"), scenario)
        goal = received(listener, "/form_goal", "geometry_msgs/PoseStamped")[0]
        assert goal.header.frame_id == "map"
        assert before - 1 <= goal.header.stamp.to_sec() <= time.time() + 1
        assert goal.pose.position.x == pytest.approx(6.283185307) and goal.pose.orientation.w == pytest.approx(0.92388)


def test_a_topic_alone_takes_its_type_from_the_master_and_mistakes_are_said(env: dict[str, str]) -> None:
    with peers(env) as spawn:
        listener = spawn(rospy_peer("rospy_typed_listener.py", "/form_count=std_msgs/Int32"), label="listener")
        listener.wait_for("subscribed")

        async def scenario(pilot: Pilot, app: FormApp) -> None:
            assert app.form is not None and app.form.type_name == "std_msgs/Int32"
            assert app.query_one("#type", Input).value == "std_msgs/Int32"
            await edit(pilot, app, "data", "2 ** 40")
            await pilot.press("ctrl+s")
            await until(lambda: "out of range" in status(app), "the range error")
            assert status(app) == "Field [data] value 1099511627776 out of range for int32"
            app.table.move_cursor(row=0)
            await pilot.press("enter")
            await until(lambda: isinstance(app.focused, Input) and app.focused.id == "line", "the editor")
            app.focused.value = ""
            await pilot.press(*"import os", "enter")
            await until(lambda: "not an expression" in str(app.screen.query_one("#line-error").render()),
                        "the editor's complaint")
            await pilot.press("escape")
            assert app.form.row("data").expression == "2 ** 40"  # type: ignore[union-attr]
            await edit(pilot, app, "data", "-7 * i")
            await pilot.press("ctrl+s")
            await until(lambda: received(listener, "/form_count", "std_msgs/Int32"), "the Int32 at rospy", DEADLINE)
            assert received(listener, "/form_count", "std_msgs/Int32")[0].data == -7  # i is 1 for the first

        run(FormApp("publish", name="/form_count"), scenario)


def test_a_call_reaches_a_rospy_server_and_its_response_shows(env: dict[str, str]) -> None:
    with peers(env) as spawn:
        spawn(rospy_peer("rospy_setbool_server.py", "/form_flag"), label="server").wait_for("ready")
        server = spawn(rospy_peer("rospy_setbool_server.py", "/form_broken", "--fail", "no flags today"),
                       label="failing server")
        server.wait_for("ready")

        async def scenario(pilot: Pilot, app: FormApp) -> None:
            assert app.form is not None and [row.path for row in app.form.rows] == ["data"]
            assert "/form_flag [std_srvs/SetBool]" in status(app)
            await edit(pilot, app, "data", "True")
            await pilot.press("ctrl+s")
            await until(lambda: "answered" in status(app), "the response", DEADLINE)
            lines = list(app.query_one("#log", Log).lines)
            assert lines == ["call #1 of /form_flag:", "  success: True", '  message: "got true"'], lines
            name = app.query_one("#name", Input)
            name.value = "/form_broken"
            name.focus()
            await pilot.press("enter")
            await until(lambda: "/form_broken [std_srvs/SetBool]" in status(app), "the second service's form")
            await pilot.press("ctrl+s")
            await until(lambda: "failed" in status(app), "the failure", DEADLINE)
            assert "call to /form_broken failed" in status(app) and "no flags today" in status(app)
            name.value = "/form_nothing"
            name.focus()
            await pilot.press("enter")
            await until(lambda: "service /form_nothing" in status(app), "the missing service said")
            assert app.form is None and app.table.rows_shown == []
            app.table.focus()  # in the service field, ctrl+w deletes a word
            await pilot.press("ctrl+w")
            assert status(app) == "no form to save yet"

        run(FormApp("call", name="/form_flag"), scenario)
        server.wait_for("request data=False")


def test_a_value_the_wire_cannot_hold_is_said_and_the_app_goes_on(env: dict[str, str]) -> None:
    async def scenario(pilot: Pilot, app: FormApp) -> None:
        await edit(pilot, app, "data", "1e39")
        await pilot.press("ctrl+s")
        await until(lambda: "cannot send it" in status(app), "the float32 overflow said", DEADLINE)
        assert "\n" not in status(app) and app.is_running
        await edit(pilot, app, "data", "1e38")
        await pilot.press("ctrl+s")
        await until(lambda: "published one std_msgs/Float32" in status(app), "a float32 that fits sent", DEADLINE)

    run(FormApp("publish", name="/form_big", type_name="std_msgs/Float32"), scenario)


def test_ctrl_w_saves_the_form_and_ctrl_o_loads_it(env: dict[str, str], tmp_path: Path) -> None:
    async def scenario(pilot: Pilot, app: FormApp) -> None:
        await edit(pilot, app, "angular.z", "sin(t)")
        app.query_one("#rate", Input).value = "5"
        await pilot.press("ctrl+w")
        await until(lambda: isinstance(app.focused, Input) and app.focused.id == "line", "the file's name")
        assert app.focused.value == "form_vel.form.yaml"
        await pilot.press("enter")
        await until(lambda: "saved form_vel.form.yaml" in status(app), "the form saved")
        await edit(pilot, app, "angular.z", "0.0")
        app.query_one("#rate", Input).value = ""
        await pilot.press("ctrl+o")
        await until(lambda: isinstance(app.focused, Input) and app.focused.id == "line", "the file's name")
        app.focused.value = "absent.yaml"
        await pilot.press("enter")
        await until(lambda: "no file 'absent.yaml'" in str(app.screen.query_one("#line-error").render()),
                    "the missing file said")
        app.focused.value = "form_vel.form.yaml"
        await pilot.press("enter")
        await until(lambda: "loaded form_vel.form.yaml" in status(app), "the form loaded")
        assert app.form is not None and app.form.row("angular.z").expression == "sin(t)"  # type: ignore
        assert app.query_one("#rate", Input).value == "5"

    run(FormApp("publish", name="/form_vel", type_name="geometry_msgs/Twist"), scenario)
    text = (tmp_path / "form_vel.form.yaml").read_text()
    assert "publish: /form_vel\ntype: geometry_msgs/Twist\nrate: 5.0\n" in text and "angular.z: sin(t)" in text
