"""A bag recorded with another version of a type rostui ships is read with the bag's own definition, as rosbag
reads old bags; only a definition that does not hash to its recorded md5sum is refused.

The bag here holds an older ``turtlesim/Pose`` (no velocities), a ``sensor_msgs/Image`` lacking ``width`` and
``step`` (self-consistent: its md5sum is its definition's) and an ordinary ``std_msgs/String``.  `topic echo -b`,
the rosbag shim and bag view's reader decode each with its own definition; bag view's inspector, which draws an
Image by its type's name, sees that this "Image" is not rostui's and shows it as text with one line saying so,
instead of reading a ``width`` it does not have.  Debian's ``rostopic echo -b`` reads the same bag for comparison.
"""

from __future__ import annotations

import asyncio
import struct
import subprocess
from pathlib import Path

import pytest

from bag_view_helpers import inspector_open
from conftest import until
from rostui.core.bag.model import Connection
from rostui.core.bag.rosbag2_0 import BagWriter
from rostui.core.msg import definition_md5, get_message_class

SEP = "\n" + "=" * 80 + "\n"
HEADER_SECTION = SEP + "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
#: turtlesim/Pose as recorded before linear_velocity and angular_velocity were added.
OLD_POSE = "float32 x\nfloat32 y\nfloat32 theta\n"
#: A sensor_msgs/Image without width and step.
IMAGE_WITHOUT_WIDTH = ("Header header\nuint32 height\nstring encoding\nuint8 is_bigendian\nuint8[] data\n"
                       + HEADER_SECTION)
T0 = 1_700_000_000_000_000_000
POSES = [(1.0, 2.0, 0.5), (1.5, 2.5, 0.25)]


