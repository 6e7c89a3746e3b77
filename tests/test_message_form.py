"""The form model of `rostui publish` and `rostui call` (rostui/models/message_form): expressions evaluated
without running Python and bounded against bombs, a type laid out as rows, the message the rows build, sliders,
and the form file (saved, read back, and every mistake in it one line with its file and line)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from rostui.core.msg import get_message_class, get_service_class
from rostui.core.rostime import Time
from rostui.models.message_form.expression import MAX_ITEMS, ExpressionError, evaluate
from rostui.models.message_form.form_file import (
    MAX_FILE_BYTES, FormFileError, apply_spec, read_form, spec_of, write_form,
)
from rostui.models.message_form.rows import FormError, MessageForm


@pytest.mark.parametrize("text, value", [
    ("1.5", 1.5), ("-2", -2), ("[1, 2.5]", [1, 2.5]), ("'map'", "map"), ("True", True),
    ("sin(pi / 2)", 1.0), ("math.cos(0) * 3", 3.0), ("2 ** 10", 1024), ("i * 2 + 1", 7), ("t if t > 1 else 0", 2.5),
    ("{'x': 1, 'y': [2]}", {"x": 1, "y": [2]}), ("max(1, i)", 3), ("round(2.567, 2)", 2.57), ("(1, 2)", [1, 2]),
    ("true and not false", True), ("round(7.5)", 8), ("len([[0] * 1000] * 999)", 999),
    ("1 < i <= 3", True), ("not i", False), ("[0.0] * 3", [0.0, 0.0, 0.0]), ("abs(-t)", 2.5),
])
def test_expressions_compute_what_rqt_publisher_users_type(text: str, value: object) -> None:
    assert evaluate(text, {"i": 3, "t": 2.5}) == value


@pytest.mark.parametrize("text, says", [
    ("__import__('os')", "unknown function '__import__'"),
    ("__import__('os').system('true')", "unknown function"),
    ("open('/etc/passwd')", "unknown function 'open'"),
    ("(1).__class__", "attribute"),
    ("[x for x in range(9)]", "a comprehension is not allowed"),
    ("lambda: 1", "lambda is not allowed"),
    ("os", "unknown name 'os' (a string needs quotes)"),
    ("sin", "sin is a function: call it"),
    ("2 ** 10 ** 10", "is too large"),
    ("9 ** 9 ** 9", "is too large"),
    ("'x' * 10 ** 9", f"longer than {MAX_ITEMS} items"),
    ("[0] * 10 ** 8", f"longer than {MAX_ITEMS} items"),
    ("[0] * 999999 + [0] * 999999", f"more than {MAX_ITEMS} items"),
    ("10.0 ** 400", "OverflowError"),
    ("1 / 0", "ZeroDivisionError"),
    ("sqrt(-1)", "ValueError"),
    ("sin(1, 2)", "TypeError"),
    ("1 +", "not an expression"),
    ("f'{1}'", "an f-string is not allowed"),
    ("'a'[0]", "indexing is not allowed"),
    ("math.sin", "math.sin is a function"),
    ("min(*[1])", "only plain arguments"),
    ("~1", "~ is not allowed"),
    ("'%(a)s' % {}", "% formatting of text is not allowed"),
    ("'%01000000000d' % 0", "% formatting of text is not allowed"),
    ("round(1, -10 ** 9)", "round to at most 400 digits"),
    ("[[0] * 10 ** 6] * 10 ** 6", f"more than {MAX_ITEMS} items"),
    ("[[0] * 1000] * 1001", f"longer than {MAX_ITEMS} items"),
    ("1 < 'a'", "TypeError"),
    pytest.param("[" * 300 + "]" * 300, "not an expression", id="lists-300-deep"),
    pytest.param("-" * 50_000 + "1", "not an expression", id="signs-50000-deep"),
])
def test_anything_else_is_refused_in_one_line(text: str, says: str) -> None:
    with pytest.raises(ExpressionError) as caught:
        evaluate(text, {"i": 0, "t": 0.0})
    assert says in str(caught.value) and "\n" not in str(caught.value)


def test_a_huge_expression_is_refused_before_it_is_parsed() -> None:
    with pytest.raises(ExpressionError, match="longer than"):
        evaluate("1+" * 60_000 + "1")


def test_a_twist_is_six_rows_and_builds_with_i_and_t() -> None:
    form = MessageForm.of(get_message_class("geometry_msgs/Twist"))
    assert [(row.path, row.type, row.expression) for row in form.rows] == [
        (f"{part}.{axis}", "float64", "0.0") for part in ("linear", "angular") for axis in "xyz"]
    form.row("linear.x").expression = "0.5 + i"  # type: ignore[union-attr]
    form.row("angular.z").expression = "sin(t)"  # type: ignore[union-attr]
    msg = form.build(i=2, t=math.pi / 2)
    assert (msg.linear.x, msg.angular.z, msg.linear.y) == (2.5, 1.0, 0.0)


def test_a_header_stamp_starts_as_now_and_arrays_are_one_row() -> None:
    form = MessageForm.of(get_message_class("sensor_msgs/JointState"))
    rows = {row.path: (row.type, row.expression) for row in form.rows}
    assert rows == {"header.seq": ("uint32", "0"), "header.stamp": ("time", "now"),
                    "header.frame_id": ("string", "''"), "name": ("string[]", "[]"),
                    "position": ("float64[]", "[]"), "velocity": ("float64[]", "[]"), "effort": ("float64[]", "[]")}
    form.row("name").expression = "['elbow', 'wrist']"  # type: ignore[union-attr]
    form.row("position").expression = "[0.1 * i, -0.2]"  # type: ignore[union-attr]
    form.row("header.frame_id").expression = "base_link"  # type: ignore[union-attr]  # text, as rqt_publisher
    msg = form.build(i=3, now=Time(12, 5))
    assert (msg.header.stamp.secs, msg.header.stamp.nsecs, msg.header.frame_id) == (12, 5, "base_link")
    assert msg.name == ["elbow", "wrist"] and msg.position == pytest.approx([0.3, -0.2])


def test_a_fixed_array_keeps_its_length_and_an_array_of_messages_takes_dicts() -> None:
    form = MessageForm.of(get_message_class("geometry_msgs/PoseWithCovarianceStamped"))
    assert form.row("pose.covariance").expression == "[" + ", ".join(["0.0"] * 36) + "]"  # type: ignore[union-attr]
    form.row("pose.covariance").expression = "[0.1] * 36"  # type: ignore[union-attr]
    assert form.build().pose.covariance == [0.1] * 36
    form.row("pose.covariance").expression = "[0.1] * 35"  # type: ignore[union-attr]
    with pytest.raises(FormError, match=r"incorrect number of elements: 35 != 36"):
        form.build()
    path = MessageForm.of(get_message_class("nav_msgs/Path"))
    path.row("poses").expression = "[{'pose': {'position': {'x': i}}}] * 2"  # type: ignore[union-attr]
    assert [pose.pose.position.x for pose in path.build(i=4).poses] == [4.0, 4.0]


@pytest.mark.parametrize("path, expression, says", [
    ("linear.x", "'fast'", "must be a number"),
    ("linear.x", "speed", "linear.x: unknown name 'speed'"),
    ("linear.y", "1 / 0", "linear.y: ZeroDivisionError"),
])
def test_a_field_that_cannot_be_filled_is_named(path: str, expression: str, says: str) -> None:
    form = MessageForm.of(get_message_class("geometry_msgs/Twist"))
    form.row(path).expression = expression  # type: ignore[union-attr]
    with pytest.raises(FormError, match=says):
        form.build()


def test_sliders_move_by_hundredths_of_their_range_and_stay_in_it() -> None:
    form = MessageForm.of(get_message_class("turtlesim/Pose"))
    x = form.row("x")
    assert x is not None and x.numeric and x.slider_range() == (-1.0, 1.0)
    assert x.nudge(3) and x.expression == "0.06"
    assert x.nudge(1000) and x.expression == "1.0"
    x.low, x.high = 0.0, 11.0
    assert x.nudge(-10) and x.expression == "0.0"
    assert x.nudge(50) and x.expression == "5.5"
    x.expression = "sin(t)"
    assert not x.nudge(1) and x.number() is None
    x.expression = "7"
    x.low = x.high = None
    assert x.slider_range() == (-10.0, 10.0)  # widened to hold the value
    count = MessageForm.of(get_message_class("std_msgs/UInt8")).row("data")
    assert count is not None and count.slider_range() == (0.0, 100.0)
    assert count.nudge(-5) and count.expression == "0"
    assert count.nudge(7) and count.expression == "7"
    text = MessageForm.of(get_message_class("std_msgs/String")).row("data")
    assert text is not None and not text.numeric and not text.nudge(1)


@pytest.mark.parametrize("expression", ["inf", "-inf", "nan", "1e308", "2 ** 2000", "uniform(-1, 1)", "pi", "0.5 + i"])
def test_only_a_plain_finite_number_has_a_slider(expression: str) -> None:
    row = MessageForm.of(get_message_class("sensor_msgs/Range")).row("max_range")
    assert row is not None
    row.expression = expression
    assert row.number() is None and row.fraction() is None and not row.nudge(1)
    assert row.expression == expression and row.slider_range() == (-1.0, 1.0)


def test_an_integer_slider_stays_within_its_type() -> None:
    count = MessageForm.of(get_message_class("std_msgs/UInt8")).row("data")
    assert count is not None
    count.expression = "255"
    assert count.slider_range() == (0.0, 255.0) and count.fraction() == 1.0
    assert count.nudge(1) and count.expression == "255"
    wide = MessageForm.of(get_message_class("std_msgs/Float64")).row("data")
    assert wide is not None
    wide.low, wide.high = 47.1230, 47.1240
    wide.expression = "47.1230"
    assert wide.nudge(1) and wide.expression == "47.12301"


def test_a_string_field_takes_what_its_expression_gives_as_text() -> None:
    form = MessageForm.of(get_message_class("std_msgs/String"))
    for expression, text in (("i", "4"), ("'a' + str(i)", "a4"), ("2024-01-01", "2024-01-01"), ("1 - 2", "-1"),
                             ("no", "no"), ("True", "True")):
        form.rows[0].expression = expression
        assert form.build(i=4).data == text, expression


def test_a_service_request_is_a_form_too() -> None:
    form = MessageForm.of(get_service_class("turtlesim/Spawn")._request_class)
    assert [row.path for row in form.rows] == ["x", "y", "theta", "name"]
    form.row("name").expression = "'t' + str(i)"  # type: ignore[union-attr]
    assert form.build(i=2).name == "t2"


def test_a_saved_form_reads_back_as_it_was(tmp_path: Path) -> None:
    form = MessageForm.of(get_message_class("geometry_msgs/Twist"))
    form.row("linear.x").expression = "2.0"  # type: ignore[union-attr]
    form.row("angular.z").expression = "sin(2 * pi * t)"  # type: ignore[union-attr]
    row = form.row("linear.x")
    assert row is not None
    row.low, row.high = -2.0, 2.0
    path = tmp_path / "drive.form.yaml"
    write_form(spec_of(form, "publish", "/turtle1/cmd_vel", "geometry_msgs/Twist", 10.0), path)
    text = path.read_text()
    assert text.startswith("# rostui form: `rostui publish --form drive.form.yaml` opens it\n")
    assert "publish: /turtle1/cmd_vel\ntype: geometry_msgs/Twist\nrate: 10.0\n" in text
    assert "  angular.z: sin(2 * pi * t)\n" in text and "sliders:\n  linear.x: [-2.0, 2.0]\n" in text
    spec = read_form(path)
    again = MessageForm.of(get_message_class(spec.type_name))
    apply_spec(again, spec)
    assert (spec.kind, spec.name, spec.rate) == ("publish", "/turtle1/cmd_vel", 10.0)
    assert again == form


def test_values_written_by_hand_are_expressions_as_written(tmp_path: Path) -> None:
    path = tmp_path / "spawn.yaml"
    path.write_text("call: /spawn\nfields:\n  x: 5.5\n  name: no\n  theta: [1]\n  y: 2024-01-01\n  z: 1e3\n")
    spec = read_form(path)
    assert (spec.kind, spec.name, spec.type_name) == ("call", "/spawn", "")
    assert spec.expressions == {"x": "5.5", "name": "no", "theta": "[1]", "y": "2024-01-01", "z": "1e3"}


@pytest.mark.parametrize("text, says", [
    ("publish: /a\ntype: std_msgs/String\nfields:\n  data: 'x'\n  nope: 1\n", ":5: std_msgs/String has no field 'nope'"),
    ("publish: /a\ntype: std_msgs/String\nsliders:\n  data: [0, 1]\n", ":4: data is a string, not a number"),
    ("publish: /a\ntype: std_msgs/Int8\nsliders:\n  data: [1, 0]\n", ":4: the slider of data needs [LOW, HIGH]"),
    ("publish: /a\ntype: std_msgs/Int8\nrate: -3\n", ":3: rate must be a positive number of Hz"),
    ("publish: /a\ntype: std_msgs/Int8\nfields: [1]\n", ":3: expected a mapping here"),
    ("publish: /a\ntype: std_msgs/Int8\ncolour: red\n", ":3: unknown key 'colour'"),
    ("publish: /a\ncall: /b\n", ":1: a form names either"),
    ("type: std_msgs/Int8\n", ":1: a form names either"),
    ("publish: /a\ntype: std_msgs/Int8\ntype: x\n", ":3: 'type' is given twice"),
    ("publish: /a\n  type: [oops\n", ":2: YAML error"),
    ("- 1\n- 2\n", ":1: a form is a mapping"),
    ("a: &x [1]\nb: *x\n", ":2: YAML aliases are not allowed"),
    ("publish: /a\nfields: {}\n", ":1: a publish form needs `type: pkg/Type`"),
    ("publish: /a\ntype: std_msgs/Int8\nrate: !!float x\n", ":3: not a value"),
    ("publish: /a\ntype: std_msgs/Int8\nfields:\n  data: !!binary '@@'\n", ":4: data: not an expression"),
    ("publish: /a\ntype: std_msgs/Int8\nfields:\n  data: 1 +\n", ":4: data: not an expression"),
    ("publish: /a\ntype: std_msgs/Int8\nfields:\n  data: " + "[" * 5000 + "\n", ":4: YAML nested more than 64 deep"),
    ("publish: /a\ntype: std_msgs/Int8\nfields:\n  data: '" + "[" * 5000 + "'\n", ":4: data: not an expression"),
])
def test_every_mistake_in_a_form_file_is_one_line_with_its_line(tmp_path: Path, text: str, says: str) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(FormFileError) as caught:
        spec = read_form(path)
        apply_spec(MessageForm.of(get_message_class(spec.type_name)), spec)
    assert str(caught.value).startswith(f"{path}:") and says in str(caught.value), str(caught.value)
    assert "\n" not in str(caught.value)


def test_a_file_too_big_or_not_text_is_refused_unread(tmp_path: Path) -> None:
    big = tmp_path / "big.yaml"
    big.write_bytes(b"# " + b"x" * MAX_FILE_BYTES + b"\n")
    with pytest.raises(FormFileError, match=f"{big}: larger than {MAX_FILE_BYTES} bytes"):
        read_form(big)
    binary = tmp_path / "binary.yaml"
    binary.write_bytes(b"publish: \xff\xfe\n")
    with pytest.raises(FormFileError, match=f"{binary}: not UTF-8 text"):
        read_form(binary)
    with pytest.raises(FormFileError, match="No such file"):
        read_form(tmp_path / "absent.yaml")
