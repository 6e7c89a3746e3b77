"""The monitor's plot model (rostui.models.monitor.plot): fields, time window, pause, field names. No Textual."""

from __future__ import annotations

import pytest

from rostui.core.msg import get_message_class
from rostui.models.monitor.plot import (
    CAPACITY, DEFAULT_WINDOW, WINDOWS, PlotFieldError, PlotModel, check_numeric, expand_spec, normal_path,
    numeric_fields, split_spec, thin,
)

Pose = get_message_class("turtlesim/Pose")
Twist = get_message_class("geometry_msgs/Twist")
Log = get_message_class("rosgraph_msgs/Log")


def pose(k: int) -> object:
    """The k-th pose of a turtle moving right and turning."""
    return Pose(x=1.0 + k, y=5.0, theta=0.1 * k, linear_velocity=1.0, angular_velocity=0.1)


def test_window_keeps_the_last_seconds_relative_to_now() -> None:
    """Points older than the window are not shown; times are seconds before now (-10 … 0)."""
    model = PlotModel()
    model.add_field("/turtle1/pose", "x")
    for k in range(30):  # one point a second, t = 100 … 129
        model.add_message("/turtle1/pose", 100.0 + k, pose(k))
    (view,) = model.view(now=129.0)
    assert model.window == DEFAULT_WINDOW == 10.0
    assert view.name == "/turtle1/pose/x"
    assert view.times == tuple(float(t) for t in range(-10, 1))
    assert view.values == tuple(1.0 + k for k in range(19, 30)) and view.last == 30.0
    assert model.longer() == 20.0 and len(model.view(129.0)[0].values) == 21
    assert model.shorter() == 10.0 and model.shorter() == 5.0 and len(model.view(129.0)[0].values) == 6
    while model.window != WINDOWS[0]:
        model.shorter()
    assert model.shorter() == WINDOWS[0]
    while model.window != WINDOWS[-1]:
        model.longer()
    assert model.longer() == WINDOWS[-1]


def test_several_fields_of_one_and_of_two_topics() -> None:
    """x, y and theta of a pose and linear.x of a Twist: each series takes only its topic's messages."""
    model = PlotModel()
    for path in expand_spec("/turtle1/pose/x:y:theta"):
        topic, field = split_spec(path, ["/turtle1/pose", "/turtle1"]) or ("", "")
        model.add_field(topic, field, pose(0))
    model.add_field("/turtle1/cmd_vel", "linear.x")
    assert [s.name for s in model.series] == ["/turtle1/pose/x", "/turtle1/pose/y", "/turtle1/pose/theta",
                                              "/turtle1/cmd_vel/linear/x"]
    assert model.topics == {"/turtle1/pose", "/turtle1/cmd_vel"}
    model.add_message("/turtle1/pose", 1.0, pose(2))
    model.add_message("/turtle1/cmd_vel", 1.5, Twist(linear=get_message_class("geometry_msgs/Vector3")(x=0.5)))
    views = {v.name: v for v in model.view(2.0)}
    assert views["/turtle1/pose/x"].values == (3.0,) and views["/turtle1/pose/y"].values == (5.0,)
    assert views["/turtle1/pose/theta"].values == (pytest.approx(0.2),)
    assert views["/turtle1/cmd_vel/linear/x"].values == (0.5,) and views["/turtle1/cmd_vel/linear/x"].times == (-0.5,)
    assert model.value_range(model.view(2.0)) == pytest.approx((0.2, 5.0))
    assert model.add_field("/turtle1/pose", "/x") is model.series[0], "the same field is not plotted twice"
    assert model.remove_field("/turtle1/pose", "y") and not model.remove_field("/turtle1/pose", "y")
    assert [s.path for s in model.series] == ["x", "theta", "linear/x"]


def test_pause_freezes_the_window_but_points_keep_counting() -> None:
    """While paused the view ends at the pause; new points are received and counted; resume shows them."""
    model = PlotModel()
    model.add_field("/turtle1/pose", "x")
    for k in range(5):
        model.add_message("/turtle1/pose", 10.0 + k, pose(k))
    model.pause(now=14.5)
    frozen = model.view(14.5)
    for k in range(5, 12):
        model.add_message("/turtle1/pose", 10.0 + k, pose(k))
    assert model.paused and model.since_pause == 7 and model.count == 12
    assert model.view(now=21.0) == frozen, "the picture stands still while paused"
    assert frozen[0].values == (1.0, 2.0, 3.0, 4.0, 5.0) and frozen[0].times[-1] == -0.5
    assert not model.toggle_pause(21.0) and model.since_pause == 0
    (live,) = model.view(21.0)
    assert live.last == 12.0 and live.times[-1] == 0.0
    assert model.toggle_pause(22.0) and model.end(30.0) == 22.0


