"""`rostui bag view`'s inspector on the sensor bombs of sensor_bombs.py, recorded in a bag beside a plain topic.

A bag holds one message of each bomb (a PointCloud2 of 5,000,000 one-point rows, a LaserScan of 10,000,000
ranges, a CompressedImage of a 1-bit 13000 x 13000 PNG) and a ``std_msgs/String`` on /d_chatter, written with
rostui's own writer into the test's directory.  Bag view runs under Textual's pilot in this process, memory
traced, and its cursor is moved onto each topic in turn.  Before the fix the inspector decoded each bomb with
the class built from the bag's definition (the scan became a list of ten million floats, once for the picture
and again for the text) and only strided the drawing.

What a user sees is asserted: each bomb's title line and text, its huge array shown by its first items and
its length, the PNG's view saying in one line why it is not drawn, the chatter's text after the bombs, and the
memory traced while all of it was shown.  A scan recorded with another version of LaserScan (its own definition:
``float32[] ranges`` only), which only a class built from that definition can read, is not decoded when it is
larger than the inspector decodes so: one line says why (before: 320 MB of floats).  No duration is asserted.
"""

from __future__ import annotations

import asyncio
import tracemalloc
from pathlib import Path

import pytest

from hostile_helpers import MB, record
from rostui.apps.view.image_view import GRAPHICS_ENV, ImageView
from rostui.core.bag.model import Connection
from rostui.core.bag.rosbag2_0 import BagWriter
from rostui.core.msg import definition_md5, get_message_class
from sensor_bombs import BOMBS, CLOUD_ROWS, PNG_SIDE, SCAN_RANGES

from bag_view_helpers import inspector_open
from conftest import until

#: Most memory traced while one message is inspected, the app's own included: the bag's reader holds the
#: 40 MB scan's chunk and its bytes (and the app the chunk read before), about 120 MB; decoded by the bag's
#: class the scan took 766 MB.
PEAK_LIMIT_MB = 150
T0 = 1_700_000_000_000_000_000
#: topic: (bomb name, what the inspector's text shows of its huge array).
TOPICS = {
    "/a_cloud": ("cloud", f"… ({2 * CLOUD_ROWS} items)"),
    "/b_png": ("png", 'data: "<array type: uint8, length: '),  # 25 kB: printed as ``rostopic echo --noarr``
    "/c_scan": ("scan", f"… ({SCAN_RANGES} items)"),
}


@pytest.fixture(autouse=True)
def halfblock(monkeypatch: pytest.MonkeyPatch) -> None:
    """Half blocks, as on a terminal without graphics (the pilot has none to ask)."""
    monkeypatch.setenv(GRAPHICS_ENV, "halfblock")


def bomb_bag(path: Path) -> Path:
    """The bag described above: one message on each bomb's topic and two on /d_chatter."""
    writer = BagWriter(str(path))
    for number, (topic, (name, _shown)) in enumerate(TOPICS.items()):
        type_name, build = BOMBS[name]
        cls = get_message_class(type_name)
        writer.add_connection(Connection(number, topic, type_name, cls._md5sum, cls._full_text))
        writer.write(number, T0, build())
    string = get_message_class("std_msgs/String")
    writer.add_connection(Connection(len(TOPICS), "/d_chatter", "std_msgs/String", string._md5sum,
                                     string._full_text))
    for i in range(2):
        writer.write(len(TOPICS), T0 + i * 100_000_000, string(data=f"hello {i}").serialize())
    writer.close()
    return path


