#!/usr/bin/env python3
"""rostui bag against real rosbag in the same run: 1 MB recording without drops, and playback timing at 1 kHz.

(a) ``record``: a publisher process (rostui, queue 100) sends numbered 1 MB
    messages (std_msgs/String) for ``--seconds`` at a rate from a ladder; the
    recorder under test (`rostui bag record` to .mcap and to .bag, `rosbag
    record`) runs as its own process. After the publisher is done and the file
    stops growing, the recorder gets Ctrl-C and its file is read back. A rate
    is *held* when the file has every message sent. The ladder goes up until a
    recorder misses messages; the highest held rate is reported per recorder
    with the ratio rostui/rosbag (target >= 1.5x).
(b) ``play``: a .bag of 3000 std_msgs/Int32 at 1 ms spacing is played by
    `rostui bag play` and `rosbag play`; a subscriber in this process stamps
    arrivals. The error of message i is its arrival time minus its bag time
    (both from the first message), less the median of those; p50/p99 of its
    absolute value are reported. rostui's own scheduled-vs-actual publish
    lateness (measured inside its player) is printed too.

    .venv/bin/python bench/bench_bag.py [--seconds 4] [--only record|play] [--dir /dev/shm] [--json out.json]
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from _common import REPO, free_port, ros_env, wait_port

sys.path.insert(0, str(REPO))
MB = 1_000_000
LADDER = [int(x) for x in os.environ.get("BENCH_BAG_LADDER", "50,100,200,300,400,500,600,700,800,1000").split(",")]
TOPIC = "/bench"


def stop(proc: subprocess.Popen, timeout: float = 20.0) -> None:
    """Ctrl-C, then SIGKILL."""
    if proc.poll() is None:
        proc.send_signal(2)
        try:
            proc.wait(timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


# ----------------------------------------------------------------------------- the publisher process
async def _publish(rate: float, seconds: float) -> None:
    from rostui.core.msg import get_message_class
    from rostui.core.node import AnyMsg, AsyncNode
    from rostui.core.node.topics import TopicType

    string = get_message_class("std_msgs/String")
    node = await AsyncNode("bench_pub", anonymous=True).start()
    pub = await node.advertise(TOPIC, AnyMsg, queue_size=100, topic_type=TopicType.of(string))
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
    """Entry of the publisher process."""
    from rostui.core.node.engine import new_event_loop

    new_event_loop().run_until_complete(_publish(rate, seconds))


# ----------------------------------------------------------------------------- (a) recording
def recorder_argv(kind: str, path: Path) -> list[str]:
    """The recorder command of each kind."""
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


def trial(kind: str, rate: int, seconds: float, env: dict[str, str], tmp: Path) -> dict[str, Any]:
    """One recorder at one rate: sent, recorded, the publisher's achieved rate."""
    path = tmp / ("trial.bag" if kind != "rostui-mcap" else "trial.mcap")
    rec = subprocess.Popen(recorder_argv(kind, path), env=env, cwd=tmp, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 30
        while not subscribed(env):
            if time.monotonic() > deadline:
                raise RuntimeError(f"{kind} never subscribed")
            time.sleep(0.05)
        pub = subprocess.run([sys.executable, __file__, "--publisher", str(rate), str(seconds)], env=env,
                             capture_output=True, text=True, timeout=seconds * 10 + 60)
        result = json.loads(pub.stdout.strip().splitlines()[-1])
        active = Path(str(path) + ".active")  # rosbag's name while recording
        last, still = -1, 0
        while still < 3:  # the recorder catches up: the file stops growing for 0.6 s
            time.sleep(0.2)
            size = max((p.stat().st_size for p in (path, active) if p.exists()), default=0)
            still = still + 1 if size == last else 0
            last = size
    finally:
        stop(rec)
    deadline = time.monotonic() + 30
    while not path.exists() and time.monotonic() < deadline:  # rosbag's child renames after the wrapper exits
        time.sleep(0.1)
    time.sleep(0.5)
    recorded = count_in(path)
    path.unlink(missing_ok=True)
    return {"rate": rate, "sent": result["sent"], "recorded": recorded,
            "pub_rate": result["sent"] / result["seconds"] if result["seconds"] else 0.0}


def bench_record(seconds: float, env: dict[str, str], tmp: Path, kinds: list[str]) -> dict[str, Any]:
    """The rate ladder per recorder; the highest rate held by each."""
    out: dict[str, Any] = {}
    for kind in kinds:
        held = 0
        rows = []
        for rate in LADDER:
            row = trial(kind, rate, seconds, env, tmp)
            rows.append(row)
            ok = row["recorded"] == row["sent"]
            print(f"  {kind:12} {rate:4d} MB/s target, publisher {row['pub_rate']:6.1f}/s: "
                  f"{row['recorded']}/{row['sent']} recorded {'held' if ok else 'DROPS'}", flush=True)
            if not ok:
                break
            held = rate
            if row["pub_rate"] < 0.9 * rate:
                print(f"  {kind:12} publisher-limited at {row['pub_rate']:.0f} msg/s", flush=True)
                break
        out[kind] = {"held_mb_s": held, "trials": rows}
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
    from rostui.core.bag.player import PlayOptions, play
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
    if len(sys.argv) == 4 and sys.argv[1] == "--publisher":
        publisher_main(float(sys.argv[2]), float(sys.argv[3]))
        return 0
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=4.0, help="Seconds of publishing per recording trial.")
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
            print(f"(a) 1 MB messages for {args.seconds:g} s per rate, recording to {tmp}", flush=True)
            kinds = ["rostui-mcap", "rostui-bag"] + (["rosbag"] if have_rosbag else [])
            rec = results["record"] = bench_record(args.seconds, env, tmp, kinds)
            if have_rosbag and rec["rosbag"]["held_mb_s"]:
                for kind in ("rostui-mcap", "rostui-bag"):
                    ratio = rec[kind]["held_mb_s"] / rec["rosbag"]["held_mb_s"]
                    rec[kind]["ratio_vs_rosbag"] = ratio
                    print(f"  {kind}: held {rec[kind]['held_mb_s']} MB/s vs rosbag {rec['rosbag']['held_mb_s']} "
                          f"MB/s = {ratio:.2f}x (target >= 1.5x)", flush=True)
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
