"""tf against a chain 3000 frames deep and a loop: lookups answer as Debian's tf2, the tree is drawn and the app answers.

Before the fix `rostui tf tree` died with a RecursionError on such a chain (the tree was walked recursively),
and the /tf view and bag view's inspector with it.  tf2 (BufferCore, in every tf2_ros listener) walks at most
1000 links up from a frame (MAX_GRAPH_DEPTH in Debian's tf2/buffer_core.h) and calls anything deeper "The tf
tree is invalid because it contains a loop."; rostui answers the same lookups the same way, with tf2's
sentence, and Debian's tf2 (tests/peers/tf2_lookups.py) is asked the same questions in the same run.

The live test sends the chain and the loop from a rostui client (tests/peers/rostui_tf_bomb.py) beside a
legitimate broadcaster at 20 Hz (tests/peers/rostui_tf_chain.py), with `rostui tf tree` (TfTreeApp under the
run_test pilot, in this process) listening, its memory sampled; Debian's tf2_ros listener
(tests/peers/rospy_tf_lookups.py) takes the same input.  Figures are recorded, never asserted as durations.
"""

from __future__ import annotations

import asyncio
import json
import os
import subprocess
import sys
import tracemalloc
from pathlib import Path
from typing import Any

import pytest
from textual.pilot import Pilot

from hostile_helpers import MB, RssSampler, record
from interop_helpers import Spawn, rospy_peer, spawn  # noqa: F401  (fixture)
from rostui.apps.view.tf_tree_app import TfTreeApp
from rostui.apps.view.tf_tree_view import TfTreeView
from rostui.tools.tf import DepthError, LoopError, TfBuffer, TfError, Transform
from rostui.tools.tf.buffer import LOOP_TEXT, MAX_GRAPH_DEPTH
from rostui.tools.tf.buffer import stamp_ns as ns
from rostui.models.tf.tree import MAX_INDENT, summary, tree_rows

from conftest import REPO, SYSTEM_PYTHON, have_rospy, need_peer, until

DEPTH = 3000
LOOP = ["l0", "l1", "l2"]
#: parent, child: the deep chain f0 -> ... -> f3000, a loop l0 -> l1 -> l2 -> l0 with x below it, a frame beside
#: the chain's root and a second tree.
EDGES = ([(f"f{i}", f"f{i + 1}") for i in range(DEPTH)] + [(LOOP[i], LOOP[(i + 1) % 3]) for i in range(3)]
         + [("l0", "x"), ("f0", "side"), ("w", "v")])
#: target, source: asked of rostui's buffer and of tf2's.
LOOKUPS = [("f0", "f1000"), ("f0", "f1001"), ("f0", f"f{DEPTH}"), ("f2000", f"f{DEPTH}"), (f"f{DEPTH}", "f2000"),
           ("f1500", "f1000"), ("f2500", "f500"), ("f1000", "side"), ("side", "f1001"), ("l0", "l1"),
           ("l1", "l0"), ("x", "l0"), ("l1", "x"), ("f0", "x"), ("w", "v"), ("f0", "v")]


def hostile_buffer() -> TfBuffer:
    """:data:`EDGES`, static, and the legitimate chain map -> odom -> base_link at 20 Hz for a second."""
    buf = TfBuffer()
    for parent, child in EDGES:
        buf.set_transform(parent, child, Transform.identity(), ns(0.0), static=True, broadcaster="/bomb", received=1.0)
    for i in range(21):
        for parent, child in (("map", "odom"), ("odom", "base_link")):
            buf.set_transform(parent, child, Transform.of((1.0, 0.0, 0.0), (0, 0, 0, 1)), ns(100.0 + i * 0.05),
                              static=False, broadcaster="/legit", received=1000.0 + i * 0.05)
    return buf


def rostui_answer(buf: TfBuffer, target: str, source: str) -> str:
    """"ok", or the error's text up to rostui's own detail in brackets (tf2 has its list of frames there)."""
    try:
        buf.lookup_transform(target, source)
        return "ok"
    except TfError as exc:
        return str(exc).split(" (")[0]


