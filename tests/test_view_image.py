"""`rostui view` on images: decoding every encoding, and the test pattern drawn right by the real app.

The decoding tests need no terminal.  The app tests run ViewApp headless (the
run_test pilot) against a `rostui core` master, with the pattern camera as a
real process (Debian's rospy, and rostui's client running the same script),
and read the colours of drawn cells: half blocks, as every terminal shows them.
"""

from __future__ import annotations

import asyncio
import subprocess
import xmlrpc.client
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image as PILImage

from rostui.apps.view.app import ViewApp
from rostui.apps.view.halfblock import HalfBlock
from rostui.apps.view.image_view import GRAPHICS_ENV, ON_LOOP_PIXELS, ImageView
from rostui.apps.view.registry import UnknownViewError, view_class, viewable_types
from rostui.core.msg import get_message_class
from rostui.models.sensors.images import ImageDecodeError, colour_map, decode_image, fit, raw_pixels_read

from conftest import have_rospy, need_peer, start_rostui_core, stop_process, until
from view_helpers import (
    BLUE, COMPRESSED, GREEN, HEIGHT, RAW, RED, SAMPLES, WHITE, WIDTH, YELLOW, close, compressed_file, grey, pattern,
    pixel_at, start_camera,
)

Image = get_message_class("sensor_msgs/Image")
CompressedImage = get_message_class("sensor_msgs/CompressedImage")
#: Colour error allowed: the drawing keeps 16 levels a channel (steps of 17), jpeg adds its own.
TOLERANCE = {"jpeg": 40}
DEFAULT_TOLERANCE = 9


@pytest.fixture(autouse=True)
def halfblock(monkeypatch: pytest.MonkeyPatch) -> None:
    """Half blocks, as on a terminal without graphics (the pilot has none to ask)."""
    monkeypatch.setenv(GRAPHICS_ENV, "halfblock")


def raw_message(encoding: str, rgb: np.ndarray) -> Any:
    """``rgb`` as a sensor_msgs/Image of ``encoding`` (rgb8, bgr8, mono8)."""
    if encoding == "bgr8":
        data = rgb[..., ::-1]
    elif encoding == "mono8":
        data = (0.299 * rgb[..., 0] + 0.587 * rgb[..., 1] + 0.114 * rgb[..., 2]).round().astype(np.uint8)
    else:
        data = rgb
    channels = 1 if encoding == "mono8" else 3
    return Image(height=rgb.shape[0], width=rgb.shape[1], encoding=encoding, is_bigendian=0,
                 step=rgb.shape[1] * channels, data=np.ascontiguousarray(data).tobytes())


# -- decoding (no terminal) ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("encoding", ["rgb8", "bgr8", "mono8"])
def test_raw_pattern_decodes_with_its_colours(encoding: str) -> None:
    picture = decode_image(raw_message(encoding, pattern()), (WIDTH, HEIGHT))
    assert picture.rgb.shape == (HEIGHT, WIDTH, 3) and (picture.width, picture.height) == (WIDTH, HEIGHT)
    for fx, fy, colour in SAMPLES:
        want = grey(colour) if encoding == "mono8" else colour
        assert tuple(picture.rgb[int(fy * HEIGHT), int(fx * WIDTH)]) == want, (fx, fy)


def test_padded_rows_big_endian_and_shrinking() -> None:
    rgb = pattern()
    padded = np.zeros((HEIGHT, WIDTH * 3 + 5), dtype=np.uint8)
    padded[:, : WIDTH * 3] = rgb.reshape(HEIGHT, -1)
    msg = Image(height=HEIGHT, width=WIDTH, encoding="rgb8", step=WIDTH * 3 + 5, data=padded.tobytes())
    picture = decode_image(msg, (16, 100))
    assert picture.rgb.shape == (12, 16, 3)  # aspect kept inside 16x100
    assert tuple(picture.rgb[9, 12]) == WHITE and tuple(picture.rgb[1, 0]) == RED
    mono16 = np.full((2, 2), 0x1234, dtype=">u2")
    big = decode_image(Image(height=2, width=2, encoding="mono16", is_bigendian=1, step=4, data=mono16.tobytes()))
    assert tuple(big.rgb[0, 0]) == (0x12, 0x12, 0x12)


