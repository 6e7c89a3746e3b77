"""`rostui action` driven headless (Textual's pilot) against actionlib_tutorials' Fibonacci server under Debian's
actionlib (a goal sent with ctrl+s followed to its result, another cancelled with ctrl+x) and under rostui's (a goal
that does not fit its type; tests/action_helpers.py). test_action_cli.py sends goals to both sides.
"""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any, Iterator

import pytest
from textual.pilot import Pilot
from textual.widgets import Log, TextArea

from rostui.apps.action.app import ActionApp
from rostui.apps.widgets.name_list import NameList

from action_helpers import fibonacci_server
from conftest import until
from test_actionlib_scripts import TUTORIALS, tutorials_python  # noqa: F401  (fixture)

DEADLINE = 60.0


@pytest.fixture
def fibonacci(request: pytest.FixtureRequest, rostui_core: Any, ros_env: dict[str, str], tutorials_python: Path,
              tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[dict[str, str]]:
    """The tutorial's server on rostui core, under the side the test names (real or shim); this process knows
    actionlib_tutorials' types."""
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(TUTORIALS))
    yield from fibonacci_server(str(request.param), ros_env, tutorials_python, tmp_path / "server.log")


def log_text(app: ActionApp) -> str:
    """What the goal log shows."""
    return "\n".join(app.query_one("#progress", Log).lines)


@pytest.mark.parametrize("fibonacci", ["real"], indirect=True)
def test_a_goal_to_its_result_and_one_cancelled(fibonacci: dict[str, str]) -> None:
    app = ActionApp(master_uri=fibonacci["ROS_MASTER_URI"], period=0.3)

    async def main() -> None:
        async with app.run_test(size=(100, 30)) as pilot:
            await asyncio.wait_for(app.started.wait(), DEADLINE)
            await until(lambda: app.selected == "/fibonacci", "the server selected", timeout=DEADLINE)
            assert app.query_one(NameList).names == ["/fibonacci"]
            editor = app.query_one("#goal", TextArea)
            assert editor.text == "order: 0\n"
            assert app.notice("master").text.endswith(" · ctrl+s sends a goal to /fibonacci")
            await pilot.press("enter")  # on the action: to its goal
            assert editor.has_focus
            editor.load_text("order: 3\n")
            await pilot.press("ctrl+s")
            # the status topic can say SUCCEEDED before the result topic delivers the result: wait for the goal's end
            await until(lambda: not app.running and app.notice("goal").text == "goal SUCCEEDED", "the result",
                        timeout=DEADLINE)
            text = log_text(app)
            assert "status: ACTIVE" in text and "feedback:\n  sequence: [0, 1, 1, 2]" in text, text
            assert text.endswith("result:\n  sequence: [0, 1, 1, 2]"), text
            editor.load_text("order: 30\n")
            await pilot.press("ctrl+s")
            await until(lambda: app.notice("goal").text == "goal ACTIVE", "the second goal running", timeout=DEADLINE)
            await pilot.press("ctrl+s")
            assert app.notice("goal").text == "a goal is running: ctrl+x cancels it first"
            await pilot.press("ctrl+x")
            await until(lambda: not app.running and app.notice("goal").text == "goal PREEMPTED", "the goal cancelled",
                        timeout=DEADLINE)
            await pilot.press("ctrl+x")
            assert app.notice("goal").text == "no goal is running"
            await pilot.press("ctrl+q")
    asyncio.run(main())
    assert app.return_code in (0, None)


@pytest.mark.parametrize("fibonacci", ["shim"], indirect=True)
def test_a_goal_that_does_not_fit_is_one_line(fibonacci: dict[str, str]) -> None:
    app = ActionApp(master_uri=fibonacci["ROS_MASTER_URI"], period=0.3)

    async def main() -> None:
        async with app.run_test(size=(100, 30)) as pilot:
            await until(lambda: app.selected == "/fibonacci", "the server selected", timeout=DEADLINE)
            app.query_one("#goal", TextArea).load_text("order: [\n")
            await pilot.press("ctrl+s")
            await until(lambda: app.notice("goal").kind == "error", "the error", timeout=DEADLINE)
            assert app.notice("goal").text.startswith("YAML error: message:2:1: ")
            assert "\n" not in app.notice("goal").text and log_text(app) == ""
            await pilot.press("ctrl+q")
    asyncio.run(main())
