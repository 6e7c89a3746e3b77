"""`rostui view` against sensor messages that amplify when decoded, beside a 10 Hz camera that must keep being drawn.

The bombs (sensor_bombs.py): a PointCloud2 of 5,000,000 rows of one point (10 MB on the wire), a LaserScan of
10,000,000 ranges (40 MB) and a CompressedImage of a 1-bit 13000 x 13000 PNG (25 kB).  Each is published by a
rostui client process; `rostui view` runs headless under the run_test pilot in this process, its memory sampled,
with the test-pattern camera (tests/view/image_pattern_pub.py) at 10 Hz in a panel beside them.  Before the fix
the view took the cloud to 1 GB and froze (never drawn), the scan to 1.4 GB and the PNG to 910 MB, and one heavy
topic held every other panel back (each panel was charged the whole process's CPU).

What a user sees is asserted: the bombs' panels drawn (a strided cloud and scan) or saying in one line why not
(the PNG), the camera still drawn frame after frame, memory bounded.  No duration is asserted.
"""

from __future__ import annotations

import asyncio
import io
import os
import tracemalloc
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from PIL import Image as PILImage

from hostile_helpers import MB, RssSampler, record
from interop_helpers import Spawn, spawn  # noqa: F401  (fixture)
from rostui.apps.view.app import ViewApp
from rostui.apps.view.image_view import GRAPHICS_ENV, ImageView
from rostui.apps.view.panel import ViewPanel, decode_for_view
from rostui.apps.view.topdown_view import TopDownView
from rostui.core.msg import md5sum
from rostui.core.node import AnyMsg
from rostui.models.sensors.cloud2d import cloud_points
from rostui.models.sensors.images import ImageDecodeError, decode_image
from rostui.models.sensors.pose2d import MAX_POINTS
from rostui.models.sensors.scan2d import scan_points
from rostui.models.sensors.scene2d import drawing_of
from sensor_bombs import BOMBS, publish_raw

from conftest import stop_process, until
from view_helpers import start_camera

#: Most the view's memory may grow while the bombs arrive (the 40 MB scan is held a few times on its way in).
GROWTH_LIMIT_MB = 250
#: Bombs each topic sends before the figures are taken.
BOMBS_SEEN = 3


@pytest.fixture(autouse=True)
def halfblock(monkeypatch: pytest.MonkeyPatch) -> None:
    """Half blocks, as on a terminal without graphics (the pilot has none to ask)."""
    monkeypatch.setenv(GRAPHICS_ENV, "halfblock")


def received(name: str) -> AnyMsg:
    """Bomb ``name`` as the view's node receives it: raw bytes and the publisher's connection header."""
    type_name, build = BOMBS[name]
    raw = AnyMsg(build())
    raw._connection_header = {"type": type_name, "md5sum": md5sum(type_name), "callerid": "/bomber"}
    return raw


@pytest.mark.parametrize("name", list(BOMBS))
def test_a_bomb_read_for_a_panel_stays_small(name: str) -> None:
    """In process, what a panel does with one bomb (decode, then the geometry or the picture), memory traced."""
    raw = received(name)
    tracemalloc.start()
    try:
        msg = decode_for_view(raw)
        if name == "png":
            with pytest.raises(ImageDecodeError, match="png of 13000x13000 pixels not drawn"):
                decode_image(msg, (320, 160))
            points = 0
        else:
            points = len(drawing_of(msg).points)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    record(f"view_model_{name}", "rostui view (in process)", message_mb=round(len(raw._buff) / MB, 1),
           peak_traced_mb=round(peak / MB, 1), points=points)
    assert peak < 16 * MB, f"{name}: {peak / MB:.0f} MB traced"
    if name != "png":
        assert 0 < points <= MAX_POINTS


def test_strided_reads_keep_evenly_spread_points() -> None:
    """A cloud with padded rows and a scan, each four times what is drawn: every fourth point, read in place."""
    width, height, step, row_step = 100, 40, 12, 1300  # 100 bytes of padding after each row
    data = np.zeros((height, row_step), dtype=np.uint8)
    xy = np.arange(width * height, dtype="<f4").reshape(height, width)
    for col in range(width):
        data[:, col * step:col * step + 4] = xy[:, col:col + 1].view(np.uint8)
        data[:, col * step + 4:col * step + 8] = (-xy[:, col:col + 1]).view(np.uint8)
    cloud = SimpleNamespace(width=width, height=height, point_step=step, row_step=row_step, is_bigendian=False,
                            data=data.tobytes(), fields=[SimpleNamespace(name="x", offset=0, datatype=7),
                                                         SimpleNamespace(name="y", offset=4, datatype=7)])
    points = cloud_points(cloud, max_points=1000)
    assert np.array_equal(points[:, 0], np.arange(0, 4000, 4)) and np.array_equal(points[:, 1], -points[:, 0])
    scan = SimpleNamespace(ranges=np.full(4000, 2.0, dtype="<f4"), angle_min=0.0, angle_increment=np.pi / 2000,
                           range_min=0.1, range_max=30.0)
    ring = scan_points(scan, max_points=1000)
    assert len(ring) == 1000 and np.allclose(np.hypot(ring[:, 0], ring[:, 1]), 2.0)
    assert np.allclose(ring[1], (2 * np.cos(np.pi / 500), 2 * np.sin(np.pi / 500)))  # beam 4, not beam 1