def test_depth_colour_map() -> None:
    values = np.array([[0.0, 1.0, 2.0, np.nan, 3.0]], dtype=np.float32)
    rgb, span = colour_map(values)
    assert span == (1.0, 3.0)
    assert tuple(rgb[0, 0]) == (0, 0, 0) and tuple(rgb[0, 3]) == (0, 0, 0)  # no reading: black
    assert rgb[0, 1, 2] > rgb[0, 1, 0] and rgb[0, 4, 0] > rgb[0, 4, 2]  # near blue, far red
    depth = np.array([[0, 500, 4500]], dtype="<u2")
    picture = decode_image(Image(height=1, width=3, encoding="16UC1", step=6, data=depth.tobytes()))
    assert picture.depth_range == (0.5, 4.5)


@pytest.mark.parametrize("fmt", COMPRESSED)
def test_compressed_pattern_decodes(tmp_path: Path, fmt: str) -> None:
    data = compressed_file(tmp_path, fmt).read_bytes()
    picture = decode_image(CompressedImage(format=fmt, data=data), (WIDTH, HEIGHT))
    for fx, fy, colour in SAMPLES:
        assert close(tuple(picture.rgb[int(fy * HEIGHT), int(fx * WIDTH)]), colour, TOLERANCE.get(fmt, 0)), (fx, fy)


