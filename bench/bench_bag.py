#!/usr/bin/env python3
"""rostui bag against real rosbag in the same run: 1 MB recording without drops, and playback timing at 1 kHz.

(a) ``record``: one publisher sends numbered 1 MB std_msgs/String messages
    for ``--seconds`` at a rate from a ladder, with a queue of 100 that drops
    the oldest when the subscriber reads too slowly (as every ROS publisher
    does). By default it is ``bench/bag_peer.cpp publish`` (roscpp, built
    here); ``--publisher python`` uses a rostui publisher instead. The recorder
    under test (`rostui bag record` to .mcap and to .bag, `rosbag record`)
    runs as its own process and writes into the same folder. With the roscpp
    peer built, a fourth "recorder", ``receive-only`` (``bag_peer count``: a
    roscpp subscriber that only counts), shows what publisher, kernel and
    one roscpp subscriber reach on this machine with no file at all (roscpp's
    receive path, not the machine's limit: rostui's raw receive path has held
    more while writing a file). The
    order of the recorders
    rotates from one rate to the next. When the publisher has sent
    everything and the file has stopped growing, the recorder gets Ctrl-C and
    its file is read back: a rate is *held* when the file has every message
    sent while the publisher kept to the rate. At each rate every recorder
    still in the race runs once; a run with drops is repeated once (so one
    load spike of the shared machine does not decide) and a run in which the
    publisher fell behind without drops is repeated (up to four runs); a
    recorder leaves the race at its first rate with drops in two runs.
    Reported: the highest held rate per recorder, the ratio
    rostui/rosbag (target >= 1.5x), and each recorder's CPU time per message
    (its whole process tree, user + system) at the rates it held; each trial
    also prints the publisher's CPU time per message.
(b) ``play``: a .bag of 3000 std_msgs/Int32 at 1 ms spacing is played by
    `rostui bag play` and `rosbag play`; a subscriber in this process stamps
    arrivals. The error of message i is its arrival time minus its bag time
    (both from the first message), less the median of those; p50/p99 of its
    absolute value are reported. rostui's own scheduled-vs-actual publish
    lateness (measured inside its player) is printed too.

    .venv/bin/python bench/bench_bag.py [--seconds 3] [--only record|play] [--dir /dev/shm]
                                        [--publisher roscpp|python] [--json out.json]
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import select
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from _common import REPO, build_cpp, free_port, ros_env, wait_port

sys.path.insert(0, str(REPO))
MB = 1_000_000
QUEUE = 100
LADDER = [int(x) for x in os.environ.get(
    "BENCH_BAG_LADDER", ",".join(str(r) for r in range(400, 2100, 100))).split(",")]
TOPIC = "/bench"
BENCH = Path(__file__).resolve().parent
CPP_PEER_SRC = BENCH / "bag_peer.cpp"
CPP_PEER = BENCH / "_build" / "bag_peer"
RECEIVE_ONLY = "receive-only"


def stop(proc: subprocess.Popen, timeout: float = 20.0) -> None:
    """Ctrl-C, then SIGKILL."""
    if proc.poll() is None:
        proc.send_signal(2)
        try:
            proc.wait(timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def load_average() -> str:
    """The 1, 5 and 15 minute load averages."""
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def tree_cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of a process and all its descendants (threads included)."""
    total = 0.0
    pending = [pid]
    tick = os.sysconf("SC_CLK_TCK")
    while pending:
        p = pending.pop()
        try:
            fields = Path(f"/proc/{p}/stat").read_text().rsplit(")", 1)[1].split()
            total += (int(fields[11]) + int(fields[12])) / tick
            for task in os.listdir(f"/proc/{p}/task"):
                pending += [int(c) for c in Path(f"/proc/{p}/task/{task}/children").read_text().split()]
        except (OSError, IndexError, ValueError):
            continue
    return total


# ----------------------------------------------------------------------------- the publishers
def build_cpp_peer() -> Path | None:
    """Compile bench/bag_peer.cpp unless the binary is newer; None when it cannot be built."""
    return build_cpp(CPP_PEER_SRC)


