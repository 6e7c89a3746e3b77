"""The cache of compiled message code (rostui/core/msg/codecache.py): used, never stale, never in the way.

A class built twice compiles once; a changed definition compiles again and gets its own fields; an entry
that is garbage, cut short or not code is ignored and replaced; a folder that cannot be made leaves every
build as it was; the folder keeps a bounded number of entries. A rospy script under `rostui python` keeps
its cache under its (here temporary) ROS_HOME and still runs when every entry there is garbage.
"""

from __future__ import annotations

import subprocess
import types
from collections.abc import Iterator
from pathlib import Path

import pytest

from conftest import rostui_cmd
from rostui.core.msg import TypeStore, codecache, parse_msg_text


@pytest.fixture
def cache(tmp_path: Path) -> Iterator[Path]:
    """The cache on, in a temporary folder; off again afterwards."""
    codecache.use_directory(tmp_path / "cache")
    folder = codecache.directory()
    assert folder is not None
    yield folder
    codecache.use_directory(None)


@pytest.fixture
def compiles(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The file names the cache compiles (the source it had no entry for)."""
    seen: list[str] = []
    real = compile

    def counting(source: str, filename: str, mode: str) -> types.CodeType:
        seen.append(filename)
        return real(source, filename, mode)

    monkeypatch.setattr(codecache, "compile", counting, raising=False)
    return seen


def _store(text: str, type_name: str = "demo_msgs/Thing") -> TypeStore:
    store = TypeStore(load_from_packages=False)
    store.add_spec(parse_msg_text(text, type_name))
    return store


def _entries(folder: Path) -> list[Path]:
    return sorted(folder.glob("*.code"))


def test_a_class_built_again_is_not_compiled_again(cache: Path, compiles: list[str]) -> None:
    first = _store("int32 a\nstring b\n").get_class("demo_msgs/Thing")
    assert compiles == ["<rostui msg demo_msgs/Thing>"] and len(_entries(cache)) == 1
    second = _store("int32 a\nstring b\n").get_class("demo_msgs/Thing")
    assert compiles == ["<rostui msg demo_msgs/Thing>"]
    msg = second(a=7, b="x")
    assert first.deserialize(msg.serialize()).b == "x" and second._md5sum == first._md5sum


def test_a_changed_definition_never_gets_the_old_code(cache: Path, compiles: list[str]) -> None:
    old = _store("int32 a\n").get_class("demo_msgs/Thing")
    new = _store("int32 a\nfloat64 c\n").get_class("demo_msgs/Thing")
    assert len(compiles) == 2 and len(_entries(cache)) == 2
    assert new.__slots__ == ["a", "c"] and old.__slots__ == ["a"]
    assert new.deserialize(new(a=1, c=2.5).serialize()).c == 2.5
    renamed = _store("int32 a\n", "demo_msgs/Other").get_class("demo_msgs/Other")  # same text, another type
    assert len(compiles) == 3 and renamed._type == "demo_msgs/Other"


@pytest.mark.parametrize("damage", ["garbage", "cut", "flipped", "empty", "not-code", "huge"])
def test_a_damaged_entry_is_ignored_and_replaced(cache: Path, compiles: list[str], damage: str) -> None:
    _store("int32 a\nstring b\n").get_class("demo_msgs/Thing")
    (entry,) = _entries(cache)
    data = entry.read_bytes()
    if damage == "garbage":
        entry.write_bytes(b"\x00\xff not a cache entry" * 50)
    elif damage == "cut":
        entry.write_bytes(data[: len(data) // 2])
    elif damage == "flipped":
        entry.write_bytes(data[:-5] + bytes([data[-5] ^ 0x55]) + data[-4:])
    elif damage == "empty":
        entry.write_bytes(b"")
    elif damage == "not-code":  # a whole entry, checksum and all, that holds something else
        import marshal

        from rostui.core.msg.codecache import _MAGIC, md5

        payload = marshal.dumps({"not": "code"})
        entry.write_bytes(_MAGIC + md5(payload).digest() + payload)
    else:
        entry.write_bytes(b"x" * (codecache.MAX_ENTRY_BYTES + 10))
    cls = _store("int32 a\nstring b\n").get_class("demo_msgs/Thing")
    assert cls.deserialize(cls(a=3, b="y").serialize()).a == 3
    assert len(compiles) == 2
    assert entry.read_bytes() == data  # rewritten whole
    _store("int32 a\nstring b\n").get_class("demo_msgs/Thing")
    assert len(compiles) == 2


def test_a_folder_that_cannot_be_made_changes_nothing(tmp_path: Path, compiles: list[str]) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    codecache.use_directory(blocker / "cache")
    try:
        for _ in range(2):
            cls = _store("int32 a\n").get_class("demo_msgs/Thing")
            assert cls.deserialize(cls(a=5).serialize()).a == 5
    finally:
        codecache.use_directory(None)
    assert len(compiles) == 2 and blocker.read_text() == "not a folder"
    assert not list(tmp_path.glob("**/*.tmp"))


def test_the_folder_keeps_a_bounded_number_of_entries(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(codecache, "MAX_ENTRIES", 8)
    for n in range(20):
        _store(f"int32 a\nint32[{n + 1}] b\n").get_class("demo_msgs/Thing")
    assert 0 < len(_entries(cache)) <= 8
    assert not list(cache.glob("*.tmp"))


def test_off_by_default_and_where_it_goes(tmp_path: Path) -> None:
    assert codecache.directory() is None
    assert codecache.default_directory({"ROS_HOME": str(tmp_path)}) == tmp_path / "rostui" / "msg_code"
    assert codecache.default_directory({"ROS_HOME": str(tmp_path), codecache.ENV_CACHE: "off"}) is None
    assert codecache.default_directory({codecache.ENV_CACHE: str(tmp_path / "c")}) == tmp_path / "c"


SCRIPT = """\
import rospy
from std_msgs.msg import String
from rostui.core.msg import codecache
print(codecache.directory())
print(String.deserialize(String(data="hi").serialize()).data)
"""


def test_a_script_keeps_its_cache_under_ros_home(ros_env: dict[str, str], tmp_path: Path) -> None:
    script = tmp_path / "script.py"
    script.write_text(SCRIPT)
    home = Path(ros_env["ROS_HOME"])
    env = {k: v for k, v in ros_env.items() if k != codecache.ENV_CACHE}
    first = subprocess.run(rostui_cmd("python", str(script)), env=env, capture_output=True, text=True, timeout=120)
    assert first.returncode == 0, first.stderr
    where, said = first.stdout.splitlines()
    assert Path(where).parent == home / "rostui" / "msg_code" and said == "hi"
    entries = list(Path(where).glob("*.code"))
    assert entries
    for entry in entries:
        entry.write_bytes(b"garbage")
    again = subprocess.run(rostui_cmd("python", str(script)), env=env, capture_output=True, text=True, timeout=120)
    assert again.returncode == 0 and again.stdout.splitlines()[1] == "hi", again.stderr
    assert all(entry.read_bytes() != b"garbage" for entry in entries)