@pytest.mark.parametrize("msg, says", [
    (Image(height=2, width=2, encoding="yuv422", step=4, data=b"\0" * 8), "encoding 'yuv422' is not shown"),
    (Image(height=4, width=4, encoding="rgb8", step=12, data=b"\0" * 20), "20 bytes of data for 4 rows of 12 bytes"),
    (Image(height=4, width=4, encoding="rgb8", step=3, data=b"\0" * 48), "step 3 is less than a row"),
    (Image(height=0, width=4, encoding="rgb8", step=12, data=b""), "0 pixels"),
    (CompressedImage(format="jpeg", data=b"not a jpeg"), "jpeg data cannot be decoded"),
    (CompressedImage(format="16UC1; compressedDepth png", data=b""), "is not shown"),
])
def test_bad_images_say_why_in_one_line(msg: Any, says: str) -> None:
    with pytest.raises(ImageDecodeError) as err:
        decode_image(msg)
    assert says in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("width, height, box, step", [
    (64, 48, (64, 48), 1), (640, 480, (100, 76), 3), (1920, 1080, (156, 70), 7), (4096, 3072, (1000, 600), 2),
])
def test_raw_pixels_read_counts_the_strided_read(width: int, height: int, box: tuple[int, int], step: int) -> None:
    """What a raw frame costs to draw grows with the pixels the strided read touches, not the frame's size."""
    msg = Image(height=height, width=width, encoding="mono8", step=width, data=bytes(width * height))
    picture = decode_image(msg, box)  # no error: the figure is of a frame that decodes
    assert picture.rgb.shape[:2] == fit(width, height, *box)[::-1]
    assert raw_pixels_read(msg, box) == -(-width // step) * -(-height // step)
    assert raw_pixels_read(CompressedImage(format="png", data=b""), box) is None


def test_small_raw_frames_are_drawn_on_the_loop_the_rest_on_a_thread(tmp_path: Path) -> None:
    """A small raw frame skips the trip to a worker thread (a busy machine makes the trip long enough for the
    next camera frame to replace the waiting one); a compressed one, or a raw one that takes long, takes it."""
    async def main() -> None:
        view = ImageView("/camera", kind="kitty")  # a picture of the panel's pixels, not of its half cells
        app = ViewApp([])
        async with app.run_test(size=(100, 40)) as pilot:
            await app.screen.mount(view)
            await pilot.pause()
            assert view.laid_out()
            assert view.off_loop(raw_message("rgb8", pattern()), 0.0) is None
            big = Image(height=4000, width=4000, encoding="mono8", step=4000, data=bytes(4000 * 4000))
            assert raw_pixels_read(big, view._layout(big).box) > ON_LOOP_PIXELS  # noqa: SLF001
            for msg in (big, CompressedImage(format="png", data=compressed_file(tmp_path, "png").read_bytes())):
                job = view.off_loop(msg, 0.0)
                assert job is not None and job().msg is msg

    asyncio.run(main())


def test_fit_keeps_aspect() -> None:
    assert fit(640, 480, 100, 80) == (100, 75)
    assert fit(640, 480, 200, 60) == (80, 60)


def test_registry() -> None:
    assert view_class("sensor_msgs/Image") is ImageView
    assert view_class("sensor_msgs/CompressedImage") is ImageView
    assert {"sensor_msgs/Image", "sensor_msgs/CompressedImage"} <= set(viewable_types())
    with pytest.raises(UnknownViewError, match="no view shows std_msgs/String; rostui view shows .*sensor_msgs/Image"):
        view_class("std_msgs/String")


# -- the app, with real publishers ------------------------------------------------------------------------------
def pixels_of(app: ViewApp, index: int = 0) -> HalfBlock:
    """The picture widget of the ``index``-th panel."""
    view = app.grid.panels[index].view
    assert isinstance(view, ImageView) and isinstance(view.pixels, HalfBlock)
    return view.pixels


def expected(encoding: str, colour: tuple[int, int, int]) -> tuple[int, int, int]:
    """What the pattern camera's ``encoding`` makes of ``colour``."""
    return grey(colour) if encoding in ("mono8", "mono16") else colour


def run_view(topics: list[str], check: Any, size: tuple[int, int] = (100, 40)) -> None:
    """Run ViewApp on ``topics``; ``await check(app, pilot)``."""
    async def main() -> None:
        app = ViewApp(topics)
        async with app.run_test(size=size) as pilot:
            await check(app, pilot)

    asyncio.run(main())


PEERS = ["rostui", "rospy"]


@pytest.mark.parametrize("peer", PEERS)
@pytest.mark.parametrize("encoding", [e for e in RAW if e not in ("16UC1", "32FC1")] + list(COMPRESSED))
def test_pattern_drawn_in_the_right_places(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path,
                                                 encoding: str, peer: str) -> None:
    if peer == "rospy":
        need_peer(have_rospy(), "rospy (Debian python3-rospy)")
    camera = start_camera(ros_env, tmp_path, "/camera/image_raw", encoding, peer=peer)
    try:
        async def check(app: ViewApp, pilot: Any) -> None:
            await until(lambda: app.grid.panels[0].view is not None
                        and app.grid.panels[0].view.drawn.count >= 2, f"{encoding} frames drawn", timeout=60)
            await pilot.pause()
            pixels = pixels_of(app)
            # 64x48 as large as the 100x40 screen's panel allows (two pixels a cell), aspect kept
            await until(lambda: (pixels.size.width, pixels.size.height) == (93, 35),
                        f"the picture at 93x35 cells (it is {pixels.size.width}x{pixels.size.height})")
            assert abs(pixels.size.width / (2 * pixels.size.height) - WIDTH / HEIGHT) < 0.03
            for fx, fy, colour in SAMPLES:
                got = pixel_at(pixels, fx, fy)
                assert close(got, expected(encoding, colour), TOLERANCE.get(encoding, DEFAULT_TOLERANCE)), \
                    f"{encoding} at ({fx}, {fy}): {got}, not {expected(encoding, colour)}"
            view = app.grid.panels[0].view
            await until(lambda: "fps" in str(view.info.render()), "the frame rate shown")
            info = str(view.info.render())
            assert f"64x48 {encoding}" in info and "drawn" in info and "latency" in info, info

        run_view(["/camera/image_raw"], check)
    finally:
        stop_process(camera)


@pytest.mark.parametrize("peer", PEERS)
@pytest.mark.parametrize("encoding", ["16UC1", "32FC1"])
def test_depth_drawn_with_the_colour_map(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path,
                                               encoding: str, peer: str) -> None:
    if peer == "rospy":
        need_peer(have_rospy(), "rospy (Debian python3-rospy)")
    camera = start_camera(ros_env, tmp_path, "/camera/depth", encoding, peer=peer)
    try:
        async def check(app: ViewApp, pilot: Any) -> None:
            await until(lambda: isinstance(app.grid.panels[0].view, ImageView)
                        and app.grid.panels[0].view.drawn.count >= 1
                        and app.grid.panels[0].view.drawn_for == app.grid.panels[0].view.area(),
                        f"{encoding} drawn at the panel's size", timeout=60)
            await pilot.pause()
            pixels = pixels_of(app)
            assert pixel_at(pixels, 0.03, 0.5) == (0, 0, 0)  # no reading: black
            near, far = pixel_at(pixels, 0.2, 0.5), pixel_at(pixels, 0.97, 0.5)
            assert near[2] > near[0] + 100 and far[0] > far[2] + 100, (near, far)
            info = str(app.grid.panels[0].view.info.render())
            assert "depth 0.50–4.50 m" in info, info

        run_view(["/camera/depth"], check)
    finally:
        stop_process(camera)


def subscribers(env: dict[str, str], topic: str) -> list[str]:
    """The nodes the master lists as subscribers of ``topic``."""
    _, _, (_, subs, _) = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/view_test")
    return next((nodes for name, nodes in subs if name == topic), [])


def test_unknown_type_says_what_can_be_shown_and_subscribes_only_while_running(
        rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    camera = start_camera(ros_env, tmp_path, "/camera/image_raw", "rgb8")
    try:
        async def check(app: ViewApp, pilot: Any) -> None:
            image, log = app.grid.panels
            await until(lambda: image.view is not None and image.view.drawn.count >= 1, "an image drawn")
            await until(lambda: log.problem != "", "the /rosout panel's line")
            assert str(log.note.render()) == ("/rosout: no view shows rosgraph_msgs/Log; rostui view shows "
                                              "sensor_msgs/CompressedImage, sensor_msgs/Image") \
                or str(log.note.render()).startswith("/rosout: no view shows rosgraph_msgs/Log; rostui view shows ")
            assert any(n.startswith("/rostui_view") for n in subscribers(ros_env, "/camera/image_raw"))
            assert not any(n.startswith("/rostui_view") for n in subscribers(ros_env, "/rosout"))
            await pilot.press("q")

        run_view(["/camera/image_raw", "/rosout"], check)
        assert not any(n.startswith("/rostui_view") for n in subscribers(ros_env, "/camera/image_raw"))
    finally:
        stop_process(camera)


def test_waits_for_a_topic_nobody_publishes(rostui_core: Any, ros_env: dict[str, str]) -> None:
    async def check(app: ViewApp, pilot: Any) -> None:
        await until(lambda: "● master" in str(app.query_one("#status").render()), "connected")
        await pilot.pause(0.6)
        assert str(app.grid.panels[0].note.render()) == "waiting for /nothing/here to be published"

    run_view(["/nothing/here"], check)


def test_frames_are_dropped_not_queued() -> None:
    from rostui.apps.view.feed import TopicFeed
    from rostui.core.node import AnyMsg

    arrivals: list[int] = []
    feed = TopicFeed("/camera/image_raw", lambda: arrivals.append(1), clock=iter(range(100)).__next__)
    for i in range(5):
        feed._on_message(AnyMsg(bytes([i])))
    taken = feed.take()
    assert taken is not None and taken[0]._buff == bytes([4]) and feed.take() is None
    assert len(arrivals) == 5 and feed.received.count == 5


def test_no_master_says_so_and_waits(ros_env: dict[str, str]) -> None:
    async def check(app: ViewApp, pilot: Any) -> None:
        status = app.query_one("#status")
        await until(lambda: "waiting for master" in str(status.render()), "the no-master line")
        assert "start one with `rostui core` (retrying)" in str(status.render())
        assert str(app.grid.panels[0].note.render()) == "waiting for /camera/image_raw to be published"

    run_view(["/camera/image_raw"], check)


def test_master_restart_subscribes_again(ros_env: dict[str, str], tmp_path: Path) -> None:
    """The master goes: the top line says so, the picture stays; a new master: the camera is drawn again."""
    core = start_rostui_core(ros_env)
    camera = start_camera(ros_env, tmp_path, "/camera/image_raw", "rgb8")

    async def check(app: ViewApp, pilot: Any) -> None:
        nonlocal core
        panel = app.grid.panels[0]
        await until(lambda: panel.view is not None and panel.view.drawn.count >= 2, "the first master's frames")
        stop_process(core)
        status = app.query_one("#status")
        await until(lambda: "gone: waiting for it to come back" in str(status.render()), "the lost master")
        assert isinstance(panel.view, ImageView) and panel.view.picture is not None
        core = start_rostui_core(ros_env)
        await until(lambda: "● master" in str(status.render()), "the new master")
        drawn = panel.view.drawn.count
        await until(lambda: panel.view is not None and panel.view.drawn.count > drawn + 2,
                    "frames through the new master")

    try:
        run_view(["/camera/image_raw"], check)
    finally:
        stop_process(camera)
        stop_process(core)