def panel_of(app: ViewApp, topic: str) -> ViewPanel:
    """The panel of ``topic``."""
    return next(p for p in app.grid.panels if p.topic == topic)


def test_bombs_are_drawn_within_bounds_and_the_camera_beside_them_keeps_going(
        rostui_core: Any, ros_env: dict[str, str], tmp_path: Path, spawn: Spawn) -> None:  # noqa: F811
    camera = start_camera(ros_env, tmp_path, "/camera", "rgb8", rate=10.0)
    try:
        for name, (type_name, build) in BOMBS.items():
            publish_raw(spawn, tmp_path, f"/{name}", type_name, build(), hz=2.0)
        topics = ["/camera", *(f"/{name}" for name in BOMBS)]

        async def main() -> None:
            app = ViewApp(topics)
            async with app.run_test(size=(160, 40)):
                camera_panel = panel_of(app, "/camera")
                await until(lambda: isinstance(camera_panel.view, ImageView) and camera_panel.view.drawn.count >= 2,
                            "the camera drawn", timeout=60)
                view = camera_panel.view
                assert isinstance(view, ImageView)
                with RssSampler(os.getpid()) as rss:
                    await until(lambda: all(panel_of(app, f"/{n}").feed.received.count >= BOMBS_SEEN for n in BOMBS),
                                lambda: "bombs received: " + ", ".join(
                                    f"{n} {panel_of(app, f'/{n}').feed.received.count}" for n in BOMBS), timeout=60)
                    drawn = view.drawn.count
                    await until(lambda: view.drawn.count >= drawn + 10, "the camera drawn again, ten times", timeout=60)
                record("view_bombs", "rostui view", peak_rss_growth_mb=round(rss.growth_mb, 1),
                       camera_received=view.received.count, camera_drawn=view.drawn.count)

                png = panel_of(app, "/png").view
                assert isinstance(png, ImageView)
                await until(lambda: "13000x13000" in png.error, "the PNG's one line")
                assert "not drawn" in png.error and "\n" not in png.error
                topdown = panel_of(app, "/cloud").view
                assert isinstance(topdown, TopDownView) and panel_of(app, "/scan").view is topdown
                for name in ("cloud", "scan"):
                    drawing = topdown.scene.drawing(f"/{name}")
                    assert drawing is not None and topdown.scene.note(f"/{name}") == ""
                    assert 0 < len(drawing.points) <= MAX_POINTS  # strided to what a panel can show
                assert rss.growth_mb < GROWTH_LIMIT_MB, f"the view grew {rss.growth_mb:.0f} MB"

        asyncio.run(main())
    finally:
        stop_process(camera)


def heavy_png(side: int = 4096) -> bytes:
    """A legitimate but costly frame: a smooth RGB PNG of ``side`` x ``side`` (about 60 ms to decode here)."""
    ramp = np.linspace(0, 255, side, dtype=np.float32)
    grey = (np.add.outer(ramp, ramp) / 2).astype(np.uint8)
    out = io.BytesIO()
    PILImage.fromarray(np.stack([grey, grey[::-1], grey.T], axis=2), "RGB").save(out, "PNG", compress_level=1)
    return out.getvalue()


def test_a_heavy_topic_drops_its_own_frames_not_its_neighbours(
        rostui_core: Any, ros_env: dict[str, str], tmp_path: Path, spawn: Spawn) -> None:  # noqa: F811
    """A 4096 x 4096 PNG at 10 Hz wants more than the panel's share of a core: it is drawn less often, the camera
    beside it as often as it comes (before, both panels were charged the whole process's CPU and held back alike)."""
    from sensor_bombs import _header, _string

    data = heavy_png()
    message = _header("camera") + _string("png") + len(data).to_bytes(4, "little") + data
    camera = start_camera(ros_env, tmp_path, "/camera", "rgb8", rate=10.0)
    try:
        publish_raw(spawn, tmp_path, "/heavy", "sensor_msgs/CompressedImage", message, hz=10.0)

        async def main() -> None:
            app = ViewApp(["/camera", "/heavy"])
            async with app.run_test(size=(160, 40)):
                camera_panel, heavy_panel = panel_of(app, "/camera"), panel_of(app, "/heavy")
                await until(lambda: all(isinstance(p.view, ImageView) and p.view.drawn.count >= 2
                                        for p in (camera_panel, heavy_panel)), "both drawn", timeout=60)
                camera_feed, heavy_feed = camera_panel.feed, heavy_panel.feed
                start = (camera_feed.received.count, camera_feed.dropped, heavy_feed.received.count,
                         heavy_feed.dropped)
                await until(lambda: camera_feed.received.count >= start[0] + 30
                            and heavy_feed.received.count >= start[2] + 30, "thirty frames of each", timeout=60)
                camera_got = camera_feed.received.count - start[0]
                camera_dropped = camera_feed.dropped - start[1]
                heavy_got = heavy_feed.received.count - start[2]
                heavy_dropped = heavy_feed.dropped - start[3]
                record("view_heavy_neighbour", "rostui view", camera_received=camera_got,
                       camera_dropped=camera_dropped, heavy_received=heavy_got, heavy_dropped=heavy_dropped,
                       heavy_cpu_s=round(heavy_panel.budget.spent, 2), camera_cpu_s=round(camera_panel.budget.spent, 2))
                assert camera_dropped <= camera_got // 5, (
                    f"the camera lost {camera_dropped} of {camera_got} frames beside the heavy topic")

        asyncio.run(main())
    finally:
        stop_process(camera)
