"""SVG snapshots of `rostui top` (stored in snapshots/test_top_snapshots/), at 80x24 and 100x40.

CPU and memory move from one measure to the next, so the app draws a fixed measure: the nodes of a robot as a live
run lists them (the test_top_* tests check those against real rospy and roscpp nodes), one of them elsewhere, one
whose getPid did not answer. Regenerate with ``pytest tests/test_top_snapshots.py --snapshot-update`` and look at
the SVGs before committing them.
"""

from __future__ import annotations

from typing import Any

import pytest
from textual.pilot import Pilot

from rostui.apps.top.app import TopApp
from rostui.apps.widgets.confirm import ConfirmScreen
from rostui.models.top import NodeRow
from rostui.tools.usage import ProcessSample

from conftest import until
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)

MASTER = "http://localhost:11311/"
ROWS = [
    NodeRow("/rosout", "http://robot:40001/", "robot", True, 4101, ProcessSample(0.8, 24_500_000, 6, 9, "rostui core")),
    NodeRow("/laser_driver", "http://robot:40002/", "robot", True, 4160,
            ProcessSample(23.5, 61_800_000, 12, 4, "/opt/robot/lib/laser_driver __name:=laser_driver")),
    NodeRow("/planner", "http://robot:40003/", "robot", True, 4188,
            ProcessSample(71.0, 412_300_000, 18, 7, "python3 /opt/robot/planner.py")),
    NodeRow("/camera", "http://robot:40004/", "robot", True, None, None, "no answer to getPid (TimeoutError)"),
    NodeRow("/base_controller", "http://base:41000/", "base", False, 912, None),
]


class StillApp(TopApp):
    """The real app drawing the fixed measure, naming the master by the default URI."""

    async def _measure(self) -> None:
        self.rows = list(ROWS)
        self.polls = 1
        self.started.set()
        self.redraw()

    def master_label(self) -> str:
        """The default master URI."""
        return MASTER


@pytest.mark.parametrize("size", [(80, 24), (100, 40)], ids=["80x24", "100x40"])
def test_the_nodes_by_cpu(snap_compare: Any, size: tuple[int, int]) -> None:
    """The busiest first; remote and unanswering nodes set apart; the planner under the cursor spelled out."""
    async def run_before(pilot: Pilot) -> None:
        await pilot.pause()
        await pilot.press("down")  # the table opens on the first row: the planner, then the laser driver
        await pilot.press("up")

    assert snap_compare(StillApp(master_uri=MASTER), run_before=run_before, terminal_size=size)


def test_the_stop_question(snap_compare: Any) -> None:
    """k on the laser driver: the question before any signal."""
    async def run_before(pilot: Pilot) -> None:
        await pilot.pause()
        await pilot.press("down", "k")
        await until(lambda: isinstance(pilot.app.screen, ConfirmScreen), "the question")
        await pilot.pause()

    assert snap_compare(StillApp(master_uri=MASTER), run_before=run_before, terminal_size=(80, 24))
