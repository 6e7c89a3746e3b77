"""Classes from a peer's or a file's definition: built only once the definition hashes to the md5sum declared
with it.  From the wire, never for a type rostui knows itself under another md5sum (rostui's type wins, in
ROS's words); from a bag (``stored``), another version of a type rostui knows is built from the bag's own
definition, privately, as rosbag reads old bags.  Also: arrays of a message type with no fields work, as ROS
allows (``std_msgs/Empty[]``).
"""

from __future__ import annotations

import struct
from typing import Iterator

import pytest

from rostui.core.msg import (
    DefinitionMismatchError,
    Md5MismatchError,
    MessageError,
    clear_cache,
    connection_class,
    definition_md5,
    foreign_version,
    get_message_class,
)
from rostui.core.msg import received

SEP = "\n" + "=" * 80 + "\n"
HEADER_SECTION = SEP + "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
#: An "Image" as a liar describes it: no width, no step.
IMAGE_WITHOUT_WIDTH = "Header header\nuint32 height\nstring encoding\nuint8[] data\n" + HEADER_SECTION


@pytest.fixture(autouse=True)
def fresh_types() -> Iterator[None]:
    """A fresh type store (and cache of received definitions) around each test."""
    clear_cache()
    yield
    clear_cache()


def test_a_known_type_with_its_own_md5_is_decoded_with_rostuis_class_whatever_its_definition_says() -> None:
    image = get_message_class("sensor_msgs/Image")
    assert connection_class("sensor_msgs/Image", image._md5sum, IMAGE_WITHOUT_WIDTH) is image
    assert connection_class("sensor_msgs/Image", image._md5sum, "") is image


def test_a_known_type_under_another_md5_is_refused_in_ros_words() -> None:
    """An "Image" lacking width, its md5sum made to agree with its definition: rostui's Image wins."""
    image = get_message_class("sensor_msgs/Image")
    theirs = definition_md5("sensor_msgs/Image", IMAGE_WITHOUT_WIDTH)
    with pytest.raises(Md5MismatchError) as caught:
        connection_class("sensor_msgs/Image", theirs, IMAGE_WITHOUT_WIDTH, sender="publisher [/liar]")
    assert str(caught.value) == (f"publisher [/liar] has datatype/md5sum [sensor_msgs/Image/{theirs}], "
                                 f"but our version has [sensor_msgs/Image/{image._md5sum}]")


#: An older turtlesim/Pose, as a bag recorded before the velocities were added.
OLD_POSE = "float32 x\nfloat32 y\nfloat32 theta\n"


def test_a_bag_of_another_version_of_a_known_type_is_read_with_its_own_definition() -> None:
    """Before: refused as from the wire ("but our version has"), so old bags could not be read at all."""
    ours = get_message_class("turtlesim/Pose")
    md5 = definition_md5("turtlesim/Pose", OLD_POSE)
    old = connection_class("turtlesim/Pose", md5, OLD_POSE, sender="the connection of /pose", stored=True)
    assert old is not ours and (old._type, old._md5sum) == ("turtlesim/Pose", md5)
    msg = old.deserialize(struct.pack("<fff", 1.0, 2.0, 0.5))
    assert (msg.x, msg.y, msg.theta) == (1.0, 2.0, 0.5) and not hasattr(msg, "linear_velocity")
    # private: rostui's own type is untouched, and the wire still refuses that version
    assert get_message_class("turtlesim/Pose") is ours
    assert connection_class("turtlesim/Pose", ours._md5sum, OLD_POSE, stored=True) is ours
    with pytest.raises(Md5MismatchError, match="but our version has"):
        connection_class("turtlesim/Pose", md5, OLD_POSE)


def test_a_bags_own_version_nests_rostuis_types_where_their_md5sums_agree() -> None:
    image = get_message_class("sensor_msgs/Image")
    theirs = definition_md5("sensor_msgs/Image", IMAGE_WITHOUT_WIDTH)
    old = connection_class("sensor_msgs/Image", theirs, IMAGE_WITHOUT_WIDTH, stored=True)
    assert old is not image and "width" not in old.__slots__
    assert type(old().header) is get_message_class("std_msgs/Header")
    definition = "sensor_msgs/Image picture\n" + SEP + "MSG: sensor_msgs/Image\n" + IMAGE_WITHOUT_WIDTH
    holder = connection_class("z/Holder", definition_md5("z/Holder", definition), definition, stored=True)
    assert holder._field_classes["sensor_msgs/Image"]._md5sum == theirs


def test_a_bags_definition_must_still_hash_to_its_md5sum() -> None:
    image = get_message_class("sensor_msgs/Image")
    with pytest.raises(DefinitionMismatchError, match="but its definition has md5sum"):
        connection_class("sensor_msgs/Image", "0" * 32, IMAGE_WITHOUT_WIDTH, stored=True)
    with pytest.raises(Md5MismatchError, match=f"but our version has \\[sensor_msgs/Image/{image._md5sum}\\]"):
        connection_class("sensor_msgs/Image", "0" * 32, "", stored=True)  # no definition: nothing to read it with
    with pytest.raises(DefinitionMismatchError, match="cannot be checked"):
        connection_class("z/Thing", "*", "int32 a\n", stored=True)