def image_without_width(height: int) -> bytes:
    """One message of that Image: a header (seq 0, stamp T0, frame "cam"), ``height``, "mono8", 4 bytes."""
    return (struct.pack("<III", 0, T0 // 10**9, 0) + struct.pack("<I", 3) + b"cam" + struct.pack("<I", height)
            + struct.pack("<I", 5) + b"mono8" + b"\0" + struct.pack("<I", 4) + bytes(4))


def old_bag(path: Path) -> Path:
    """The bag described above: /camera/image_raw, /chatter and /turtle1/pose, two messages each."""
    string = get_message_class("std_msgs/String")
    writer = BagWriter(str(path))
    writer.add_connection(Connection(0, "/camera/image_raw", "sensor_msgs/Image",
                                     definition_md5("sensor_msgs/Image", IMAGE_WITHOUT_WIDTH), IMAGE_WITHOUT_WIDTH))
    writer.add_connection(Connection(1, "/chatter", "std_msgs/String", string._md5sum, string._full_text))
    writer.add_connection(Connection(2, "/turtle1/pose", "turtlesim/Pose", definition_md5("turtlesim/Pose", OLD_POSE),
                                     OLD_POSE))
    for i, pose in enumerate(POSES):
        t = T0 + i * 100_000_000
        writer.write(0, t, image_without_width(10 + i))
        writer.write(1, t, string(data=f"hello {i}").serialize())
        writer.write(2, t, struct.pack("<fff", *pose))
    writer.close()
    return path


def test_topic_echo_b_reads_an_old_version_as_rostopic_does(tmp_path: Path) -> None:
    """Before: "the connection of /turtle1/pose has datatype/md5sum [...], but our version has [...]", exit 1."""
    from rostui.tools.topic.bag_echo import echo_bag
    from rostui.tools.topic.echo import EchoFormatter

    path = old_bag(tmp_path / "old.bag")
    printed: list[str] = []
    assert echo_bag(str(path), "/turtle1/pose", EchoFormatter("", from_bag=True), printed.append) == 2
    assert "".join(printed) == "x: 1.0\ny: 2.0\ntheta: 0.5\n---\nx: 1.5\ny: 2.5\ntheta: 0.25\n---\n"
    images: list[str] = []
    echo_bag(str(path), "/camera/image_raw/height", EchoFormatter("", from_bag=True), images.append)
    assert images == ["10\n---\n", "11\n---\n"]
    try:
        debian = subprocess.run(["rostopic", "echo", "-b", str(path), "/turtle1/pose"], capture_output=True,
                                text=True, timeout=60)
    except FileNotFoundError:
        return
    assert debian.stdout == "".join(printed), debian.stderr  # Debian's rostopic reads it the same


def test_the_rosbag_shim_reads_an_old_version(tmp_path: Path) -> None:
    from rostui.compat.rosbag_bag import Bag

    path = old_bag(tmp_path / "old.bag")
    with Bag(str(path)) as bag:
        poses = [(m.x, m.y, m.theta) for _topic, m, _t in bag.read_messages(topics=["/turtle1/pose"])]
        heights = [m.height for _topic, m, _t in bag.read_messages(topics=["/camera/image_raw"])]
        chatter = [m.data for _topic, m, _t in bag.read_messages(topics=["/chatter"])]
    assert poses == POSES and heights == [10, 11] and chatter == ["hello 0", "hello 1"]
    assert not hasattr(get_message_class("turtlesim/Pose")(), "height")  # nothing registered over rostui's types


def test_bag_view_inspects_an_image_of_another_version_as_text_with_one_line(tmp_path: Path) -> None:
    """Before the bag's own version was read, the inspector said "but our version has"; reading it without the
    inspector's check drew it as an Image and died on ``msg.width`` (AttributeError)."""
    from rostui.apps.bagview.app import BagViewApp

    path = old_bag(tmp_path / "old.bag")
    image = get_message_class("sensor_msgs/Image")
    theirs = definition_md5("sensor_msgs/Image", IMAGE_WITHOUT_WIDTH)

    async def main() -> None:
        app = BagViewApp([str(path)], publish=False)
        async with app.run_test(size=(100, 40)) as pilot:
            await inspector_open(app, pilot)
            assert app.timeline.selected_topic == "/camera/image_raw"
            await until(lambda: "height: 10" in str(app.inspector_text.render()), "the old Image as text")
            await pilot.pause()
            assert app.inspector_view.view is None
            note = str(app.inspector_view.note.render())
            assert note == (f"sensor_msgs/Image here has md5sum {theirs}, not the one rostui knows "
                            f"({image._md5sum}): shown as text"), note
            await pilot.press("end")
            await until(lambda: "height: 11" in str(app.inspector_text.render()), "the second one")
            await pilot.press("down")  # /chatter: an ordinary topic, no picture and no note
            await until(lambda: "hello" in str(app.inspector_text.render()), "the String as text")
            assert not app.inspector_view.note.display
            await app.action_quit()

    asyncio.run(main())


def test_what_draws_a_type_by_its_fields_refuses_another_version_in_one_line() -> None:
    """The image decoder and the top-down geometry read fields by the type's name: a bag's own version (another
    md5sum) is one line, not an AttributeError deep in them."""
    from rostui.core.msg import connection_class
    from rostui.models.sensors.images import ImageDecodeError, decode_image
    from rostui.models.sensors.scene2d import drawing_of

    image = connection_class("sensor_msgs/Image", definition_md5("sensor_msgs/Image", IMAGE_WITHOUT_WIDTH),
                             IMAGE_WITHOUT_WIDTH, stored=True)
    with pytest.raises(ImageDecodeError, match=r"^sensor_msgs/Image here has md5sum \w+, not the one rostui knows "
                                               r"\(\w+\): not drawn$"):
        decode_image(image.deserialize(image_without_width(10)))
    old_scan = "Header header\nfloat32 angle_min\n" + HEADER_SECTION  # no ranges
    scan = connection_class("sensor_msgs/LaserScan", definition_md5("sensor_msgs/LaserScan", old_scan), old_scan,
                            stored=True)
    with pytest.raises(ValueError, match=r"^sensor_msgs/LaserScan here has md5sum .*: not drawn$"):
        drawing_of(scan())


def test_the_view_and_the_monitor_refuse_a_played_bag_of_another_version_in_one_line(
        tmp_path: Path, rostui_core: object, ros_env: dict[str, str], monkeypatch: pytest.MonkeyPatch) -> None:
    """`rostui bag play` publishes the old bag's Image under the bag's own type, md5sum and definition: the view's
    Image panel and the monitor's tree each refuse it in one line (no AttributeError), the bag's String still
    reaching the monitor."""
    from rostui.apps.monitor.app import MonitorApp
    from rostui.apps.view.app import ViewApp
    from rostui.apps.view.image_view import GRAPHICS_ENV

    from conftest import rostui_cmd, stop_process

    monkeypatch.setenv(GRAPHICS_ENV, "halfblock")
    path = old_bag(tmp_path / "old.bag")
    image = get_message_class("sensor_msgs/Image")
    theirs = definition_md5("sensor_msgs/Image", IMAGE_WITHOUT_WIDTH)
    refused = (f"refused publisher [/play_", f"has datatype/md5sum [sensor_msgs/Image/{theirs}], "
               f"not [sensor_msgs/Image/{image._md5sum}]")
    play = subprocess.Popen(rostui_cmd("bag", "play", "-q", "-l", "-r", "10", str(path)), env=ros_env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    monitor_lines: list[str] = []

    async def main() -> None:
        view = ViewApp(["/camera/image_raw"], master_uri=ros_env["ROS_MASTER_URI"], period=0.3)
        async with view.run_test(size=(80, 24)):
            panel = view.grid.panels[0]
            await until(lambda: panel.refused_line.display, "the view's panel to refuse the bag's Image", timeout=60)
            line = str(panel.refused_line.render())
            assert line.startswith(refused[0]) and refused[1] in line and "\n" not in line, line
            await view.action_quit()
        monitor = MonitorApp(period=0.3)
        async with monitor.run_test(size=(120, 40)) as pilot:
            await until(lambda: monitor.topic_type("/camera/image_raw") == "sensor_msgs/Image", "the topic listed")
            monitor.toggle_expanded("/camera/image_raw")
            monitor.toggle_expanded("/chatter")
            label = lambda topic: str(monitor.message_trees.topic_node(topic).label)  # noqa: E731
            await until(lambda: "✖ refused publisher [/play_" in label("/camera/image_raw")
                        and monitor.source.latest("/chatter") is not None, "the monitor's line and /chatter")
            monitor_lines.append(label("/camera/image_raw"))
            await pilot.press("q")

    try:
        asyncio.run(main())
    finally:
        stop_process(play)
    assert f"but our version has [sensor_msgs/Image/{image._md5sum}]" in monitor_lines[0], monitor_lines
    assert "Traceback" not in (play.stderr.read() if play.stderr else "")
