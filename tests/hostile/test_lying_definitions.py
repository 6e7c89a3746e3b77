"""A publisher that lies in its connection header, against the subscribers that decode any type from it.

`rostui topic echo`, the monitor and the views subscribe with md5sum ``*`` and decode each message with the
class its publisher's header describes.  The publisher here (tests/hostile/lying_publisher.py, raw TCPROS on
threads of this test) declares:

- ``bomb``: a type rostui does not know, whose definition nests a fixed ``Z[1000000]`` of a tiny type in an
  array, its md5sum made to agree: a 20-byte message asks for a thousand million objects (2.5 GB in 25 s
  before the element budget; Debian's rostopic echo: "Cannot load message class");
- ``bomb as String``: the same definition, with its md5sum, declared as ``std_msgs/String``: rostui's String
  wins (Debian's rostopic echo decodes with its own String too);
- ``md5 that lies``: the bomb under a type rostui does not know, with an md5sum its definition does not hash to;
- ``Image without width`` (in-process): ``sensor_msgs/Image`` lacking ``width``, its md5sum made to agree: the
  views read ``width`` and crashed with AttributeError.

Against rostui the tests assert what a user sees: one line naming the lie, memory flat, and a legitimate
publisher on another topic still echoed (the in-process one still decoded).  Debian's ``rostopic echo`` meets
the same publisher; its figures and what it printed are recorded, never asserted.
"""

from __future__ import annotations

import asyncio
import os
import struct
import time
from typing import Any, Iterator

import pytest

from conftest import rostui_cmd, until, wait_until
from hostile_helpers import MB, RssSampler, record
from interop_helpers import Peer, Spawn, need_command, spawn  # noqa: F401  (spawn is a fixture)
from lying_publisher import SEPARATOR, LyingPublisher, md5_of_text
from rostui.core.msg import MessageError, get_message_class

#: Peak RSS growth allowed to a rostui subscriber under attack (the bomb took 2.5 GB).
GROWTH_LIMIT_MB = 100
#: A safety net only: the victim's address space, so a regression fails the test, not the machine.
VICTIM_ADDRESS_SPACE = 2_000_000_000

STRING_TEXT = "string data\n"


def bomb_definition(package: str) -> tuple[str, str]:
    """``Outer[] o`` of ``Z[1000000] z`` of ``uint8[0] x`` in ``package``, and the md5sum it hashes to."""
    z = md5_of_text("uint8[0] x")
    outer = md5_of_text(f"{z} z")
    top = md5_of_text(f"{outer} o")
    return ("Outer[] o" + SEPARATOR + f"MSG: {package}/Outer\nZ[1000000] z" + SEPARATOR
            + f"MSG: {package}/Z\nuint8[0] x\n"), top


def image_without_width() -> tuple[str, str]:
    """A ``sensor_msgs/Image`` definition lacking ``width`` (and ``step``), and the md5sum it hashes to."""
    header = md5_of_text("uint32 seq\ntime stamp\nstring frame_id")
    own = "Header header\nuint32 height\nstring encoding\nuint8 is_bigendian\nuint8[] data\n"
    md5 = md5_of_text(f"{header} header\nuint32 height\nstring encoding\nuint8 is_bigendian\nuint8[] data")
    return own + SEPARATOR + "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n", md5


def bomb_frame(outers: int) -> bytes:
    """A message of the bomb: ``outers`` elements of ``Outer``, padded to 20 bytes."""
    return struct.pack("<I", outers) + bytes(16)


def lie(name: str, outers: int = 1000) -> dict[str, Any]:
    """The header fields and frame of the lie called ``name``, and the words the refusal must hold."""
    if name == "bomb":
        definition, md5 = bomb_definition("evil_pkg")
        return {"type_name": "evil_pkg/Bomb", "md5sum": md5, "definition": definition,
                "frame": bomb_frame(outers), "words": "decoding budget"}
    if name == "bomb as String":
        definition, md5 = bomb_definition("std_msgs")
        return {"type_name": "std_msgs/String", "md5sum": md5, "definition": definition,
                "frame": bomb_frame(outers), "words": "but our version has [std_msgs/String/"}
    if name == "md5 that lies":
        definition, _ = bomb_definition("evil_pkg")
        return {"type_name": "evil_pkg/Bomb", "md5sum": md5_of_text("int32 a"), "definition": definition,
                "frame": bomb_frame(outers), "words": "but its definition has md5sum"}
    assert name == "Image without width"
    definition, md5 = image_without_width()
    frame = struct.pack("<III", 0, 0, 0) + struct.pack("<I", 0) + struct.pack("<I", 2) + struct.pack("<I", 4) \
        + b"mono" + b"\0" + struct.pack("<I", 4) + bytes(4)
    return {"type_name": "sensor_msgs/Image", "md5sum": md5, "definition": definition, "frame": frame,
            "words": "but our version has [sensor_msgs/Image/"}


def honest_publisher(master: str) -> LyingPublisher:
    """A raw publisher that tells the truth: std_msgs/String "hello" on /good at 20 Hz."""
    string = get_message_class("std_msgs/String")
    return LyingPublisher(master, "/good", "std_msgs/String", string._md5sum, STRING_TEXT,
                          string(data="hello").serialize(), callerid="/honest")


