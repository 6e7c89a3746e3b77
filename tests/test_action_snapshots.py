"""SVG snapshots of `rostui action` (stored in snapshots/test_action_snapshots/), at 80x24 and 100x40: the Fibonacci
tutorial's server under Debian's actionlib listed and selected, its goal template in the editor, before anything is
sent. The master line shows the default URI instead of the test's free port. Regenerate with ``pytest
tests/test_action_snapshots.py --snapshot-update`` and look at the SVGs before committing them.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterator

import pytest
from textual.pilot import Pilot

from rostui.apps.action.app import ActionApp

from action_helpers import fibonacci_server
from conftest import until
from test_actionlib_scripts import TUTORIALS, tutorials_python  # noqa: F401  (fixture)
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)


class StillApp(ActionApp):
    """The real app, naming the master by the default URI."""

    def master_label(self) -> str:
        """The default master URI."""
        return "http://localhost:11311/"


@pytest.fixture
def server(rostui_core: Any, ros_env: dict[str, str], tutorials_python: Path, tmp_path: Path,
           monkeypatch: pytest.MonkeyPatch) -> Iterator[dict[str, str]]:
    """Debian's side of the tutorial's server on rostui core."""
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(TUTORIALS))
    yield from fibonacci_server("real", ros_env, tutorials_python, tmp_path / "server.log")


@pytest.mark.parametrize("size", [(80, 24), (100, 40)], ids=["80x24", "100x40"])
def test_the_server_and_its_goal(snap_compare: Any, server: dict[str, str], size: tuple[int, int]) -> None:
    """/fibonacci listed and selected, its type in the goal panel's title, the goal's defaults to edit."""
    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, ActionApp)
        await until(lambda: app.selected == "/fibonacci", "the server selected", timeout=60)
        await pilot.pause()

    assert snap_compare(StillApp(master_uri=server["ROS_MASTER_URI"], period=0.3), run_before=run_before,
                        terminal_size=size)
