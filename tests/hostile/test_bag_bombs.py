"""Decompression bombs and a run of zeros in bag files, against rostui's bag readers, beside Debian's rosbag.

The files (tests/hostile/bag_bombs.py) are valid as far as their headers go: a zstd MCAP of 49 KB whose one chunk
holds 1.5 GB (with its summary, without, and declaring its true size), ``.bag`` files whose second chunk (bz2:
7 KB for 450 MB; lz4: 4 MB for 1 GB) declares the size of its 20 real records and goes on with zeros, and an
unclosed ``.bag`` followed by 200 MiB of zeros.  Each victim is a real command (or bag view under Textual's pilot)
with its memory sampled; what a user sees is asserted: memory bounded, a one-line refusal naming the file and
the byte, no hang, and the legitimate part served (the good chunk's 20 messages reach a subscriber, another bag's
info is printed).  Debian's ``rosbag info``/``rosbag play`` (and, for MCAP, the ``mcap`` library's own reader,
as rosbag reads no MCAP) run on the same files under a 3 GB address-space limit; their figures are recorded,
never asserted.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterator

import psutil
import pytest
from textual.pilot import Pilot

from bag_bombs import GOOD_COUNT, GOOD_TOPIC, TOPIC, bag_bomb, mcap_bomb, unclosed_with_zeros
from hostile_helpers import MB, RssSampler, record
from rostui.apps.bagview.app import BagViewApp
from rostui.core.xmlrpc import call_sync

from bag_view_helpers import run_pilot
from conftest import REPO, master_port, rostui_cmd, until, wait_until

#: Peak resident memory a victim command may reach (they start at 30-60 MB).
PEAK_LIMIT_MB = 150
#: How much bag view's process may grow while it plays a bomb.
GROWTH_LIMIT_MB = 100
BOMB_MIB = {"bz2": 450, "lz4": 1024}
MCAP_BOMB_MIB = 1536
ZEROS_MIB = 200
REAL_BAG = REPO / "tests" / "bag_corpus" / "example-unsorted-chunks.bag"
#: A comparison tool gets this long (and 3 GB of address space) before it is stopped: only its figures count.
PEER_TIMEOUT = 20.0
#: Far longer than any victim needs; reaching it is a hang.
HANG = 60.0


class TreeRssSampler(RssSampler):
    """An :class:`RssSampler` of a process and its children together (Debian's ``rosbag play`` is a Python
    script that runs the C++ player as a child)."""

    def _run(self) -> None:
        while not self._stop.wait(0.02):
            try:
                tree = [self.process, *self.process.children(recursive=True)]
            except psutil.Error:
                return
            total = 0
            for proc in tree:
                try:
                    total += proc.memory_info().rss
                except psutil.Error:
                    pass
            self.peak = max(self.peak, total)


@dataclass
class Run:
    """A finished command: exit status, output, peak RSS in MB, and whether it had to be stopped."""

    code: int
    out: str
    err: str
    peak_mb: float
    stopped: bool = False

    def figures(self) -> dict[str, Any]:
        """What :func:`record` keeps of it."""
        lines = self.err.strip().splitlines() or self.out.strip().splitlines() or [""]
        said = [line.strip() for line in self.err.splitlines() + self.out.splitlines()]  # bag info warns on stdout
        tail = next((line for line in said if line.startswith(("warning:", "rostui", "ERROR"))),
                    next((line for line in said if line.startswith("messages:")), lines[-1]))
        return {"exit": "stopped" if self.stopped else self.code, "peak_rss_mb": round(self.peak_mb, 1),
                "said": tail[:160]}


def run_sampled(cmd: list[str], env: dict[str, str], *, timeout: float = HANG, peer: bool = False) -> Run:
    """Run ``cmd`` to its end with its resident memory sampled; a ``peer`` (a comparison tool) runs under a 3 GB
    address-space limit and is stopped after ``PEER_TIMEOUT``; a victim running past ``timeout`` is a hang."""
    argv = ["prlimit", "--as=3000000000", "--", *cmd] if peer else cmd
    proc = subprocess.Popen(argv, env=env, cwd=REPO, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=peer)
    with TreeRssSampler(proc.pid) as rss:
        try:
            out, err = proc.communicate(timeout=PEER_TIMEOUT if peer else timeout)
            stopped = False
        except subprocess.TimeoutExpired:
            if not peer:
                proc.kill()
                proc.communicate()
                pytest.fail(f"{' '.join(cmd)} hangs: still running after {timeout:.0f} s")
            os.killpg(proc.pid, 9)
            out, err = proc.communicate()
            stopped = True
    return Run(proc.returncode, out, err, rss.peak / MB, stopped)


def debian(*args: str) -> list[str] | None:
    """Debian's ``rosbag`` command line, or None where it is not installed."""
    return ["rosbag", *args] if shutil.which("rosbag") else None