@pytest.fixture(params=["rostui", "debian"])
def echo_tool(request: pytest.FixtureRequest) -> str:
    """Whose ``topic echo`` meets the liar: rostui's (asserted) or Debian's rostopic (recorded)."""
    if request.param == "debian":
        need_command("rostopic")
    return str(request.param)


@pytest.mark.parametrize("name", ["bomb", "bomb as String", "md5 that lies"])
def test_topic_echo_refuses_a_lying_publisher(name: str, echo_tool: str, rostui_core: Any,
                                              ros_env: dict[str, str], spawn: Spawn) -> None:
    """`rostui topic echo` says in one line what the publisher lied about and ends; `echo /good` goes on."""
    master = ros_env["ROS_MASTER_URI"]
    told = lie(name)
    words = told.pop("words")
    with honest_publisher(master), LyingPublisher(master, "/evil", **told) as liar:
        good = spawn(rostui_cmd("topic", "echo", "/good"), label="echo /good")
        good.wait_for(r"^data: \"?hello")
        echo = ["rostopic", "echo", "/evil"] if echo_tool == "debian" else rostui_cmd("topic", "echo", "/evil")
        started = time.monotonic()
        victim = spawn(["prlimit", f"--as={VICTIM_ADDRESS_SPACE}", "--", *echo], label=f"{echo_tool} echo /evil")
        with RssSampler(victim.proc.pid) as rss:
            # rostui's echo ends at the first lying message; Debian's runs on while it decodes, or ends at once
            wait_until(lambda: victim.proc.poll() is not None or liar.frames_sent >= 40,
                       lambda: f"the victim to end or take 40 frames\n{victim.describe()}", timeout=120)
            ended = victim.proc.poll()
            seconds = time.monotonic() - started
        good_before = good.output.count("---")
        wait_until(lambda: good.output.count("---") > good_before + 2, "echo /good to print three more messages")
    printed = victim.output.splitlines()
    record(f"topic echo of a lying publisher: {name}", echo_tool, peak_rss_mb=round(rss.peak / MB, 1),
           peak_rss_growth_mb=round(rss.growth_mb, 1), exit_code=ended, seconds=round(seconds, 2),
           frames_sent=liar.frames_sent, lines=len(printed), first_lines=printed[:3])
    if echo_tool != "rostui":
        return
    assert ended is not None and ended != 0, victim.describe()
    assert len(printed) == 1 and words in printed[0] and "Traceback" not in victim.output, victim.describe()
    assert rss.growth_mb < GROWTH_LIMIT_MB, f"peak RSS grew {rss.growth_mb:.1f} MB"


@pytest.fixture
def monitor(ros_env: dict[str, str], rostui_core: Any) -> Iterator[tuple[asyncio.AbstractEventLoop, Any]]:
    """The monitor's source in this process (its own event loop), wanting /evil and /good."""
    from rostui.models.monitor.source import MonitorSource

    loop = asyncio.new_event_loop()
    source = MonitorSource(ros_env["ROS_MASTER_URI"], period=0.2)
    task = loop.create_task(source.run())
    source.want({"/evil", "/good"})
    yield loop, source
    loop.run_until_complete(source.stop())
    task.cancel()
    loop.run_until_complete(asyncio.gather(task, return_exceptions=True))
    loop.close()


#: Outers in the in-process bomb: before the budget it took about 300 MB of this test's own process.
IN_PROCESS_OUTERS = 6


@pytest.mark.parametrize("name", ["bomb", "bomb as String", "md5 that lies", "Image without width"])
def test_in_process_subscription_refuses_a_lying_publisher(name: str, ros_env: dict[str, str],
                                                           monitor: tuple[asyncio.AbstractEventLoop, Any]) -> None:
    """The path the monitor and the views decode on: one MessageError line per lying message, memory flat,
    the honest topic beside it still decoded."""
    loop, source = monitor
    master = ros_env["ROS_MASTER_URI"]
    told = lie(name, outers=IN_PROCESS_OUTERS)
    words = told.pop("words")
    refusals: list[str] = []

    def try_evil() -> bool:
        try:
            source.latest("/evil")
        except MessageError as exc:
            refusals.append(str(exc))
        return len(refusals) >= 3

    async def attack() -> None:
        await until(lambda: source.latest("/good") is not None, "the honest topic to be decoded")
        await until(try_evil, "three lying messages to be refused")
        await until(lambda: source.latest("/good").data == "hello" and source.stats("/good").messages > 10,
                    "the honest topic to go on")

    with honest_publisher(master), LyingPublisher(master, "/evil", **told) as liar:
        with RssSampler(os.getpid()) as rss:
            loop.run_until_complete(attack())
    record(f"in-process subscription to a lying publisher: {name}", "rostui", peak_rss_mb=round(rss.peak / MB, 1),
           peak_rss_growth_mb=round(rss.growth_mb, 1), frames_sent=liar.frames_sent, refusal=refusals[0])
    assert all(words in text and "\n" not in text for text in refusals), refusals[0]
    assert rss.growth_mb < GROWTH_LIMIT_MB, f"peak RSS grew {rss.growth_mb:.1f} MB"
