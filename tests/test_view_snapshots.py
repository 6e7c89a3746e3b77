"""SVG snapshots of `rostui view` (stored in snapshots/test_view_snapshots/).

The app runs for real against a `rostui core` master; the cameras are the
pattern script run by rostui's client, each publishing one latched message
with a zero stamp, so the figures line ("1 frame", no latency) is the same on
every machine.  Drawn with half blocks.  Regenerate with
``pytest tests/test_view_snapshots.py --snapshot-update`` and look at the
SVGs (as PNG) before committing them.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterator

import pytest
from textual.pilot import Pilot

from rostui.apps.view.app import ViewApp
from rostui.apps.view.image_view import GRAPHICS_ENV, ImageView

from conftest import stop_process, until
from textual_snapshots import snapshot  # noqa: F401  (stores SVGs in snapshots/)
from view_helpers import start_camera


@pytest.fixture(autouse=True)
def terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """The same colour system on every machine, half blocks."""
    monkeypatch.setenv("COLORTERM", "truecolor")
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.setenv(GRAPHICS_ENV, "halfblock")


@pytest.fixture
def cameras(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> Iterator[None]:
    """/camera/image_raw (the pattern, rgb8) and /camera/depth (a ramp, 32FC1), latched."""
    procs = [start_camera(ros_env, tmp_path, "/camera/image_raw", "rgb8", rate=0),
             start_camera(ros_env, tmp_path, "/camera/depth", "32FC1", rate=0)]
    yield
    for proc in procs:
        stop_process(proc)


async def all_drawn(pilot: Pilot) -> None:
    """Wait until every panel's view has drawn its latched image and the layout has settled."""
    app = pilot.app
    assert isinstance(app, ViewApp)

    def drawn() -> bool:
        return all(isinstance(p.view, ImageView) and p.view.drawn.count >= 1 and not p.note.display
                   and p.view.drawn_for == p.view.area() for p in app.grid.panels)
    await until(drawn, "every image drawn")
    await pilot.pause(0.3)


def test_one_camera_80x24(snap_compare: Any, cameras: None) -> None:
    """`rostui view /camera/image_raw` in 80x24: the pattern as large as fits, aspect kept."""
    assert snap_compare(ViewApp(["/camera/image_raw"]), run_before=all_drawn, terminal_size=(80, 24))


def test_camera_and_depth_100x40(snap_compare: Any, cameras: None) -> None:
    """`rostui view /camera/image_raw /camera/depth` in 100x40: the pattern beside the coloured depth ramp."""
    assert snap_compare(ViewApp(["/camera/image_raw", "/camera/depth"]), run_before=all_drawn,
                        terminal_size=(100, 40))