def assert_one_line_naming(run: Run, path: Path) -> None:
    """A refusal as a user must see it: exit status 1, one line on stderr, naming the file and a byte."""
    lines = [line for line in run.err.strip().splitlines() if line.startswith("rostui")]
    assert run.code == 1 and "Traceback" not in run.err, run.err
    assert len(lines) == 1 and str(path) in lines[0] and "byte" in lines[0], run.err


@pytest.fixture(scope="module")
def bombs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder of the bombs (built once: about 2 s)."""
    folder = tmp_path_factory.mktemp("bombs")
    for kind, mib in BOMB_MIB.items():
        bag_bomb(folder / f"{kind}.bag", kind, mib)
    mcap_bomb(folder / "summary.mcap", MCAP_BOMB_MIB, summary=True)
    mcap_bomb(folder / "unclosed.mcap", MCAP_BOMB_MIB, summary=False)
    mcap_bomb(folder / "honest.mcap", MCAP_BOMB_MIB, summary=False, honest=True)
    unclosed_with_zeros(folder / "zeros.bag", ZEROS_MIB)
    return folder


# -- bag info on a zstd MCAP -------------------------------------------------------------------------------------
MCAP_LIBRARY_INFO = """
import sys
from mcap.reader import make_reader
with open(sys.argv[1], "rb") as f:
    reader = make_reader(f)
    summary = reader.get_summary()
    if summary is not None and summary.statistics is not None:
        print("messages", summary.statistics.message_count)
    else:
        print("messages", sum(1 for _ in reader.iter_messages()))
