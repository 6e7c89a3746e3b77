"""SVG snapshots of `rostui publish` and `rostui call` (stored in snapshots/test_form_snapshots/): a Twist form
with an edited field, an expression and a moved slider at 80x24 and 100x40, and a SetBool call answered by
Debian's rospy server at 80x24. The master line shows the default URI instead of the test's free port.
Regenerate with ``pytest tests/test_form_snapshots.py --snapshot-update`` and look at the SVGs before committing.
"""

from __future__ import annotations

from typing import Any, Iterator

import pytest
from textual.pilot import Pilot

from rostui.apps.form.app import FormApp

from conftest import until
from interop_helpers import peers, rospy_peer
from test_form_app import edit, env, master  # noqa: F401  (fixtures)
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)


class StillApp(FormApp):
    """The real app, naming the master by the default URI."""

    def master_label(self) -> str:
        """The default master URI."""
        return "http://localhost:11311/"


@pytest.mark.parametrize("size", [(80, 24), (100, 40)], ids=["80x24", "100x40"])
def test_a_twist_form(snap_compare: Any, env: dict[str, str], size: tuple[int, int]) -> None:
    """linear.x typed, angular.z an expression, linear.y's slider moved; the detail line under the cursor."""
    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, FormApp)
        await until(app.ready.is_set, "the form")
        await edit(pilot, app, "linear.x", "0.5")
        await edit(pilot, app, "angular.z", "0.8 * sin(t)")
        app.table.move_cursor(row=1)
        await pilot.press("right", "right", "right", "right", "right")
        await pilot.pause()

    assert snap_compare(StillApp("publish", name="/turtle1/cmd_vel", type_name="geometry_msgs/Twist", rate=10),
                        run_before=run_before, terminal_size=size)


@pytest.fixture
def server(env: dict[str, str]) -> Iterator[None]:
    """Debian's rospy SetBool server on /snap_flag."""
    with peers(env) as spawn:
        spawn(rospy_peer("rospy_setbool_server.py", "/snap_flag"), label="server").wait_for("ready")
        yield


def test_a_call_answered(snap_compare: Any, env: dict[str, str], server: None) -> None:
    """/snap_flag's request set to True, called, and rospy's response in the Response panel."""
    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, FormApp)
        await until(lambda: app.form is not None, "the request's form", 60)
        await edit(pilot, app, "data", "True")
        await pilot.press("ctrl+s")
        await until(lambda: "answered" in app.query_one("#status").text, "the response", 60)  # type: ignore
        await pilot.pause()

    assert snap_compare(StillApp("call", name="/snap_flag"), run_before=run_before, terminal_size=(80, 24))
