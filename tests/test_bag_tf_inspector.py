"""`bag view`'s inspector draws a tf2_msgs/TFMessage under the cursor as the tree of its transforms.

Two bags: one recorded by Debian's `rosbag record` from a real roscore while
Debian's rospy broadcaster (tests/peers/rospy_tf_chain.py: map -> odom and
odom -> base_link, one transform a message) and tf2_ros's
static_transform_publisher (base_link -> laser, latched on /tf_static) run;
and one written by rostui's bag writer holding a single message with the
whole chain, as robot_state_publisher sends it (the snapshot, stored in
snapshots/test_bag_tf_inspector/).
"""

from __future__ import annotations

import subprocess
import time
from pathlib import Path
from typing import Any

import pytest
from textual.pilot import Pilot

from rostui.apps.bagview.app import BagViewApp
from rostui.apps.view.tf_tree_view import TfTreeView
from rostui.core.bag.files import open_writer
from rostui.core.bag.model import Connection
from rostui.core.msg import get_message_class

from bag_view_helpers import run_pilot
from conftest import until
from interop_helpers import Spawn, spawn  # noqa: F401  (fixture)
from textual_snapshots import snapshot  # noqa: F401  (stores SVGs in snapshots/)
from tf_chain import CHAIN, start_rospy_chain

TFMessage = get_message_class("tf2_msgs/TFMessage")
TransformStamped = get_message_class("geometry_msgs/TransformStamped")
T0 = 1_795_360_000_000_000_000


def rows(view: TfTreeView) -> list[list[str]]:
    """The tree's rows as the table shows them."""
    table = view.table
    return [[str(getattr(cell, "plain", cell)) for cell in table.get_row_at(i)] for i in range(table.row_count)]


def detail(view: TfTreeView) -> str:
    """The lines under the table."""
    return str(view.detail.render())


async def tree_shown(app: BagViewApp) -> TfTreeView:
    """The inspector's tf tree view, once it shows a message."""
    if not app.inspector.display:
        await app.run_action("toggle_inspector")
    await until(lambda: isinstance(app.inspector_view.view, TfTreeView)
                and app.inspector_view.view.table.row_count > 0, "the tf tree in the inspector")
    view = app.inspector_view.view
    assert isinstance(view, TfTreeView)
    return view


@pytest.fixture
def recorded_tf_bag(tmp_path: Path, real_roscore: Any, ros_env: dict[str, str], rospy_available: None,
                    spawn: Spawn) -> Path:
    """/tf and /tf_static of the rospy chain and the static publisher, recorded by Debian's rosbag for 3 s."""
    start_rospy_chain(spawn)
    path = tmp_path / "tf.bag"
    record = subprocess.run(["rosbag", "record", "-O", str(path), "--duration=3", "/tf", "/tf_static"],
                            env=ros_env, capture_output=True, text=True, timeout=120)
    assert record.returncode == 0, record.stderr
    return path