"""


@pytest.mark.parametrize("name", ["summary.mcap", "unclosed.mcap", "honest.mcap"])
def test_bag_info_on_a_zstd_mcap_bomb(bombs: Path, name: str, ros_env: dict[str, str]) -> None:
    """With a summary, info decompresses nothing; without, the chunk stops at the size it declares, or is
    refused unread when it declares more than ROSTUI_BAG_MAX_CHUNK. The real bag named after it is shown."""
    path = bombs / name
    run = run_sampled(rostui_cmd("bag", "info", str(path), str(REAL_BAG)), ros_env)
    assert "Traceback" not in run.err and run.code == 0, run.err
    assert run.peak_mb < PEAK_LIMIT_MB, f"rostui bag info reached {run.peak_mb:.0f} MB"
    shown = run.out.split("\n---\n")
    assert len(shown) == 2 and re.search(r"^messages: +3$", shown[1], re.M), run.out  # the legitimate file
    if name == "summary.mcap":
        assert re.search(r"^messages: +20$", shown[0], re.M), run.out
    else:
        why = "more than ROSTUI_BAG_MAX_CHUNK" if name == "honest.mcap" else "decompresses past"
        assert why in shown[0] and "at byte 36" in shown[0], run.out
    library = run_sampled([sys.executable, "-c", MCAP_LIBRARY_INFO, str(path)], ros_env, peer=True)
    record(f"bag info on a {MCAP_BOMB_MIB} MiB zstd bomb ({name})", "rostui", **run.figures(),
           file_kb=round(path.stat().st_size / 1024, 1))
    record(f"bag info on a {MCAP_BOMB_MIB} MiB zstd bomb ({name})", "mcap library (get_summary/iter_messages)",
           **library.figures())


def test_the_cap_bounds_a_chunk_that_declares_its_true_size(tmp_path: Path, ros_env: dict[str, str]) -> None:
    """Under ROSTUI_BAG_MAX_CHUNK=64 MiB an unclosed MCAP chunk that honestly declares 48 MiB (its records, then
    zeros) is read and stops at its first zero record; one declaring 96 MiB is refused unread, and the real bag
    named after it is shown."""
    env = {**ros_env, "ROSTUI_BAG_MAX_CHUNK": str(64 * MB)}
    under = mcap_bomb(tmp_path / "under.mcap", 48, summary=False, honest=True)
    over = mcap_bomb(tmp_path / "over.mcap", 96, summary=False, honest=True)
    first = run_sampled(rostui_cmd("bag", "info", str(under)), env)
    second = run_sampled(rostui_cmd("bag", "info", str(over), str(REAL_BAG)), env)
    assert first.code == 0 and re.search(r"^messages: +20$", first.out, re.M), first.out
    assert "a record of opcode 0" in first.out, first.out
    shown = second.out.split("\n---\n")
    assert second.code == 0 and "more than ROSTUI_BAG_MAX_CHUNK allows (67108864)" in shown[0], second.out
    assert len(shown) == 2 and re.search(r"^messages: +3$", shown[1], re.M), second.out
    assert first.peak_mb < 64 + PEAK_LIMIT_MB and second.peak_mb < PEAK_LIMIT_MB, (first.peak_mb, second.peak_mb)
    record("bag info, a chunk declaring 48 MiB under a 64 MiB cap", "rostui", **first.figures())
    record("bag info, a chunk declaring 96 MiB under a 64 MiB cap", "rostui", **second.figures())


# -- bag play and bag view on bz2 and lz4 bombs --------------------------------------------------------------------
LISTENER = f"""
import sys
from rostui import client as ros
String = ros.msg("std_msgs/String")
ros.init_node("good_listener", anonymous=True)
heard = []

def take(message):
    print("data:", message.data, flush=True)
    heard.append(message)
    if len(heard) == {GOOD_COUNT}:
        ros.signal_shutdown("heard them all")