def test_lookups_through_a_deep_chain_and_a_loop_answer_as_tf2() -> None:
    need_peer(have_rospy(), "rospy, tf2_py (Debian python3-rospy, python3-tf2)")
    tracemalloc.start()
    try:
        buf = hostile_buffer()
        answers = [rostui_answer(buf, t, s) for t, s in LOOKUPS]
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    scenario = json.dumps({"edges": EDGES, "lookups": LOOKUPS})
    tf2 = subprocess.run([SYSTEM_PYTHON, str(REPO / "tests" / "peers" / "tf2_lookups.py")], input=scenario,
                         capture_output=True, text=True, timeout=120)
    assert tf2.returncode == 0, tf2.stderr
    reference = json.loads(tf2.stdout)
    record("tf_lookups_deep_chain", "rostui TfBuffer (in process)", peak_traced_mb=round(peak / MB, 1),
           tf2_maxrss_mb=round(reference["maxrss_mb"], 1))
    assert dict(zip(LOOKUPS, answers)) == dict(zip(LOOKUPS, reference["answers"]))
    assert reference["answers"][1] == LOOP_TEXT and MAX_GRAPH_DEPTH == 1000  # what the comparison rests on
    assert peak < 20 * MB


def test_errors_say_which_loop_or_depth_in_one_short_line() -> None:
    buf = hostile_buffer()
    with pytest.raises(DepthError) as deep:
        buf.lookup_transform("f0", f"f{DEPTH}")
    with pytest.raises(LoopError) as loop:
        buf.lookup_transform("f0", "x")
    for text in (str(deep.value), str(loop.value)):
        assert text.startswith(LOOP_TEXT) and "\n" not in text and len(text) < 200, text
    assert "more than 1000 links up from f3000" in str(deep.value)
    assert "l0 -> l2 -> l1 -> l0" in str(loop.value)


def test_tree_rows_of_a_deep_chain_and_a_loop() -> None:
    tracemalloc.start()
    try:
        buf = hostile_buffer()
        rows = tree_rows(buf)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert len(rows) == len(buf.frames()) == len({r.frame for r in rows})
    by_frame = {r.frame: r for r in rows}
    deepest = by_frame[f"f{DEPTH}"]
    assert deepest.depth == DEPTH and deepest.label().startswith(f"┄{DEPTH - 1 - MAX_INDENT}┄ ")
    assert max(len(r.prefix) for r in rows) <= 3 * (MAX_INDENT + 1) + 8  # narrow however deep
    assert [r.frame for r in rows if r.in_loop] == LOOP and by_frame["x"].depth == 1 and not by_frame["x"].in_loop
    assert summary(buf, rows) == f"{DEPTH + 11} frames, 3 trees, {DEPTH + 6} static, 3 in a loop"
    assert peak < 20 * MB


def table_rows(view: TfTreeView) -> list[str]:
    """The frame column as the table shows it."""
    return [str(getattr(view.table.get_row_at(i)[0], "plain", "")) for i in range(view.table.row_count)]


def test_tf_tree_app_draws_a_deep_chain_and_a_loop_and_answers() -> None:
    buf = hostile_buffer()

    async def main() -> None:
        view = TfTreeView(buffer=buf, clock=lambda: 101.0)
        app = TfTreeApp(master_uri="http://localhost:11311/", view=view)
        async with app.run_test(size=(100, 24)) as pilot:
            await until(lambda: view.table.row_count == len(buf.frames()), "every frame in the table")
            shown = table_rows(view)
            assert shown[0] == "f0" and "map" in shown and "└─ odom" in shown
            assert str(view.summary_line.render()) == summary(buf)
            view.table.move_cursor(row=shown.index(next(r for r in shown if r.endswith(f"└─ f{DEPTH}"))))
            await pilot.pause()
            assert f"f{DEPTH} in f{DEPTH - 1}" in str(view.detail.render())
            assert LOOP_TEXT in str(view.detail.render())  # its pose in the root: too deep for tf2
            await pilot.press("down")
            await pilot.pause()
            assert str(view.detail.render()).startswith("side in f0")
            view.table.move_cursor(row=shown.index("l0  (in a loop)"))
            await pilot.pause()
            assert str(view.detail.render()).startswith("l0 in l2") and LOOP_TEXT in str(view.detail.render())
            view.table.move_cursor(row=shown.index("   └─ base_link"))
            await pilot.pause()
            assert "base_link in map: xyz [2.000, 0.000, 0.000]" in str(view.detail.render())
            await pilot.press("q")
        assert app.return_code == 0

    asyncio.run(main())


