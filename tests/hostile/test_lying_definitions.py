"""Publishers that lie in their connection header, beside honest publishers that must still be heard.

`rostui topic echo`, the monitor and the views subscribe with md5sum ``*``.  The liar here
(tests/hostile/lying_publisher.py, raw TCPROS on threads of this test) declares:

- ``bomb``: a type rostui does not know, whose definition nests a fixed ``Z[1000000]`` of a tiny type in an
  array, its md5sum made to agree: a 20-byte message asks for a thousand million objects (2.5 GB in 25 s
  before the element budget; Debian's rostopic echo: "Cannot load message class");
- ``bomb as String``: the same definition, with its md5sum, declared as ``std_msgs/String``: another version of
  a type rostui knows, refused as ROS refuses it;
- ``md5 that lies``: the bomb under a type rostui does not know, with an md5sum its definition does not hash to;
- ``Image without width``: ``sensor_msgs/Image`` lacking ``width``, its md5sum made to agree (the views read
  ``width`` and crashed with AttributeError);
- ``evil/Image`` (views): told the master sensor_msgs/Image, its header says evil/Image with Image's own text.

A liar whose header is refused loses its connection and is not asked again; one line says why; the honest
publisher of the same topic is still echoed, decoded and drawn.  Memory is sampled.  Debian's ``rostopic echo``
meets the same publishers; its figures and what it printed are recorded, never asserted.
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
from rostui.core.msg import MessageError, definition_md5, get_message_class

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


def honest_publisher(master: str, topic: str = "/good") -> LyingPublisher:
    """A raw publisher that tells the truth: std_msgs/String "hello" on ``topic`` at 20 Hz."""
    string = get_message_class("std_msgs/String")
    return LyingPublisher(master, topic, "std_msgs/String", string._md5sum, STRING_TEXT,
                          string(data="hello").serialize(), callerid="/honest")


@pytest.fixture(params=["rostui", "debian"])
def echo_tool(request: pytest.FixtureRequest) -> str:
    """Whose ``topic echo`` meets the liar: rostui's (asserted) or Debian's rostopic (recorded)."""
    if request.param == "debian":
        need_command("rostopic")
    return str(request.param)


#: Honest messages the echo must print after the liar was refused.
HONEST_AFTER = 10


@pytest.mark.parametrize("name", ["bomb", "bomb as String", "md5 that lies"])
def test_topic_echo_refuses_a_liar_and_keeps_the_honest_publisher(name: str, echo_tool: str, rostui_core: Any,
                                                                  ros_env: dict[str, str], spawn: Spawn) -> None:
    """A liar and an honest publisher on one topic.  `rostui topic echo` says once, in one line, what the liar
    lied about and goes on printing the honest one's messages; a liar refused for its header loses its connection
    and is not asked again.  (It ended at the first lie: one liar silenced every honest publisher of the topic.)"""
    master = ros_env["ROS_MASTER_URI"]
    told = lie(name)
    words = told.pop("words")
    header_refused = name != "bomb"  # the bomb's header is true: its messages are what fails
    with honest_publisher(master, "/chatter"), LyingPublisher(master, "/chatter", **told) as liar:
        echo = ["rostopic", "echo", "/chatter"] if echo_tool == "debian" else rostui_cmd("topic", "echo", "/chatter")
        started = time.monotonic()
        victim = spawn(["prlimit", f"--as={VICTIM_ADDRESS_SPACE}", "--", *echo], label=f"{echo_tool} echo /chatter")
        with RssSampler(victim.proc.pid) as rss:
            wait_until(lambda: victim.proc.poll() is not None or (liar.connections >= 1 and victim.count("hello") > 0),
                       lambda: f"the victim to meet both publishers\n{victim.describe()}", timeout=120)
            heard = victim.count("hello")
            wait_until(lambda: victim.proc.poll() is not None or victim.count("hello") >= heard + HONEST_AFTER,
                       lambda: f"{HONEST_AFTER} more honest messages\n{victim.describe()}", timeout=120)
            alive = victim.proc.poll() is None
            seconds = time.monotonic() - started
    others = [line for line in victim.output.splitlines() if line != "---" and not line.startswith("data:")]
    record(f"topic echo of a liar beside an honest publisher: {name}", echo_tool,
           peak_rss_mb=round(rss.peak / MB, 1), peak_rss_growth_mb=round(rss.growth_mb, 1), alive=alive,
           seconds=round(seconds, 2), honest_printed=victim.count("hello"), liar_connections=liar.connections,
           frames_sent=liar.frames_sent, other_lines=len(others), first_other_lines=others[:3])
    if echo_tool != "rostui":
        return
    assert alive, victim.describe()
    assert len(others) == 1 and words in others[0] and "Traceback" not in victim.output, victim.describe()
    if header_refused:
        assert others[0].startswith("ERROR: refused a publisher of /chatter: publisher [/liar] "), others[0]
        assert liar.connections == 1, "the refused liar was asked again"
    else:
        assert others[0].startswith("ERROR: cannot decode messages on /chatter from publisher [/liar]: "), others[0]
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
def test_in_process_subscription_refuses_a_liar_and_keeps_the_honest_publisher(
        name: str, ros_env: dict[str, str], monitor: tuple[asyncio.AbstractEventLoop, Any]) -> None:
    """The monitor's source, a liar and an honest publisher on one topic: a lying header is refused once (one line
    in the topic's refusals, its connection dropped), lying messages are one MessageError line each; memory flat;
    the honest publisher's messages are still decoded."""
    loop, source = monitor
    master = ros_env["ROS_MASTER_URI"]
    told = lie(name, outers=IN_PROCESS_OUTERS)
    words = told.pop("words")
    header_refused = name != "bomb"
    refusals: list[str] = []
    honest: list[str] = []

    def look() -> None:
        try:
            msg = source.latest("/evil")
        except MessageError as exc:
            refusals.append(str(exc))
            return
        if msg is not None:
            honest.append(msg.data)

    async def attack() -> None:
        await until(lambda: source.stats("/evil") is not None and source.stats("/evil").messages > 0,
                    "messages on /evil")
        if header_refused:
            await until(lambda: source.refusals("/evil"), "the liar refused")
            refusals.extend(source.refusals("/evil"))
        else:
            await until(lambda: (look(), len(refusals) >= 3)[1], "three lying messages to be refused")
        counted = source.stats("/evil").messages
        await until(lambda: (look(), source.stats("/evil").messages > counted + 10 and "hello" in honest)[1],
                    "the honest publisher to go on")

    with honest_publisher(master, "/evil"), LyingPublisher(master, "/evil", **told) as liar:
        with RssSampler(os.getpid()) as rss:
            loop.run_until_complete(attack())
        connections = liar.connections
    record(f"in-process subscription to a liar beside an honest publisher: {name}", "rostui",
           peak_rss_mb=round(rss.peak / MB, 1), peak_rss_growth_mb=round(rss.growth_mb, 1),
           frames_sent=liar.frames_sent, liar_connections=connections, refusal=refusals[0])
    assert all(words in text and "\n" not in text for text in refusals), refusals[0]
    assert set(honest) == {"hello"}
    if header_refused:
        assert source.refusals("/evil") == refusals[:1] and refusals[0].startswith("publisher [/liar] "), refusals
        assert connections == 1, "the refused liar was asked again"
    assert rss.growth_mb < GROWTH_LIMIT_MB, f"peak RSS grew {rss.growth_mb:.1f} MB"