ros.Subscriber("{GOOD_TOPIC}", String, take)
ros.spin()
"""


@dataclass
class Listener:
    """A node subscribed to the good topic until it has heard all of it: the legitimate subscriber."""

    proc: subprocess.Popen[str]

    def messages(self) -> list[str]:
        """The ``data`` lines it printed (once it has ended)."""
        out, _ = self.proc.communicate(timeout=HANG)
        return [line for line in out.splitlines() if line.startswith("data:")]


@pytest.fixture
def listener(rostui_core: Any, ros_env: dict[str, str]) -> Iterator[Listener]:
    """The legitimate subscriber, registered with the master before the test goes on."""
    proc = subprocess.Popen([sys.executable, "-c", LISTENER], env=ros_env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    uri = f"http://127.0.0.1:{master_port(ros_env)}"

    def subscribed() -> bool:
        assert proc.poll() is None, proc.communicate()[0]
        subscribers = call_sync(uri, "getSystemState", "/test")[2][1]
        return any(topic == GOOD_TOPIC for topic, _ in subscribers)
    wait_until(subscribed, "the listener to subscribe")
    yield Listener(proc)
    if proc.poll() is None:
        proc.kill()
        proc.wait()


@pytest.mark.parametrize("kind", ["bz2", "lz4"])
def test_bag_play_plays_the_good_chunk_then_refuses_the_bomb_in_one_line(bombs: Path, kind: str, listener: Listener,
                                                                         ros_env: dict[str, str]) -> None:
    path = bombs / f"{kind}.bag"
    run = run_sampled(rostui_cmd("bag", "play", "-q", "-d", "1", str(path)), ros_env)
    assert_one_line_naming(run, path)
    assert "decompresses past the" in run.err, run.err
    assert run.peak_mb < PEAK_LIMIT_MB, f"rostui bag play reached {run.peak_mb:.0f} MB"
    assert len(listener.messages()) == GOOD_COUNT
    record(f"bag play of a {kind} chunk declaring 1 KB, holding {BOMB_MIB[kind]} MiB", "rostui", **run.figures(),
           file_kb=round(path.stat().st_size / 1024, 1))
    argv = debian("play", "-q", "-d", "1", str(path))
    if argv is not None:
        record(f"bag play of a {kind} chunk declaring 1 KB, holding {BOMB_MIB[kind]} MiB", "Debian rosbag play",
               **run_sampled(argv, ros_env, peer=True).figures())


@pytest.mark.parametrize("kind", ["bz2", "lz4"])
def test_bag_view_plays_the_good_chunk_and_shows_the_bomb_on_its_status_line(bombs: Path, kind: str) -> None:
    path = bombs / f"{kind}.bag"
    rss = RssSampler(os.getpid())

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await until(lambda: app.transport is not None, "the bag to be read")
        transport = app.transport
        assert transport is not None
        await pilot.press("space")
        await until(lambda: transport.paused and transport.at_end, "the end of the bag")
        app.refresh_view()
        status = str(app.status.render())
        assert f"⚠ {path}: a {kind} chunk decompresses past the" in status and "(byte " in status, status
        assert transport.published == GOOD_COUNT  # every good message, none of the bomb's
        assert app.timeline.selected_topic == TOPIC
        assert "decompresses past the" in str(app.inspector_text.render())  # the bomb's message, inspected

    with rss:
        run_pilot(BagViewApp([str(path)], publish=False, rate=100.0), scenario, size=(200, 30))
    assert rss.growth_mb < GROWTH_LIMIT_MB, f"bag view grew {rss.growth_mb:.0f} MB"
    record(f"bag view of a {kind} chunk declaring 1 KB, holding {BOMB_MIB[kind]} MiB", "rostui (pilot)",
           peak_rss_growth_mb=round(rss.growth_mb, 1), played=GOOD_COUNT)


# -- an unclosed bag followed by zeros -------------------------------------------------------------------------------
def test_info_and_play_stop_at_the_first_zero_of_an_unclosed_bag(bombs: Path, listener: Listener,
                                                                  ros_env: dict[str, str]) -> None:
    """As ``rosbag reindex`` stops at the first record that is not one, the readers stop at the zeros' first
    byte (a record without an op) and read what comes before: info counts the good messages, play plays
    them. Neither reads the 200 MiB."""
    path = bombs / "zeros.bag"
    info = run_sampled(rostui_cmd("bag", "info", str(path)), ros_env)
    assert info.code == 0 and "Traceback" not in info.err, info.err
    assert f"{GOOD_TOPIC}   {GOOD_COUNT} msgs" in info.out and "a record has no 'op' field at byte" in info.out, \
        info.out
    play = run_sampled(rostui_cmd("bag", "play", "-q", "-d", "1", str(path)), ros_env)
    assert play.code == 0 and "Traceback" not in play.err, play.err
    assert len(listener.messages()) == GOOD_COUNT
    assert max(info.peak_mb, play.peak_mb) < PEAK_LIMIT_MB, (info.peak_mb, play.peak_mb)
    what = f"an unclosed bag followed by {ZEROS_MIB} MiB of zeros"
    record(f"bag info of {what}", "rostui", **info.figures())
    record(f"bag play of {what}", "rostui", **play.figures())
    for verb in ("info", "play"):
        argv = debian(verb, *(("-q", "-d", "1") if verb == "play" else ()), str(path))
        if argv is not None:
            record(f"bag {verb} of {what}", f"Debian rosbag {verb}", **run_sampled(argv, ros_env, peer=True).figures())