async def _publish(rate: float, seconds: float) -> None:
    from rostui.core.msg import get_message_class
    from rostui.core.node import AnyMsg, AsyncNode
    from rostui.core.node.topics import TopicType

    string = get_message_class("std_msgs/String")
    node = await AsyncNode("bench_pub", anonymous=True).start()
    pub = await node.advertise(TOPIC, AnyMsg, queue_size=QUEUE, topic_type=TopicType.of(string))
    while pub.get_num_connections() < 1:
        await asyncio.sleep(0.01)
    await asyncio.sleep(0.3)
    body = bytearray(struct.pack("<I", MB - 4) + b"x" * (MB - 4))
    loop = asyncio.get_running_loop()
    count = int(rate * seconds)
    start = loop.time()
    for i in range(count):
        due = start + i / rate
        delay = due - loop.time()
        if delay > 0:
            await asyncio.sleep(delay)
        body[4:12] = b"%08d" % i
        pub.publish(AnyMsg(bytes(body)))
    took = loop.time() - start
    deadline = loop.time() + 30
    while loop.time() < deadline and any(getattr(p, "_pending", None) for p in node.publications.values()):
        await asyncio.sleep(0.01)
    print(json.dumps({"sent": count, "seconds": took}), flush=True)
    await asyncio.sleep(0.5)
    await node.shutdown()


def publisher_main(rate: float, seconds: float) -> None:
    """Entry of the Python publisher process."""
    from rostui.core.node.engine import new_event_loop

    new_event_loop().run_until_complete(_publish(rate, seconds))


def publisher_argv(kind: str, rate: int, seconds: float) -> list[str]:
    """The publisher command: the roscpp one, or this script as a rostui publisher."""
    if kind == "roscpp":
        return [str(CPP_PEER), "publish", TOPIC, str(MB), str(rate), str(seconds), str(QUEUE)]
    return [sys.executable, __file__, "--publisher-process", str(rate), str(seconds)]


def read_result(pub: subprocess.Popen, timeout: float) -> dict[str, Any]:
    """The first JSON line a peer prints (the publisher's ``{"sent": N, "seconds": S}``)."""
    assert pub.stdout is not None
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        ready, _, _ = select.select([pub.stdout], [], [], 0.5)
        if ready:
            line = pub.stdout.readline()
            if line.startswith("{"):
                return json.loads(line)
            if not line and pub.poll() is not None:
                break
    raise RuntimeError(f"{pub.args[0]} gave no result (exit status {pub.poll()})")


# ----------------------------------------------------------------------------- (a) recording
def recorder_argv(kind: str, path: Path) -> list[str]:
    """The recorder command of each kind."""
    if kind == RECEIVE_ONLY:
        return [str(CPP_PEER), "count", TOPIC, "__name:=record_receive_only"]
    if kind == "rosbag":
        return ["rosbag", "record", "-O", str(path), TOPIC]
    return [sys.executable, "-m", "rostui", "bag", "record", "-O", str(path), TOPIC]


def subscribed(env: dict[str, str]) -> bool:
    """True when a /record_ node subscribes to the bench topic."""
    import xmlrpc.client

    state = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/bench")[2]
    return any(t == TOPIC and any(n.startswith("/record") for n in nodes) for t, nodes in state[1])


def count_in(path: Path) -> int:
    """Messages in a finished file (read with rostui's reader)."""
    from rostui.core.bag.files import open_reader

    reader = open_reader(str(path))
    try:
        return sum(1 for _ in reader.messages())
    finally:
        reader.close()


