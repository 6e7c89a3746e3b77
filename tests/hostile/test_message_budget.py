"""The decoding budget of generated message classes: what a message may decode is tied to the bytes it came in.

A definition can make a few bytes decode into millions of objects: an array of a type that takes no bytes
(``Z[]`` with ``Z`` empty, or a fixed ``Z[1000000]`` inside an array), or of a type whose fields mostly take
none.  The issue's message, ``Outer[1000]`` of ``Z[1000000]`` in 20 bytes, took 1.5 GB (genpy does the same).
Each shape is decoded in a child process capped at 1.5 GB of address space (so a regression fails the test,
not the machine); the child reports what ``deserialize`` raised and how far its peak RSS rose.
"""

from __future__ import annotations

import json
import struct
import subprocess
import sys
import textwrap
from typing import Any

import pytest

from hostile_helpers import record

SEP = "\n" + "=" * 80 + "\n"
GROWTH_LIMIT_MB = 50

CHILD = textwrap.dedent("""
    import json, resource, sys
    from rostui.core.msg import TypeStore
    from rostui.core.msg.registry import split_definition

    type_name, definition, frame = sys.argv[1], sys.argv[2], sys.stdin.buffer.read()
    resource.setrlimit(resource.RLIMIT_AS, (1500 << 20, 1500 << 20))
    store = TypeStore(load_from_packages=False)
    for spec in split_definition(type_name, definition):
        store.add_spec(spec)
    cls = store.get_class(type_name)
    def peak_kb():  # VmHWM: this program's own peak (ru_maxrss would start at the parent's, hiding any growth)
        with open("/proc/self/status") as status:
            return next(int(line.split()[1]) for line in status if line.startswith("VmHWM:"))

    before = peak_kb()
    try:
        msg = cls.deserialize(frame)
        error = None
    except Exception as exc:
        msg, error = None, f"{type(exc).__name__}: {exc}"
    after = peak_kb()
    print(json.dumps({"error": error, "growth_mb": (after - before) / 1024}))
""")


def decode_in_child(type_name: str, definition: str, frame: bytes) -> dict[str, Any]:
    """What decoding ``frame`` as ``type_name`` (built from ``definition``) raised, and its peak RSS growth."""
    done = subprocess.run([sys.executable, "-c", CHILD, type_name, definition], input=frame,
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:].decode(errors="replace")
    result: dict[str, Any] = json.loads(done.stdout)
    return result


#: Empty and (nearly) empty element types, named as the definitions below use them.
TINY = SEP + "MSG: z/Z\nuint8[0] pad\n"
EMPTY = SEP + "MSG: z/E\n"

BOMBS = {
    # the issue's: Outer[1000] of Z[1000000], Z a tiny type, in 20 bytes
    "fixed arrays of a tiny type in an array": (
        "Outer[] o" + SEP + "MSG: z/Outer\nZ[1000000] z" + TINY, struct.pack("<I", 1000) + bytes(16)),
    "fixed arrays of an empty type in an array": (
        "Outer[] o" + SEP + "MSG: z/Outer\nE[1000000] z" + EMPTY, struct.pack("<I", 1000) + bytes(16)),
    "an array of an empty type, a million long in 4 bytes": ("E[] e" + EMPTY, struct.pack("<I", 1 << 20)),
    "four arrays of a million empty elements in 20 bytes": (
        "A[] a" + SEP + "MSG: z/A\nE[] e" + EMPTY, struct.pack("<5I", 4, *[1 << 20] * 4)),
    "a one-byte element holding 200 empty fields": (
        "W[] w" + SEP + "MSG: z/W\nuint8 a\n" + "".join(f"E e{i}\n" for i in range(200)) + EMPTY,
        struct.pack("<I", 1 << 20) + bytes(1 << 20)),
}


@pytest.mark.parametrize("shape", list(BOMBS))
def test_a_message_decodes_no_more_than_its_bytes_pay_for(shape: str) -> None:
    """Refused with the deserialisation error, in one line naming the budget, with memory flat."""
    definition, frame = BOMBS[shape]
    result = decode_in_child("z/Top", definition, frame)
    record("message budget: " + shape, "rostui", frame_bytes=len(frame), **result)
    assert result["error"] is not None and result["error"].startswith("DeserializationError: z/Top: ")
    assert "budget" in result["error"] and "\n" not in result["error"]
    assert result["growth_mb"] < GROWTH_LIMIT_MB, result


LEGIT = {
    "a thousand std_msgs/Empty in 4 bytes": ("E[] e" + EMPTY, struct.pack("<I", 1000)),
    "100000 points": ("geometry_msgs/Point32[] p" + SEP + "MSG: geometry_msgs/Point32\nfloat32 x\nfloat32 y\nfloat32 z\n",
                      struct.pack("<I", 100_000) + bytes(12 * 100_000)),
    "a million bools": ("bool[] b", struct.pack("<I", 1 << 20) + bytes(1 << 20)),
    "a million std_msgs/Bool": ("std_msgs/Bool[] b" + SEP + "MSG: std_msgs/Bool\nbool data\n",
                                struct.pack("<I", 1 << 20) + bytes(1 << 20)),
    "a million colours of three bytes": ("C[] c" + SEP + "MSG: z/C\nuint8 r\nuint8 g\nuint8 b\n",
                                         struct.pack("<I", 1 << 20) + bytes(3 << 20)),
}


@pytest.mark.parametrize("shape", list(LEGIT))
def test_legitimate_messages_stay_within_the_budget(shape: str) -> None:
    definition, frame = LEGIT[shape]
    assert decode_in_child("z/Top", definition, frame)["error"] is None