def test_nested_and_array_fields_are_numeric_fields() -> None:
    """Nested fields are found (linear/x), array items by index, times as seconds; strings are not numbers."""
    twist = Twist()
    assert numeric_fields(twist) == ["linear/x", "linear/y", "linear/z", "angular/x", "angular/y", "angular/z"]
    log = Log(level=2, line=42, topics=["a", "b"])
    log.header.stamp.secs = 7
    assert numeric_fields(log) == ["header/seq", "header/stamp", "level", "line"]
    assert check_numeric(log, "/rosout", "header.stamp") == 7.0
    joint = get_message_class("sensor_msgs/JointState")(position=[0.5, 1.5])
    assert "position[1]" in numeric_fields(joint) and check_numeric(joint, "/j", "position[1]") == 1.5
    assert normal_path("/linear.x") == "linear/x"


def test_non_numeric_fields_are_refused_with_a_clear_message() -> None:
    """A string, a message, an array or a missing field: one line naming the field and why; nothing is added."""
    model = PlotModel()
    log = Log(msg="hello", topics=["a"])
    with pytest.raises(PlotFieldError, match=r"^/rosout/msg is a string, not a number: only numeric fields"):
        model.add_field("/rosout", "msg", log)
    with pytest.raises(PlotFieldError, match=r"^/cmd_vel/linear is a message \(geometry_msgs/Vector3\), not a "
                                             r"number: .*e\.g\. /cmd_vel/linear/x$"):
        model.add_field("/cmd_vel", "linear", Twist())
    with pytest.raises(PlotFieldError, match=r"^/rosout/topics is an array of 1, not a number"):
        model.add_field("/rosout", "topics", log)
    with pytest.raises(PlotFieldError, match=r"^/turtle1/pose/z: no field 'z' in turtlesim/Pose$"):
        model.add_field("/turtle1/pose", "z", pose(0))
    with pytest.raises(PlotFieldError, match="is a topic: name one of its numeric fields"):
        model.add_field("/turtle1/pose", "")
    assert model.series == []
    series = model.add_field("/rosout", "msg")  # no message yet: refused when one arrives
    model.add_message("/rosout", 1.0, log)
    assert series.count == 0 and series.error.startswith("/rosout/msg is a string")
    assert model.view(1.0)[0].error == series.error


def test_field_names_as_rqt_plot_takes_them() -> None:
    """`/a/b/x:y` is two fields; the topic is the longest known prefix; a topic alone is no field."""
    assert expand_spec("/turtle1/pose/x:y:theta") == ["/turtle1/pose/x", "/turtle1/pose/y", "/turtle1/pose/theta"]
    assert expand_spec("/turtle1/pose/x") == ["/turtle1/pose/x"]
    topics = ["/turtle1", "/turtle1/pose", "/turtle1/cmd_vel"]
    assert split_spec("/turtle1/pose/x", topics) == ("/turtle1/pose", "x")
    assert split_spec("/turtle1/cmd_vel/linear.x", topics) == ("/turtle1/cmd_vel", "linear/x")
    assert split_spec("/turtle1/pose", ["/turtle1/pose"]) is None
    assert split_spec("/other/x", topics) is None


def test_ring_buffer_drops_the_oldest_points() -> None:
    """A fast topic keeps at most CAPACITY points per field, and nothing older than the longest window."""
    model = PlotModel()
    series = model.add_field("/turtle1/pose", "x")
    for k in range(CAPACITY + 10):
        model.add_message("/turtle1/pose", k * 0.01, pose(k))
    assert len(series.values) == CAPACITY and series.values[0] == 11.0 and series.count == CAPACITY + 10
    model.add_message("/turtle1/pose", 10_000.0, pose(0))
    assert list(series.times) == [10_000.0]


def test_thinning_keeps_each_slices_extremes() -> None:
    """Many points: at most two per slice (its lowest and highest, in time order); few points: all of them."""
    times = [k * 0.01 for k in range(1000)]
    values = [float((k * 37) % 101) for k in range(1000)]
    kept_t, kept_v = thin(times, values, 0.0, 10.0, 10)
    assert len(kept_t) == 20 and kept_t == sorted(kept_t)
    for bucket in range(10):
        inside = [v for t, v in zip(times, values) if bucket <= t < bucket + 1]
        shown = [v for t, v in zip(kept_t, kept_v) if bucket <= t < bucket + 1]
        assert sorted(shown) == [min(inside), max(inside)]
    assert thin(times[:15], values[:15], 0.0, 10.0, 10) == (times[:15], values[:15])
    model = PlotModel()
    model.add_field("/turtle1/pose", "x")
    for k in range(300):
        model.add_message("/turtle1/pose", k * 0.02, pose(k % 7))
    (view,) = model.view(6.0, buckets=25)
    assert len(view.values) == 30, "6 s of points fill 15 of the 10 s window's 25 slices"
    assert min(view.values) == 1.0 and max(view.values) == 7.0