# ------------------------------------------------------------------------------- the views and the monitor's screen

def image_frame(frame_id: str, rgb: tuple[int, int, int]) -> bytes:
    """A 4 x 2 rgb8 sensor_msgs/Image of one colour, its header's frame_id ``frame_id``."""
    image = get_message_class("sensor_msgs/Image")
    msg = image(height=2, width=4, encoding="rgb8", step=12, data=bytes(rgb) * 8)
    msg.header.frame_id = frame_id
    return bytes(msg.serialize())


def honest_camera(master: str) -> LyingPublisher:
    """A raw publisher that tells the truth: a green sensor_msgs/Image (frame "honest") on /camera at 20 Hz."""
    image = get_message_class("sensor_msgs/Image")
    return LyingPublisher(master, "/camera", "sensor_msgs/Image", image._md5sum, image._full_text,
                          image_frame("honest", (0, 255, 0)), callerid="/honest")


def camera_liar(master: str, name: str) -> LyingPublisher:
    """A liar the master knows as a sensor_msgs/Image publisher of /camera.

    ``evil/Image``: its header says type evil/Image with Image's own definition (so its md5sum is Image's) and it
    sends red images; ``Image without width``: its header says sensor_msgs/Image with the width-less definition,
    its md5sum made to agree.
    """
    image = get_message_class("sensor_msgs/Image")
    if name == "evil/Image":
        return LyingPublisher(master, "/camera", "evil/Image", image._md5sum, image._full_text,
                              image_frame("liar", (255, 0, 0)), registered_type="sensor_msgs/Image")
    told = lie("Image without width")
    told.pop("words")
    return LyingPublisher(master, "/camera", registered_type="sensor_msgs/Image", **told)