def trial(kind: str, rate: int, seconds: float, env: dict[str, str], tmp: Path, publisher: str) -> dict[str, Any]:
    """One recorder at one rate: sent, recorded, the publisher's achieved rate, the recorder's CPU per message."""
    path = tmp / ("trial.bag" if kind != "rostui-mcap" else "trial.mcap")
    receive_only = kind == RECEIVE_ONLY
    rec = subprocess.Popen(recorder_argv(kind, path), env=env, cwd=tmp, stderr=subprocess.DEVNULL, text=True,
                           stdout=subprocess.PIPE if receive_only else subprocess.DEVNULL)
    pub: subprocess.Popen | None = None
    try:
        deadline = time.monotonic() + 30
        while not subscribed(env):
            if time.monotonic() > deadline:
                raise RuntimeError(f"{kind} never subscribed")
            time.sleep(0.05)
        cpu_before = tree_cpu_seconds(rec.pid)
        pub = subprocess.Popen(publisher_argv(publisher, rate, seconds), env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.DEVNULL, text=True)
        result = read_result(pub, seconds * 10 + 60)
        pub_cpu = tree_cpu_seconds(pub.pid)
        if receive_only:  # it reports and exits 1 s after the last message
            cpu = tree_cpu_seconds(rec.pid) - cpu_before
            deadline = time.monotonic() + 60
            while rec.poll() is None and time.monotonic() < deadline:
                cpu = tree_cpu_seconds(rec.pid) - cpu_before
                time.sleep(0.1)
            received = read_result(rec, 10)["received"] if rec.poll() is not None else 0
        else:
            active = Path(str(path) + ".active")  # rosbag's name while recording
            last, still = -1, 0
            while still < 3:  # the recorder catches up: the file stops growing for 0.6 s
                time.sleep(0.2)
                size = max((p.stat().st_size for p in (path, active) if p.exists()), default=0)
                still = still + 1 if size == last else 0
                last = size
            cpu = tree_cpu_seconds(rec.pid) - cpu_before
    finally:
        stop(rec)
        if pub is not None:
            stop(pub)
    if receive_only:
        recorded = received
    else:
        deadline = time.monotonic() + 30
        while not path.exists() and time.monotonic() < deadline:  # rosbag's child renames after the wrapper exits
            time.sleep(0.1)
        time.sleep(0.5)
        recorded = count_in(path)
        path.unlink(missing_ok=True)
        os.sync()  # the next trial starts with no writeback of this one's data in progress
    return {"rate": rate, "sent": result["sent"], "recorded": recorded,
            "pub_rate": result["sent"] / result["seconds"] if result["seconds"] else 0.0,
            "recorder_cpu_us_per_msg": cpu / max(recorded, 1) * 1e6,
            "publisher_cpu_us_per_msg": pub_cpu / max(result["sent"], 1) * 1e6, "load": load_average()}


def bench_record(seconds: float, env: dict[str, str], tmp: Path, kinds: list[str], publisher: str) -> dict[str, Any]:
    """Every recorder still in the race at each rate of the ladder; the highest rate held by each.

    A rate is held after one run with every message recorded while the publisher kept to within 5% of the
    rate; a recorder leaves the race after two runs with drops at one rate. A run whose publisher fell
    behind (the shared machine did not give it the CPU) without drops counts neither way and is repeated,
    four runs at most; a recorder whose rate was never reached on time leaves the race as publisher-limited.
    """
    out: dict[str, Any] = {kind: {"held_mb_s": 0, "trials": []} for kind in kinds}
    racing = list(kinds)
    for step, rate in enumerate(LADDER):
        order = racing[step % len(racing):] + racing[:step % len(racing)]  # nobody always goes first
        for kind in order:
            verdict = ""
            drops = 0
            for attempt in range(1, 5):
                row = trial(kind, rate, seconds, env, tmp, publisher)
                row["attempt"] = attempt
                out[kind]["trials"].append(row)
                complete = row["recorded"] == row["sent"]
                on_time = row["pub_rate"] >= 0.95 * rate
                drops += not complete
                verdict = "held" if complete and on_time else "DROPS" if drops >= 2 else ""
                note = ("held" if verdict == "held" else "DROPS" if not complete
                        else "all recorded, but the publisher was late: not counted")
                print(f"  {kind:12} {rate:5d} MB/s target, publisher {row['pub_rate']:6.1f}/s: "
                      f"{row['recorded']}/{row['sent']} recorded, {note}"
                      f"{f' (run {attempt})' if attempt > 1 else ''}; recorder CPU "
                      f"{row['recorder_cpu_us_per_msg']:.0f} us/msg, publisher {row['publisher_cpu_us_per_msg']:.0f} us/msg; "
                      f"load {row['load']}", flush=True)
                if verdict:
                    break
            if verdict == "held":
                out[kind]["held_mb_s"] = rate
                continue
            racing.remove(kind)
            if verdict != "DROPS":
                out[kind]["publisher_limited_at"] = rate
                print(f"  {kind:12} the publisher never kept to {rate} msg/s: stopping here", flush=True)
        if not racing:
            break
    for kind in kinds:
        held = [t["recorder_cpu_us_per_msg"] for t in out[kind]["trials"] if t["recorded"] == t["sent"]]
        out[kind]["cpu_us_per_msg_median"] = statistics.median(held) if held else None
    return out


