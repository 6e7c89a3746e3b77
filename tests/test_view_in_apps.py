"""The views inside other apps: the monitor's Enter on an image topic, and the bag view's inspector.

The monitor runs headless against `rostui core` with the pattern camera
(rostui's client running tests/view/image_pattern_pub.py); the bag view
browses a bag holding the pattern as an image (no master needed).
"""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from textual.pilot import Pilot

from rostui.apps.bagview.app import BagViewApp
from rostui.apps.monitor.app import MonitorApp
from rostui.apps.view.app import ViewScreen
from rostui.apps.view.halfblock import HalfBlock
from rostui.apps.view.image_view import GRAPHICS_ENV, ImageView
from rostui.core.bag.files import open_writer
from rostui.core.bag.model import Connection
from rostui.core.msg import get_message_class

from bag_view_helpers import inspector_open
from conftest import stop_process, until
from monitor_helpers import run_monitor
from view_helpers import GREEN, HEIGHT, RED, WHITE, WIDTH, YELLOW, close, pattern, pixel_at, start_camera

Image = get_message_class("sensor_msgs/Image")
T0 = 1_700_000_000_000_000_000


@pytest.fixture(autouse=True)
def halfblock(monkeypatch: pytest.MonkeyPatch) -> None:
    """Half blocks, as on a terminal without graphics."""
    monkeypatch.setenv(GRAPHICS_ENV, "halfblock")


def test_monitor_enter_on_an_image_opens_its_view(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    camera = start_camera(ros_env, tmp_path, "/camera/image_raw", "rgb8")

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await until(lambda: app.topic_type("/camera/image_raw") == "sensor_msgs/Image", "the camera listed")
        await until(lambda: app.table.select_topic("/camera/image_raw"), "the camera's row")
        await pilot.press("enter")
        assert isinstance(app.screen, ViewScreen) and app.expanded == []
        panel = app.screen.grid.panels[0]
        await until(lambda: isinstance(panel.view, ImageView) and panel.view.drawn.count >= 1, "the image drawn")
        assert isinstance(panel.view, ImageView) and isinstance(panel.view.pixels, HalfBlock)
        await pilot.pause()
        assert close(pixel_at(panel.view.pixels, 0.75, 0.25), GREEN, 9)
        assert panel.feed.subscribed
        sort = app.sort_column
        await pilot.press("s")  # the table's keys wait under the view
        assert app.sort_column == sort and isinstance(app.screen, ViewScreen)
        await pilot.press("escape")
        await until(lambda: not isinstance(app.screen, ViewScreen), "back to the table")
        assert not panel.feed.subscribed
        # a topic without a view still expands into its message tree
        assert app.table.select_topic("/rosout")
        await pilot.press("enter")
        assert app.expanded == ["/rosout"] and not isinstance(app.screen, ViewScreen)

    try:
        run_monitor(MonitorApp(period=0.3), scenario, size=(120, 40))
    finally:
        stop_process(camera)


def image_bag(path: Path) -> Path:
    """A bag with /camera/image_raw: the pattern (rgb8), then the pattern upside down, 100 ms apart."""
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/camera/image_raw", "sensor_msgs/Image", Image._md5sum, Image._full_text,
                                     "/camera/image_raw"))
    for i, rgb in enumerate([pattern(), pattern()[::-1]]):
        msg = Image(height=HEIGHT, width=WIDTH, encoding="rgb8", step=WIDTH * 3,
                    data=np.ascontiguousarray(rgb).tobytes())
        msg.header.stamp.secs = T0 // 10**9
        writer.write(0, T0 + i * 100_000_000, msg.serialize())
    writer.close()
    return path


def test_bag_inspector_shows_the_image_under_the_cursor(tmp_path: Path) -> None:
    path = image_bag(tmp_path / "camera.mcap")

    async def main() -> None:
        app = BagViewApp([str(path)], publish=False)
        async with app.run_test(size=(100, 40)) as pilot:
            await inspector_open(app, pilot)
            await until(lambda: isinstance(app.inspector_view.view, ImageView)
                        and app.inspector_view.view.drawn.count >= 1, "the first image in the inspector")
            view = app.inspector_view.view
            assert isinstance(view, ImageView) and isinstance(view.pixels, HalfBlock)
            await pilot.pause()
            assert close(pixel_at(view.pixels, 0.25, 0.25), YELLOW, 9)
            assert close(pixel_at(view.pixels, 0.25, 0.75), (0, 0, 255), 9)
            assert "rgb8" in str(app.inspector_text.render())  # the text too, its arrays left out
            await pilot.press("end")  # the second message: upside down
            await until(lambda: view.drawn.count >= 2, "the second image")
            await pilot.pause()
            assert close(pixel_at(view.pixels, 0.25, 0.75), YELLOW, 9)
            assert close(pixel_at(view.pixels, 0.04, 0.95), RED, 9)
            assert close(pixel_at(view.pixels, 0.75, 0.25), WHITE, 9)
            await app.action_quit()

    asyncio.run(main())


def marker_bag(path: Path) -> Path:
    """Two MarkerArrays on /markers: every marker type, then a DELETEALL and one cube at (2, 2)."""
    from topdown_helpers import Marker, MarkerArray, every_marker_type, marker

    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/markers", "visualization_msgs/MarkerArray", MarkerArray._md5sum,
                                     MarkerArray._full_text, "/rostui_test"))
    writer.write(0, T0, every_marker_type().serialize())
    cleared = MarkerArray(markers=[Marker(action=Marker.DELETEALL), marker(Marker.CUBE, 2.0, 2.0, ident=99)])
    writer.write(0, T0 + 100_000_000, cleared.serialize())
    writer.close()
    return path


def test_bag_inspector_shows_the_markers_of_the_message_under_the_cursor(tmp_path: Path) -> None:
    """Each recorded MarkerArray shows its own markers (the second's DELETEALL clears the first's, and stepping
    back shows the first's again), drawn where they belong; the tool keys are bag view's own there."""
    from rostui.apps.view.topdown_view import TopDownView

    path = marker_bag(tmp_path / "markers.bag")

    async def main() -> None:
        app = BagViewApp([str(path)], publish=False)
        async with app.run_test(size=(100, 40)) as pilot:
            await inspector_open(app, pilot)
            await until(lambda: isinstance(app.inspector_view.view, TopDownView)
                        and (store := app.inspector_view.view.scene.markers("/markers")) is not None
                        and len(store) == 12, "the first message's twelve markers in the inspector")
            view = app.inspector_view.view
            assert isinstance(view, TopDownView) and view.one_message
            await pilot.pause(0.2)
            vp = view.viewport
            assert vp is not None
            arrow = vp.cell_of(-2.5, 2.0)
            assert arrow is not None and view.cell_topic(*arrow) == "/markers"
            await pilot.press("end")  # the second message: DELETEALL, then one cube
            await until(lambda: [key for key, _, _ in view.scene.markers("/markers").held()] == [("n", 99)],
                        "only the second message's cube")
            await pilot.pause(0.2)
            assert view.cell_topic(*arrow) != "/markers"
            await pilot.press("home")
            await until(lambda: len(view.scene.markers("/markers")) == 12, "the first message's markers again")
            await app.action_quit()

    asyncio.run(main())