@pytest.fixture
def halfblock(monkeypatch: pytest.MonkeyPatch) -> None:
    """Half blocks, as on a terminal without graphics."""
    from rostui.apps.view.image_view import GRAPHICS_ENV

    monkeypatch.setenv(GRAPHICS_ENV, "halfblock")


@pytest.mark.parametrize("name", ["evil/Image", "Image without width"])
def test_view_refuses_a_liar_and_keeps_drawing_the_honest_camera(name: str, rostui_core: Any, ros_env: dict[str, str],
                                                                 halfblock: None) -> None:
    """The view picks its Image panel from the master's type; the liar told the master sensor_msgs/Image but its
    header says otherwise.  The panel refuses it in one line and draws only the honest camera.  (It drew the liar's
    evil/Image frames among the honest ones; the width-less one's frames, refused one by one, took the honest
    frames' turn; before the definition check it died on their ``msg.width``.)"""
    from rostui.apps.view.app import ViewApp
    from rostui.apps.view.image_view import ImageView

    master = ros_env["ROS_MASTER_URI"]
    drawn_from: set[str] = set()

    async def main() -> None:
        app = ViewApp(["/camera"], master_uri=master, period=0.3)
        async with app.run_test(size=(80, 24)) as pilot:
            panel = app.grid.panels[0]

            def watch() -> bool:
                last = getattr(panel.view, "_last", None)
                if last is not None:
                    drawn_from.add(str(last[0].header.frame_id))
                return True

            await until(lambda: watch() and isinstance(panel.view, ImageView) and panel.view.drawn.count >= 1,
                        "the camera drawn")
            await until(lambda: watch() and panel.refused_line.display, "the liar refused")
            view = panel.view
            assert isinstance(view, ImageView)
            drawn = view.drawn.count
            await until(lambda: watch() and view.drawn.count >= drawn + 10, "ten more honest frames drawn")
            await pilot.pause()
            line = str(panel.refused_line.render())
            assert line.startswith("refused publisher [/liar] has datatype/md5sum [") and "\n" not in line, line
            assert line.endswith(f"not [sensor_msgs/Image/{get_message_class('sensor_msgs/Image')._md5sum}]: "
                                 "its messages are not drawn"), line
            assert not panel.note.display or "cannot decode" not in str(panel.note.render())
            await app.action_quit()

    with honest_camera(master), camera_liar(master, name) as liar:
        asyncio.run(main())
        connections = liar.connections
    assert drawn_from == {"honest"}, drawn_from
    assert connections == 1, "the refused liar was asked again"