# ----------------------------------------------------------------------------- (b) playback timing
def make_timing_bag(path: Path, count: int = 3000) -> None:
    """Int32 0..count-1 at 1 ms spacing."""
    from rostui.core.bag.files import open_writer
    from rostui.core.bag.model import Connection
    from rostui.core.msg import get_message_class

    int32 = get_message_class("std_msgs/Int32")
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, TOPIC, "std_msgs/Int32", int32._md5sum, int32._full_text, "/bench"))
    t0 = 1_700_000_000_000_000_000
    for i in range(count):
        writer.write(0, t0 + i * 1_000_000, int32(data=i).serialize())
    writer.close()


def arrivals(player_argv: list[str], env: dict[str, str], count: int) -> list[tuple[int, float]]:
    """(value, arrival perf_counter) of each message a player publishes."""
    from rostui.core.msg import get_message_class
    from rostui.core.node import AsyncNode
    from rostui.core.node.engine import Engine

    int32 = get_message_class("std_msgs/Int32")
    got: list[tuple[int, float]] = []
    engine = Engine()
    node = engine.run(AsyncNode("bench_sub", anonymous=True).start(), timeout=30)
    engine.run(node.subscribe(TOPIC, int32, lambda m: got.append((m.data, time.perf_counter())),
                              tcp_nodelay=True), timeout=30)
    try:
        subprocess.run(player_argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=120)
        deadline = time.monotonic() + 5
        while len(got) < count and time.monotonic() < deadline:
            time.sleep(0.05)
    finally:
        engine.run(node.shutdown(), timeout=10)
        engine.stop()
    return list(got)