def test_a_class_of_another_version_says_so_in_one_line() -> None:
    image = get_message_class("sensor_msgs/Image")
    theirs = definition_md5("sensor_msgs/Image", IMAGE_WITHOUT_WIDTH)
    old = connection_class("sensor_msgs/Image", theirs, IMAGE_WITHOUT_WIDTH, stored=True)
    assert foreign_version(image) is None and foreign_version(image()) is None
    assert foreign_version(old()) == (f"sensor_msgs/Image here has md5sum {theirs}, not the one rostui knows "
                                      f"({image._md5sum})")
    unknown = connection_class("z/Thing", definition_md5("z/Thing", "int32 a\n"), "int32 a\n")
    assert foreign_version(unknown) == "z/Thing is not a type rostui knows"
    assert foreign_version(object()) == "object is not a message"


def test_a_type_rostui_knows_nested_in_an_unknown_one_must_be_rostuis_too() -> None:
    definition = "sensor_msgs/Image picture\n" + SEP + "MSG: sensor_msgs/Image\n" + IMAGE_WITHOUT_WIDTH
    with pytest.raises(Md5MismatchError, match=r"datatype/md5sum \[sensor_msgs/Image/"):
        connection_class("z/Holder", definition_md5("z/Holder", definition), definition)


def test_a_definition_that_does_not_hash_to_its_declared_md5_is_refused() -> None:
    declared = definition_md5("z/Thing", "int32 b\n")
    with pytest.raises(DefinitionMismatchError) as caught:
        connection_class("z/Thing", declared, "int32 a\n", sender="publisher [/liar]")
    text = str(caught.value)
    assert "\n" not in text and declared in text and definition_md5("z/Thing", "int32 a\n") in text


def test_an_unknown_type_whose_definition_hashes_to_its_md5_is_built() -> None:
    definition = "Header header\nz/Inner[] items\nInner pair\n" + HEADER_SECTION + SEP + "MSG: z/Inner\nfloat32 v\n"
    md5 = definition_md5("z/Outer", definition)
    outer = connection_class("z/Outer", md5, definition)
    assert outer._md5sum == md5 and outer._type == "z/Outer"
    inner = outer._field_classes["z/Inner"]
    msg = outer(items=[inner(v=1.5)], pair=inner(v=2.0))
    assert outer.deserialize(msg.serialize()) == msg
    assert connection_class("z/Outer", md5, definition) is outer


@pytest.mark.parametrize("md5", ["*", ""])
def test_no_md5_means_rostuis_class_for_a_known_type_and_no_class_for_an_unknown_one(md5: str) -> None:
    assert connection_class("std_msgs/String", md5, "int64 data\n") is get_message_class("std_msgs/String")
    with pytest.raises(DefinitionMismatchError, match="cannot be checked"):
        connection_class("z/Thing", md5, "int32 a\n")


def test_an_unknown_type_without_a_definition_is_unknown() -> None:
    with pytest.raises(MessageError, match=r"unknown message type \[z/Thing\]"):
        connection_class("z/Thing", "0123456789abcdef0123456789abcdef", "")


def test_a_peers_md5_is_shown_on_one_line() -> None:
    with pytest.raises(Md5MismatchError) as caught:
        connection_class("std_msgs/String", "abc\nFAKE LINE", "")
    assert "\n" not in str(caught.value)


def test_a_refusal_is_remembered_not_worked_out_again(monkeypatch: pytest.MonkeyPatch) -> None:
    """A publisher repeats its header with every message: its definition is parsed once, not per message."""
    parsed: list[str] = []
    real = received.split_definition

    def counting(type_name: str, definition: str) -> list:  # type: ignore[type-arg]
        parsed.append(type_name)
        return real(type_name, definition)
    monkeypatch.setattr(received, "split_definition", counting)
    for _ in range(3):
        with pytest.raises(DefinitionMismatchError):
            connection_class("z/Thing", "0" * 32, "int32 a\n")
    assert parsed == ["z/Thing"]


def test_an_array_of_an_empty_message_type_round_trips() -> None:
    """ROS allows ``std_msgs/Empty[]``; its class could not be generated ("cannot generate its class")."""
    empty = get_message_class("std_msgs/Empty")
    definition = "std_msgs/Empty[] many\nstd_msgs/Empty[3] few\nint32 after\n" + SEP + "MSG: std_msgs/Empty\n"
    holder = connection_class("z/Holder", definition_md5("z/Holder", definition), definition)
    msg = holder(many=[empty(), empty()], after=7)
    data = msg.serialize()
    assert data == struct.pack("<Ii", 2, 7)
    back = holder.deserialize(data)
    assert (len(back.many), len(back.few), back.after) == (2, 3, 7)
    assert all(isinstance(e, empty) for e in back.many + back.few)