def test_recorded_tf_messages_as_trees(recorded_tf_bag: Path) -> None:
    chain = {child: (parent, xyz) for parent, child, xyz, _ in CHAIN}

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await until(lambda: app.index is not None and app.transport is not None, "the bag read")
        await pilot.press("end")
        view = await tree_shown(app)
        assert "/tf  tf2_msgs/TFMessage" in str(app.inspector_title.render())
        seen = set()
        for _ in range(2):  # the broadcaster alternates map -> odom and odom -> base_link
            app.refresh_view()
            await pilot.pause()
            await until(lambda: len(rows(view)) == 2, "one transform's tree")
            (parent, _), (child, stamp) = rows(view)
            child = child.replace("└─", "").strip()
            assert chain[child][0] == parent.strip()
            assert float(stamp) * 1e9 == pytest.approx(app.transport.bag_ns(), abs=1e9)  # type: ignore[union-attr]
            x, y, z = chain[child][1]
            assert f"{child} in {parent.strip()}: xyz [{x:.3f}, {y:.3f}, {z:.3f}]" in detail(view)
            assert str(view.summary_line.render()).startswith("1 transform in this message: 2 frames, 1 tree")
            assert "Hz" not in " ".join(sum(rows(view), []))  # no rates for one message
            seen.add(child)
            await pilot.press("comma")  # the message before
        assert seen == {"odom", "base_link"}
        await pilot.press("end", "down")  # /tf_static: the static publisher's latched message
        app.refresh_view()
        def static_shown() -> bool:
            shown = app.inspector_view.view
            return "/tf_static" in str(app.inspector_title.render()) and isinstance(shown, TfTreeView) \
                and shown is not view and bool(rows(shown)) and "laser" in rows(shown)[-1][0]

        await until(static_shown, "the static transform in a new view")
        view = await tree_shown(app)
        assert [r[0].replace("└─", "").strip() for r in rows(view)] == ["base_link", "laser"]
        assert "laser in base_link: xyz [0.200, 0.000, 0.300]  rpy° [180.0, 0.0, -17.2]" in detail(view)
        assert str(view.summary_line.render()).startswith("1 transform in this message: 2 frames, 1 tree, 1 static")

    run_pilot(BagViewApp([str(recorded_tf_bag)], publish=False), scenario, size=(120, 40))


def chain_message(stamp_ns: int) -> Any:
    """One TFMessage with the whole chain (as robot_state_publisher sends several transforms at once)."""
    import math

    msg = TFMessage()
    for parent, child, (x, y, z), (roll, pitch, yaw) in CHAIN:
        t = TransformStamped()
        t.header.frame_id, t.child_frame_id = parent, child
        t.header.stamp.secs, t.header.stamp.nsecs = divmod(stamp_ns, 10**9)
        t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = x, y, z
        cr, sr = math.cos(roll / 2), math.sin(roll / 2)
        cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
        cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
        q = t.transform.rotation
        q.x, q.y = sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy
        q.z, q.w = cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy
        msg.transforms.append(t)
    return msg


def write_chain_bag(path: Path) -> Path:
    """/tf: the whole chain in one message, five times 100 ms apart (stamped as recorded)."""
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/tf", TFMessage._type, TFMessage._md5sum, TFMessage._full_text,
                                     "/robot_state_publisher"))
    for i in range(5):
        t = T0 + i * 100_000_000
        writer.write(0, t, chain_message(t).serialize())
    writer.close()
    return path


def test_several_transforms_in_one_message(tmp_path: Path) -> None:
    path = write_chain_bag(tmp_path / "chain.bag")

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await until(lambda: app.index is not None and app.transport is not None, "the bag read")
        view = await tree_shown(app)
        assert [r[0] for r in rows(view)] == ["map", "└─ odom", "   └─ base_link", "      └─ laser"]
        assert all(r[1] == f"{T0 / 1e9:.6f}" for r in rows(view)[1:]) and rows(view)[0][1] == ""
        assert str(view.summary_line.render()) == "3 transforms in this message: 4 frames, 1 tree"
        await pilot.press("end")
        app.refresh_view()
        await until(lambda: rows(view)[1][1] == f"{(T0 + 400_000_000) / 1e9:.6f}", "the last message's stamps")

    run_pilot(BagViewApp([str(path)], publish=False), scenario, size=(120, 40))


def test_snapshot_chain_message(snap_compare: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The chain message under the cursor, laser selected: the tree, its stamps, laser in base_link and in map."""
    monkeypatch.setenv("COLORTERM", "truecolor")  # the terminal the other bag view snapshots are taken in
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()
    path = write_chain_bag(tmp_path / "chain.bag")

    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, BagViewApp)
        await until(lambda: app.transport is not None, "the bag to be read")
        view = await tree_shown(app)
        view.table.move_cursor(row=3, animate=False)
        view.table.focus()
        await pilot.pause()

    assert snap_compare(BagViewApp([str(path)], publish=False), run_before=run_before, terminal_size=(100, 30))
