"""tf maths and the transform buffer, checked against transforms composed by hand as 4x4 matrices."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from rostui.tools.tf import (
    ConnectivityError, ExtrapolationError, FrameNotFoundError, LoopError, TfBuffer, Transform, quat_from_rpy,
    quat_to_rpy,
)
from rostui.tools.tf.buffer import stamp_ns as ns


def rot_x(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def hom(t: tuple[float, float, float], r: np.ndarray) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = r
    m[:3, 3] = t
    return m


def rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    return rot_z(yaw) @ rot_y(pitch) @ rot_x(roll)


# map -> odom -> base_link -> laser, each given as translation and roll/pitch/yaw
CHAIN = [
    ("map", "odom", (1.0, 2.0, 0.0), (0.0, 0.0, 0.5)),
    ("odom", "base_link", (0.5, -0.25, 0.1), (0.1, -0.2, 1.2)),
    ("base_link", "laser", (0.2, 0.0, 0.3), (math.pi, 0.0, -0.3)),
]


def chain_buffer(static_last: bool = False) -> TfBuffer:
    buf = TfBuffer()
    for i, (parent, child, t, rpy) in enumerate(CHAIN):
        static = static_last and i == len(CHAIN) - 1
        buf.set_transform(parent, child, Transform.of(t, quat_from_rpy(*rpy)), ns(0.0 if static else 100.0),
                          static=static, broadcaster=f"/node{i}", received=1.0)
    return buf


def expected(target: str, source: str) -> np.ndarray:
    frames = {"map": np.eye(4)}
    for parent, child, t, rpy in CHAIN:
        frames[child] = frames[parent] @ hom(t, rpy_matrix(*rpy))
    return np.linalg.inv(frames[target]) @ frames[source]


def test_quaternion_of_rpy_matches_matrices() -> None:
    for rpy in [(0.1, 0.2, 0.3), (-1.0, 0.5, 2.5), (math.pi, 0.0, -0.3)]:
        got = Transform.of((0, 0, 0), quat_from_rpy(*rpy)).matrix()[:3, :3]
        assert np.allclose(got, rpy_matrix(*rpy), atol=1e-12)


def test_rpy_round_trip() -> None:
    for rpy in [(0.1, 0.2, 0.3), (-1.0, 0.5, 2.5), (3.0, -1.2, -3.0)]:
        assert np.allclose(quat_to_rpy(quat_from_rpy(*rpy)), rpy, atol=1e-12)


def test_rpy_at_gimbal_lock_is_the_same_rotation() -> None:
    q = quat_from_rpy(0.3, math.pi / 2, 0.4)
    roll, pitch, yaw = quat_to_rpy(q)
    assert pitch == pytest.approx(math.pi / 2)
    assert yaw == 0.0
    assert np.allclose(rpy_matrix(roll, pitch, yaw), Transform.of((0, 0, 0), q).matrix()[:3, :3], atol=1e-9)


def test_composition_and_inverse_match_matrices() -> None:
    a = Transform.of((1, 2, 3), quat_from_rpy(0.1, 0.2, 0.3))
    b = Transform.of((-0.5, 0.4, 2.0), quat_from_rpy(-0.7, 0.3, 1.9))
    assert np.allclose((a * b).matrix(), a.matrix() @ b.matrix(), atol=1e-12)
    assert np.allclose(a.inverse().matrix(), np.linalg.inv(a.matrix()), atol=1e-12)
    assert np.allclose((a * a.inverse()).matrix(), np.eye(4), atol=1e-12)
    assert np.allclose(a.apply((1, 0, 0)), (a.matrix() @ [1, 0, 0, 1])[:3], atol=1e-12)


def test_non_finite_or_zero_quaternion_refused() -> None:
    with pytest.raises(ValueError):
        Transform.of((0, 0, 0), (0, 0, 0, 0))
    with pytest.raises(ValueError):
        Transform.of((float("nan"), 0, 0), (0, 0, 0, 1))


@pytest.mark.parametrize("target,source", [
    ("map", "laser"), ("laser", "map"), ("odom", "laser"), ("base_link", "odom"), ("laser", "laser"),
    ("laser", "odom"),
])
def test_lookup_through_the_tree(target: str, source: str) -> None:
    got = chain_buffer().lookup_transform(target, source)
    assert got.stamp == 100.0  # a frame in itself too: tf2 stamps it with the frame's newest data
    assert np.allclose(got.transform.matrix(), expected(target, source), atol=1e-12)


def test_lookup_between_branches_uses_the_common_ancestor() -> None:
    buf = chain_buffer()
    buf.set_transform("base_link", "camera", Transform.of((0.1, 0.1, 0.5), quat_from_rpy(0, 0.4, 0)), ns(100.0),
                      static=False, broadcaster="/cam", received=1.0)
    base = np.linalg.inv(expected("base_link", "map"))  # base_link in map
    camera_in_map = base @ hom((0.1, 0.1, 0.5), rpy_matrix(0, 0.4, 0))
    want = np.linalg.inv(expected("map", "laser")) @ camera_in_map
    assert np.allclose(buf.lookup_transform("laser", "camera").transform.matrix(), want, atol=1e-12)


def test_static_edge_answers_any_time_and_sets_no_stamp() -> None:
    buf = chain_buffer(static_last=True)
    got = buf.lookup_transform("base_link", "laser")
    assert got.stamp == 0.0
    assert buf.lookup_transform("map", "laser").stamp == 100.0
    assert buf.edge("laser").static and buf.edge("laser").rate() is None


def test_latest_common_time_interpolates_the_newer_edge() -> None:
    buf = TfBuffer()
    buf.set_transform("map", "odom", Transform.of((0, 0, 0), (0, 0, 0, 1)), ns(10.0), static=False,
                      broadcaster="/a", received=0)
    buf.set_transform("map", "odom", Transform.of((2, 0, 0), quat_from_rpy(0, 0, 1.0)), ns(12.0), static=False,
                      broadcaster="/a", received=1)
    buf.set_transform("odom", "base", Transform.of((0, 1, 0), (0, 0, 0, 1)), ns(11.0), static=False,
                      broadcaster="/b", received=1)
    got = buf.lookup_transform("map", "base")
    assert got.stamp == 11.0
    want = hom((1, 0, 0), rot_z(0.5)) @ hom((0, 1, 0), np.eye(3))
    assert np.allclose(got.transform.matrix(), want, atol=1e-12)
    with pytest.raises(ExtrapolationError, match=r"at time 12\.000000000, but only time 11\.000000000 is in the buffer, "
                                                 r"when looking up transform from frame \[base\] to frame \[map\]"):
        buf.lookup_transform("map", "base", ns(12.0))
    with pytest.raises(ExtrapolationError, match=r"1\.000000000s into the future"):
        buf.lookup_transform("map", "odom", ns(13.0))
    with pytest.raises(ExtrapolationError, match="into the past"):
        buf.lookup_transform("map", "odom", ns(9.0))


def test_dynamic_window_drops_old_samples_and_rate_counts_receipts() -> None:
    buf = TfBuffer(cache_time=2.0)
    for i in range(50):
        buf.set_transform("map", "odom", Transform.of((i, 0, 0), (0, 0, 0, 1)), ns(100.0 + i * 0.1), static=False,
                          broadcaster="/odom_pub", received=i * 0.1)
    edge = buf.edge("odom")
    assert edge is not None
    assert edge.oldest_stamp() >= 104.9 - 2.0 - 1e-9
    assert edge.rate() == pytest.approx(10.0)
    assert edge.age(now=105.4) == pytest.approx(0.5)
    assert edge.broadcaster == "/odom_pub" and edge.count == 50


def test_time_jumping_back_starts_the_edge_again() -> None:
    buf = TfBuffer(cache_time=2.0)
    buf.set_transform("map", "odom", Transform.identity(), ns(100.0), static=False, broadcaster="/a", received=0)
    buf.set_transform("map", "odom", Transform.of((1, 0, 0), (0, 0, 0, 1)), ns(5.0), static=False,
                      broadcaster="/a", received=1)
    assert buf.lookup_transform("map", "odom").stamp == 5.0


def test_unknown_unconnected_and_looping_frames() -> None:
    buf = chain_buffer()
    with pytest.raises(FrameNotFoundError, match='"nowhere" passed to lookupTransform argument source_frame'):
        buf.lookup_transform("map", "nowhere")
    buf.set_transform("world", "other", Transform.identity(), ns(100.0), static=False, broadcaster="/x", received=0)
    with pytest.raises(ConnectivityError, match="not part of the same tree"):
        buf.lookup_transform("map", "other")
    assert buf.roots() == ["map", "world"]
    buf.set_transform("c", "a", Transform.identity(), ns(1.0), static=False, broadcaster="/x", received=0)
    buf.set_transform("a", "b", Transform.identity(), ns(1.0), static=False, broadcaster="/x", received=0)
    buf.set_transform("b", "c", Transform.identity(), ns(1.0), static=False, broadcaster="/x", received=0)
    with pytest.raises(LoopError, match="loop"):
        buf.lookup_transform("map", "a")


def test_message_feed_strips_slashes_and_reports_bad_transforms() -> None:
    def ts(parent: str, child: str, x: float, w: float) -> SimpleNamespace:
        return SimpleNamespace(
            header=SimpleNamespace(frame_id=parent, stamp=SimpleNamespace(secs=7, nsecs=500_000_000)),
            child_frame_id=child,
            transform=SimpleNamespace(translation=SimpleNamespace(x=x, y=0.0, z=0.0),
                                      rotation=SimpleNamespace(x=0.0, y=0.0, z=0.0, w=w)))
    buf = TfBuffer()
    problems = buf.add_message(SimpleNamespace(transforms=[
        ts("/map", "/odom", 1.0, 1.0), ts("odom", "odom", 0.0, 1.0), ts("odom", "bad", 0.0, 0.0),
        ts("odom", "", 0.0, 1.0),
    ]), static=False, broadcaster="/pub", received=3.0)
    assert len(problems) == 3 and all(p.startswith("ignoring transform from [/pub]") for p in problems)
    assert buf.frames() == ["map", "odom"]
    got = buf.lookup_transform("/map", "odom")
    assert got.stamp == 7.5 and got.transform.translation.tolist() == [1.0, 0.0, 0.0]
    assert buf.all_frames_as_string() == "Frame odom exists with parent map.\n"


def test_parent_change_replaces_the_edge() -> None:
    buf = chain_buffer()
    buf.set_transform("map", "base_link", Transform.identity(), ns(100.0), static=False, broadcaster="/amcl",
                      received=2.0)
    assert buf.parent("base_link") == "map"
    assert buf.children("map") == ["base_link", "odom"]
    assert buf.edge("base_link").broadcaster == "/amcl"


def test_frame_limit() -> None:
    buf = TfBuffer(max_frames=3)
    buf.set_transform("a", "b", Transform.identity(), ns(1.0), static=False, broadcaster="/x", received=0)
    buf.set_transform("b", "c", Transform.identity(), ns(1.0), static=False, broadcaster="/x", received=0)
    with pytest.raises(Exception, match="more than 3 frames"):
        buf.set_transform("c", "d", Transform.identity(), ns(1.0), static=False, broadcaster="/x", received=0)
    assert buf.frames() == ["a", "b", "c"]


def test_raw_feed_takes_the_broadcaster_and_refuses_garbage_and_other_types() -> None:
    from rostui.core.msg import get_message_class
    from rostui.core.node import AnyMsg
    from rostui.models.tf.source import feed_raw

    tf_message = get_message_class("tf2_msgs/TFMessage")
    stamped = get_message_class("geometry_msgs/TransformStamped")()
    stamped.header.frame_id, stamped.child_frame_id = "map", "odom"
    stamped.header.stamp.secs = 12
    stamped.transform.translation.x = 3.0
    stamped.transform.rotation.w = 1.0
    good = AnyMsg(tf_message(transforms=[stamped]).serialize())
    good._connection_header = {"type": "tf2_msgs/TFMessage", "callerid": "/odom_node"}
    buf = TfBuffer()
    assert feed_raw(buf, good, static=False, received=1.0) == []
    assert buf.edge("odom").broadcaster == "/odom_node"
    assert buf.lookup_transform("map", "odom").transform.translation.tolist() == [3.0, 0.0, 0.0]

    garbage = AnyMsg(b"\xff\xff\xff\x7f")
    garbage._connection_header = {"type": "tf2_msgs/TFMessage", "callerid": "/bad"}
    assert feed_raw(buf, garbage, static=False, received=2.0)[0].startswith("undecodable tf2_msgs/TFMessage from [/bad]")
    other = AnyMsg(b"")
    other._connection_header = {"type": "std_msgs/String", "callerid": "/confused"}
    assert feed_raw(buf, other, static=False, received=2.0) == [
        "[/confused] publishes std_msgs/String, not tf2_msgs/TFMessage; ignored"]
    assert buf.frames() == ["map", "odom"]
    stamped.header.frame_id, stamped.child_frame_id = "odom", "base"
    older = AnyMsg(tf_message(transforms=[stamped]).serialize())  # its bytes would even decode as ours
    older._connection_header = {"type": "tf2_msgs/TFMessage", "md5sum": "0" * 32, "callerid": "/old"}
    assert feed_raw(buf, older, static=False, received=3.0) == [
        f"[/old] publishes tf2_msgs/TFMessage with md5sum {'0' * 32}, not rostui's {tf_message._md5sum}; ignored"]
    assert buf.frames() == ["map", "odom"]


def test_an_edge_keeps_a_bounded_number_of_samples() -> None:
    from rostui.tools.tf.buffer import MAX_SAMPLES

    buf = TfBuffer()
    for i in range(MAX_SAMPLES + 500):
        buf.set_transform("map", "odom", Transform.of((i, 0, 0), (0, 0, 0, 1)), ns(100.0 + i * 1e-5), static=False,
                          broadcaster="/flood", received=0.0)
    edge = buf.edge("odom")
    assert edge is not None and len(edge.samples) == len(edge.stamps) == MAX_SAMPLES
    assert buf.lookup_transform("map", "odom").transform.translation[0] == MAX_SAMPLES + 499


def test_an_edges_first_receipts_in_a_burst_do_not_lift_its_rate() -> None:
    """Three transforms queued while the listener started, handed over at once, then 20 Hz: the rate reads 20."""
    from rostui.tools.tf.buffer import Edge

    edge = Edge("odom", "map", False, "/b")
    edge.receipts.extend([100.0, 100.0001, 100.0002] + [100.0002 + 0.05 * i for i in range(1, 6)])
    assert edge.rate() == pytest.approx(20.0)


def test_an_edge_seen_only_in_one_burst_has_no_rate_yet() -> None:
    """A listener held up by a busy machine takes three 20 Hz transforms in one read: no rate (once 13 kHz, in CI)."""
    from rostui.tools.tf.buffer import Edge

    edge = Edge("odom", "map", False, "/b")
    edge.receipts.extend([100.0, 100.00005, 100.00015])
    assert edge.rate() is None
    edge.receipts.extend([100.00015 + 0.05 * i for i in range(1, 6)])
    assert edge.rate() == pytest.approx(20.0)