def write_deep_bag(path: Path) -> Path:
    """/tf: the deep chain and the loop in one message (as a hostile recorder would leave it)."""
    from rostui.core.bag.files import open_writer
    from rostui.core.bag.model import Connection
    from rostui.core.msg import get_message_class

    tf_message = get_message_class("tf2_msgs/TFMessage")
    stamped = get_message_class("geometry_msgs/TransformStamped")
    msg = tf_message()
    for parent, child in EDGES:
        t = stamped(child_frame_id=child)
        t.header.frame_id, t.transform.rotation.w = parent, 1.0
        msg.transforms.append(t)
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/tf", tf_message._type, tf_message._md5sum, tf_message._full_text, "/bomb"))
    writer.write(0, 1_795_360_000_000_000_000, msg.serialize())
    writer.close()
    return path


def test_bag_view_inspects_a_deep_chain_message(tmp_path: Path) -> None:
    from rostui.apps.bagview.app import BagViewApp

    from bag_view_helpers import inspector_open, run_pilot

    path = write_deep_bag(tmp_path / "deep.bag")

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await inspector_open(app, pilot)
        await until(lambda: isinstance(app.inspector_view.view, TfTreeView)
                    and app.inspector_view.view.table.row_count == DEPTH + 8, "every frame in the inspector",
                    timeout=60)
        view = app.inspector_view.view
        assert isinstance(view, TfTreeView)
        assert str(view.summary_line.render()) == (f"{len(EDGES)} transforms in this message: {DEPTH + 8} frames, "
                                                   "2 trees, 3 in a loop")
        await pilot.press("down")  # the app still answers its keys

    run_pilot(BagViewApp([str(path)], publish=False), scenario, size=(120, 40))


def test_live_tree_beside_a_legit_broadcaster_and_tf2_ros_on_the_same_input(
        rostui_core: Any, ros_env: dict[str, str], spawn: Spawn) -> None:  # noqa: F811
    """The chain and the loop from one node, the legitimate chain from another: `rostui tf tree` shows both,
    the legitimate edges' rates keep coming; Debian's tf2_ros listener answers the same lookups (recorded)."""
    need_peer(have_rospy(), "rospy, tf2_ros (Debian python3-rospy, python3-tf2-ros)")
    spawn([sys.executable, str(REPO / "tests" / "peers" / "rostui_tf_bomb.py"), str(DEPTH), "10"],
          label="tf bomb").wait_for("broadcasting")
    spawn([sys.executable, str(REPO / "tests" / "peers" / "rostui_tf_chain.py"), "20"],
          label="legit chain").wait_for("broadcasting")

    async def main() -> None:
        app = TfTreeApp()
        async with app.run_test(size=(100, 24)) as pilot:
            view = app.view
            with RssSampler(os.getpid()) as rss:
                await until(lambda: view.table.row_count >= DEPTH + 1 + 3 + 4, lambda: (
                    f"the frames in the table: {view.table.row_count} of {len(view.buffer.frames())}"), timeout=60)
                odom = view.buffer.edge("odom")
                assert odom is not None
                count = odom.count
                await until(lambda: odom.count >= count + 20, "the legitimate chain still received", timeout=60)
            shown = table_rows(view)
            assert "map" in shown and "└─ odom" in shown and "f0" in shown
            assert "3 in a loop" in str(view.summary_line.render())
            row = shown.index("└─ odom")
            rate = str(view.table.get_row_at(row)[2].plain)
            assert rate.endswith(" Hz"), rate
            record("tf_tree_live_deep_chain", "rostui tf tree", peak_rss_growth_mb=round(rss.growth_mb, 1),
                   frames=len(view.buffer.frames()), odom_rate=rate)
            assert rss.growth_mb < 200
            await pilot.press("q")

    asyncio.run(main())
    listener = subprocess.run(rospy_peer("rospy_tf_lookups.py", "f0", f"f{DEPTH}", "map", "base_link"),
                              env=ros_env, capture_output=True, text=True, timeout=120)
    assert listener.returncode == 0, listener.stderr
    answer = json.loads(listener.stdout.splitlines()[-1])
    record("tf_listener_live_deep_chain", "Debian tf2_ros listener (rospy)", **answer)
    assert answer["answers"] == [LOOP_TEXT, "ok"]