def timing_errors(got: list[tuple[int, float]]) -> dict[str, float]:
    """p50/p99 of |arrival - bag time - median offset| in microseconds; how many arrived."""
    if len(got) < 2:
        return {"received": len(got), "p50_us": float("nan"), "p99_us": float("nan")}
    v0, a0 = got[0]
    offsets = [(a - a0) - (v - v0) * 1e-3 for v, a in got]
    med = statistics.median(offsets)
    errs = sorted(abs(o - med) * 1e6 for o in offsets)
    return {"received": len(got), "p50_us": errs[len(errs) // 2], "p99_us": errs[int(len(errs) * 0.99) - 1]}


def in_process_lateness(path: Path) -> dict[str, float]:
    """rostui's player's own scheduled-vs-actual publish lateness (no subscriber)."""
    from rostui.tools.bag.player import PlayOptions, play
    from rostui.core.node.engine import new_event_loop

    stats = new_event_loop().run_until_complete(play(PlayOptions(files=[str(path)], delay_s=0.2)))
    late = sorted(x * 1e6 for x in stats.lateness)
    return {"p50_us": late[len(late) // 2], "p99_us": late[int(len(late) * 0.99) - 1]}


def bench_play(env: dict[str, str], tmp: Path, with_rosbag: bool) -> dict[str, Any]:
    """Both players on the same 1 kHz bag."""
    path = tmp / "timing.bag"
    make_timing_bag(path)
    out: dict[str, Any] = {}
    players = {"rostui": [sys.executable, "-m", "rostui", "bag", "play", "-q", "-d", "0.5", str(path)]}
    if with_rosbag:
        players["rosbag"] = ["rosbag", "play", "-q", "-d", "0.5", str(path)]
    for name, argv in players.items():
        out[name] = timing_errors(arrivals(argv, env, 3000))
        r = out[name]
        print(f"  {name:8} received {r['received']}/3000, |error| p50 {r['p50_us']:.0f} us, "
              f"p99 {r['p99_us']:.0f} us", flush=True)
    out["rostui_in_process"] = in_process_lateness(path)
    print(f"  rostui scheduled-vs-actual publish lateness: p50 {out['rostui_in_process']['p50_us']:.0f} us, "
          f"p99 {out['rostui_in_process']['p99_us']:.0f} us", flush=True)
    return out


def main() -> int:
    """Run the benchmarks against a `rostui core` master."""
    if len(sys.argv) == 4 and sys.argv[1] == "--publisher-process":
        publisher_main(float(sys.argv[2]), float(sys.argv[3]))
        return 0
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=3.0, help="Seconds of publishing per recording trial.")
    parser.add_argument("--publisher", choices=["roscpp", "python"], default="roscpp",
                        help="The 1 MB publisher: bench/bag_peer.cpp (roscpp) or a rostui publisher.")
    parser.add_argument("--only", choices=["record", "play"], help="Run one part.")
    parser.add_argument("--json", help="Write the results to this file.")
    parser.add_argument("--dir", help="Record into this folder (e.g. /dev/shm: no disk, the recorders' own limits).")
    args = parser.parse_args()
    have_rosbag = shutil.which("rosbag") is not None
    tmp = Path(tempfile.mkdtemp(prefix="bench_bag_", dir=args.dir))
    port = free_port()
    env = ros_env(port, str(tmp / "ros_home"), PYTHONPATH=str(REPO))
    os.environ.update({k: env[k] for k in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")})
    core = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=env, cwd=REPO,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    results: dict[str, Any] = {}
    try:
        wait_port(port)
        if args.only in (None, "record"):
            publisher = args.publisher
            have_peer = build_cpp_peer() is not None
            if publisher == "roscpp" and not have_peer:
                print("  bench/bag_peer.cpp cannot be built here (g++ and roscpp headers): "
                      "using the rostui publisher", flush=True)
                publisher = "python"
            print(f"(a) 1 MB messages for {args.seconds:g} s per rate from the {publisher} publisher, recording to "
                  f"{tmp}; load average {load_average()}", flush=True)
            kinds = ([RECEIVE_ONLY] if have_peer else []) + ["rostui-mcap", "rostui-bag"] + (
                ["rosbag"] if have_rosbag else [])
            rec = results["record"] = bench_record(args.seconds, env, tmp, kinds, publisher)
            rec["publisher"] = publisher
            rec["load_after"] = load_average()
            for kind in kinds:
                cpu = rec[kind]["cpu_us_per_msg_median"]
                print(f"  {kind}: held {rec[kind]['held_mb_s']} MB/s; recorder CPU per 1 MB message "
                      f"{'-' if cpu is None else f'{cpu:.0f} us'} (median over the rates it held)", flush=True)
            if have_rosbag and rec["rosbag"]["held_mb_s"]:
                for kind in ("rostui-mcap", "rostui-bag"):
                    ratio = rec[kind]["held_mb_s"] / rec["rosbag"]["held_mb_s"]
                    rec[kind]["ratio_vs_rosbag"] = ratio
                    print(f"  {kind}: held {rec[kind]['held_mb_s']} MB/s vs rosbag {rec['rosbag']['held_mb_s']} "
                          f"MB/s = {ratio:.2f}x (target >= 1.5x)", flush=True)
            if have_peer:
                print(f"  {RECEIVE_ONLY} (a roscpp subscriber that writes nothing) held "
                      f"{rec[RECEIVE_ONLY]['held_mb_s']} MB/s: what roscpp's receive path alone reaches here",
                      flush=True)
            print(f"  load average after: {rec['load_after']}", flush=True)
        if args.only in (None, "play"):
            print("(b) playback of 3000 messages at 1 kHz", flush=True)
            results["play"] = bench_play(env, tmp, have_rosbag)
    finally:
        stop(core)
        shutil.rmtree(tmp, ignore_errors=True)
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