def test_monitor_shows_a_refused_liar_in_one_line_and_keeps_the_honest_camera(rostui_core: Any,
                                                                             ros_env: dict[str, str],
                                                                             halfblock: None) -> None:
    """The monitor's tree of /camera and its view (Enter) beside a publisher of a width-less sensor_msgs/Image:
    one line each, the honest camera's message in the tree and its frames in the view, no traceback."""
    from textual.pilot import Pilot

    from monitor_helpers import run_monitor
    from rostui.apps.monitor.app import MonitorApp
    from rostui.apps.view.app import ViewScreen
    from rostui.apps.view.image_view import ImageView

    master = ros_env["ROS_MASTER_URI"]
    image = get_message_class("sensor_msgs/Image")

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await until(lambda: app.topic_type("/camera") == "sensor_msgs/Image", "the camera listed")
        app.toggle_expanded("/camera")
        label = lambda: str(app.message_trees.topic_node("/camera").label)  # noqa: E731
        await until(lambda: "✖ refused publisher [/liar]" in label() and app.source.latest("/camera") is not None,
                    lambda: f"the liar refused and the honest camera heard: {label()}")
        assert f"but our version has [sensor_msgs/Image/{image._md5sum}]" in label() and "\n" not in label()
        assert app.source.latest("/camera").header.frame_id == "honest"
        app.toggle_expanded("/camera")
        assert app.open_view("/camera") and isinstance(app.screen, ViewScreen)
        panel = app.screen.grid.panels[0]
        await until(lambda: isinstance(panel.view, ImageView) and panel.view.drawn.count >= 3
                    and panel.refused_line.display, "the honest camera drawn and the liar refused in the view")
        await pilot.press("escape")

    with honest_camera(master), camera_liar(master, "Image without width"):
        run_monitor(MonitorApp(period=0.3), scenario, size=(120, 40))


def tf_frame(parent: str, child: str) -> bytes:
    """A tf2_msgs/TFMessage of one identity transform ``parent`` -> ``child``."""
    stamped = get_message_class("geometry_msgs/TransformStamped")()
    stamped.header.frame_id, stamped.child_frame_id = parent, child
    stamped.transform.rotation.w = 1.0
    return bytes(get_message_class("tf2_msgs/TFMessage")(transforms=[stamped]).serialize())


def test_tf_source_refuses_another_version_of_tfmessage_and_keeps_the_honest_broadcaster(
        rostui_core: Any, ros_env: dict[str, str]) -> None:
    """The tf tree's and the top-down view's source: a /tf publisher whose header gives tf2_msgs/TFMessage another
    md5sum (its definition agreeing) is refused once, in one problem line, never decoded (it was decoded as rostui's
    TFMessage whatever its md5sum said); the honest broadcaster's frames are in the buffer."""
    from rostui.models.tf.source import TfSource

    master = ros_env["ROS_MASTER_URI"]
    tf_message = get_message_class("tf2_msgs/TFMessage")
    other = tf_message._full_text.replace("Transform transform", "Transform transform\nfloat64 confidence")
    other_md5 = definition_md5("tf2_msgs/TFMessage", other)
    loop = asyncio.new_event_loop()
    source = TfSource(master, node_name="tf_victim")

    async def listen() -> None:
        task = asyncio.get_running_loop().create_task(source.run())
        try:
            await until(lambda: "odom" in source.buffer.frames() and source.problems, "both publishers heard")
            counted = source.messages
            await until(lambda: source.messages >= counted + 10, "the honest broadcaster heard on")
        finally:
            await source.stop()
            task.cancel()
            await asyncio.gather(task, return_exceptions=True)

    with LyingPublisher(master, "/tf", "tf2_msgs/TFMessage", tf_message._md5sum, tf_message._full_text,
                        tf_frame("map", "odom"), callerid="/honest"), \
            LyingPublisher(master, "/tf", "tf2_msgs/TFMessage", other_md5, other, tf_frame("map", "evil"),
                           callerid="/liar") as liar:
        loop.run_until_complete(listen())
        connections = liar.connections
    loop.close()
    problems = list(source.problems)
    assert problems == [f"publisher [/liar] has datatype/md5sum [tf2_msgs/TFMessage/{other_md5}], "
                        f"not [tf2_msgs/TFMessage/{tf_message._md5sum}]"], problems
    assert "evil" not in source.buffer.frames() and connections == 1