def test_the_inspector_shows_each_bomb_within_bounds_and_the_chatter_after_them(tmp_path: Path) -> None:
    from rostui.apps.bagview.app import BagViewApp

    path = bomb_bag(tmp_path / "bombs.bag")
    peaks: dict[str, float] = {}

    def text() -> str:
        return str(app.inspector_text.render())

    async def main() -> None:
        tracemalloc.start()  # before the app: the inspector shows the first topic as soon as the bag is read
        try:
            async with app.run_test(size=(100, 40)) as pilot:
                await inspector_open(app, pilot)
                for number, (topic, (name, shown)) in enumerate(TOPICS.items()):
                    if number:
                        await pilot.press("down")
                    assert app.timeline.selected_topic == topic
                    await until(lambda: shown in text() and topic in str(app.inspector_title.render()),
                                lambda: f"the {name} bomb in the inspector, not {text()[:400]!r}")
                    await pilot.pause()
                    assert len(text()) < 20_000, f"{name}: {len(text())} characters of text"
                    view = app.inspector_view.view
                    assert view is not None, f"{name}: no picture"
                    if name == "png":
                        assert isinstance(view, ImageView)
                        await until(lambda: f"png of {PNG_SIDE}x{PNG_SIDE} pixels not drawn" in view.error,
                                    "the PNG's one line")
                    peaks[name] = tracemalloc.get_traced_memory()[1] / MB
                    tracemalloc.reset_peak()
                await pilot.press("down")
                assert app.timeline.selected_topic == "/d_chatter"
                await until(lambda: 'data: "hello 0"' in text(), "the chatter as text")
                assert app.inspector_view.view is None and not app.inspector_view.note.display
                await app.action_quit()
        finally:
            tracemalloc.stop()

    app = BagViewApp([str(path)], publish=False)
    asyncio.run(main())
    record("bag_inspector_bombs", "rostui bag view inspector (in process, traced)",
           bag_mb=round(path.stat().st_size / MB, 1), **{f"peak_{k}_mb": round(v, 1) for k, v in peaks.items()})
    for name, peak in peaks.items():
        assert peak < PEAK_LIMIT_MB, f"{name}: {peak:.0f} MB traced"


#: A sensor_msgs/LaserScan of another version: ranges only.
SCAN_OF_ANOTHER_VERSION = "float32[] ranges\n"


def test_a_huge_message_of_another_version_is_one_line_and_the_chatter_still_shown(tmp_path: Path) -> None:
    import numpy as np

    from rostui.apps.bagview.app import BagViewApp

    path = tmp_path / "other.bag"
    writer = BagWriter(str(path))
    writer.add_connection(Connection(0, "/a_scan", "sensor_msgs/LaserScan",
                                     definition_md5("sensor_msgs/LaserScan", SCAN_OF_ANOTHER_VERSION),
                                     SCAN_OF_ANOTHER_VERSION))
    writer.write(0, T0, np.array([SCAN_RANGES], dtype="<u4").tobytes() + np.full(SCAN_RANGES, 2.0, "<f4").tobytes())
    string = get_message_class("std_msgs/String")
    writer.add_connection(Connection(1, "/b_chatter", "std_msgs/String", string._md5sum, string._full_text))
    writer.write(1, T0, string(data="hello 0").serialize())
    writer.close()
    app = BagViewApp([str(path)], publish=False)
    peak = 0.0

    def text() -> str:
        return str(app.inspector_text.render())

    async def main() -> None:
        nonlocal peak
        tracemalloc.start()  # before the app: the inspector shows the first topic as soon as the bag is read
        try:
            async with app.run_test(size=(100, 40)) as pilot:
                await inspector_open(app, pilot)
                assert app.timeline.selected_topic == "/a_scan"
                await until(lambda: "not decoded here" in text(), lambda: f"one line, not {text()[:400]!r}")
                await pilot.pause()
                peak = tracemalloc.get_traced_memory()[1] / MB
                assert text().count("\n") == 0 and "LaserScan message of 40000004 B on /a_scan" in text(), text()
                assert app.inspector_view.view is None
                await pilot.press("down")
                await until(lambda: 'data: "hello 0"' in text(), "the chatter as text")
                await app.action_quit()
        finally:
            tracemalloc.stop()

    asyncio.run(main())
    record("bag_inspector_other_version", "rostui bag view inspector (in process, traced)",
           bag_mb=round(path.stat().st_size / MB, 1), peak_scan_mb=round(peak, 1))
    assert peak < PEAK_LIMIT_MB, f"{peak:.0f} MB traced"
