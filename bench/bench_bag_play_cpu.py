#!/usr/bin/env python3
"""CPU time of `rostui bag play` against `rosbag play` on one bag, one rospy subscriber, start-up included.

The workload of issue 35: a 160 MB ``.bag`` written by Debian's rosbag Python
API, 8000 sensor_msgs/Image messages of 20 000 data bytes at 100 Hz (80 s),
once uncompressed and once with lz4 chunks (each image half noise, half flat:
lz4 halves it), played at ``-r 4`` (20 s) to one
Debian rospy subscriber on Debian's ``roscore``. Each player is a child of this
script; its CPU (user + system of it and every process it waited for, from
``wait4``) is read when it exits. ``rosbag play`` is Debian's command as users
run it: a Python script that starts the C++ ``play`` program; its C++ part
alone is reported too. Before each play the script reads the bag, so that each
player finds it in the page cache; each round's line gives how long that read took and how often the player
was preempted (its involuntary context switches). Rounds are interleaved; the subscriber must receive
every message of every run, or the run counts as failed. The summary gives the
ratio of the medians and rostui's ratio within each round (its run and
``rosbag play``'s back to back) with their median.

    .venv/bin/python bench/bench_bag_play_cpu.py                 # 3 rounds, about 5 minutes
    .venv/bin/python bench/bench_bag_play_cpu.py --load 2        # with two busy-looping processes
    .venv/bin/python bench/bench_bag_play_cpu.py --rounds 1 --only lz4 --json out.json
    .venv/bin/python bench/bench_bag_play_cpu.py --rostui /tmp/new/bin/rostui --before /tmp/old/bin/rostui
    .venv/bin/python bench/bench_bag_play_cpu.py --rostui /tmp/deb/bin/rostui --also pyenv=/tmp/pyenv/bin/rostui

``--rostui`` plays with another install's ``rostui`` (a regular ``pip install``, as
users have, starts faster than the editable ``.venv``); ``--before`` adds a fourth
player, an install of the commit before a change, to the same rounds, and
``--also LABEL=EXE`` any other (the same code on another Python, say). Each
rostui's Python is printed first: the interpreter's build moves a player's CPU
(bench/README.md, "Bag play CPU", eighteenth pass).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import free_port, ros_env, wait_port  # noqa: E402

ROSTUI = str(Path(sys.executable).with_name("rostui"))
MESSAGES = 8000
DATA_BYTES = 20_000
RATE_HZ = 100.0
PLAY_RATE = "4"

WRITE_BAG = r"""
import random, sys, rosbag, rospy
from sensor_msgs.msg import Image
path, compression, count, size, hz = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5])
noise = random.Random(35).randbytes(1 << 20)  # camera noise: lz4 gains little, as on real images
with rosbag.Bag(path, "w", compression=compression) as bag:
    for i in range(count):
        t = rospy.Time.from_sec(1_700_000_000 + i / hz)
        img = Image(height=100, width=size // 100, encoding="mono8", step=size // 100)
        img.header.seq = i
        img.header.stamp = t
        img.header.frame_id = "camera"
        start = (i * 262147) % (len(noise) - size)  # far apart: no repeats within lz4's 64 KB window
        img.data = noise[start:start + size // 2] + bytes(size - size // 2)  # half noise, half a flat wall
        bag.write("/camera/image", img, t)
"""

SUBSCRIBER = r"""
import sys, rospy
from sensor_msgs.msg import Image
got = [0]
def on_image(msg):
    got[0] += 1
rospy.init_node("bench_counter", anonymous=True, disable_signals=True)
rospy.Subscriber("/camera/image", Image, on_image, queue_size=100000)
print("ready", flush=True)
try:
    for line in sys.stdin:
        print(got[0], flush=True)
        got[0] = 0
except KeyboardInterrupt:
    pass
"""

BUSY = "import signal\nsignal.signal(signal.SIGINT, signal.SIG_DFL)\nwhile True: pass"


def write_bag(path: Path, compression: str) -> None:
    """Write the workload with Debian's rosbag API."""
    subprocess.run(["/usr/bin/python3", "-c", WRITE_BAG, str(path), compression, str(MESSAGES),
                    str(DATA_BYTES), str(RATE_HZ)], check=True)


def interpreter_of(exe: str) -> str:
    """The Python an installed ``rostui`` script runs on (its ``#!`` line): its version, the binary it resolves
    to, and whether the interpreter runs from a shared libpython (slower calls) or is linked into the binary."""
    with open(exe, "rb") as f:
        first = f.readline().decode(errors="replace")
    python = first[2:].strip() if first.startswith("#!") else sys.executable
    probe = ("import os, sys; maps = open('/proc/self/maps').read(); "
             "print(sys.version.split()[0], os.path.realpath(sys.executable), "
             "'(libpython shared)' if 'libpython' in maps else '(libpython linked in)')")
    out = subprocess.run([python, "-c", probe], capture_output=True, text=True, check=False)
    return out.stdout.strip() or f"{python}: {out.stderr.strip()[-200:]}"


def player_argv(kind: str, bag: Path, exes: dict[str, str]) -> list[str]:
    """The command line of one player (``exes``: the ``rostui`` executable of each rostui kind)."""
    if kind in exes:
        return [exes[kind], "bag", "play", "-q", "-d", "1", "-r", PLAY_RATE, str(bag)]
    return ["rosbag", "play", "-q", "-d", "1", "-r", PLAY_RATE, str(bag)]


def run_player(argv: list[str], env: dict[str, str]) -> dict[str, float]:
    """Run one player to its end; CPU of the whole tree (seconds) and of its C++ part when there is one."""
    start = time.perf_counter()
    proc = subprocess.Popen(argv, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    _pid, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    err = proc.stderr.read().decode(errors="replace") if proc.stderr else ""
    if proc.returncode != 0:
        raise RuntimeError(f"{argv[0]} exited {proc.returncode}: {err.strip()[-400:]}")
    return {"cpu": usage.ru_utime + usage.ru_stime, "user": usage.ru_utime, "sys": usage.ru_stime, "wall": wall,
            "maxrss_mb": usage.ru_maxrss / 1024, "preempted": usage.ru_nivcsw}


def warm_page_cache(bag: Path) -> float:
    """Read the whole bag (here, not in a player) so that every play finds it in the page cache; the seconds it
    took. This VM's kernel pages out what no one touched for about a minute (DAMON's ``pageout`` scheme), and
    bag files wait minutes between their plays: without this, whichever player came first after a pause read
    the file from disk at its own cost (an uncompressed play's CPU was 0.94 s in such a round, 0.56 s in the
    next)."""
    start = time.perf_counter()
    with bag.open("rb", buffering=0) as f:
        while f.read(8 << 20):
            pass
    return time.perf_counter() - start


def cpp_play_cpu(bag: Path, env: dict[str, str]) -> dict[str, float]:
    """Debian's C++ ``play`` program alone (what ``rosbag play`` starts), same options."""
    play = shutil.which("play", path="/usr/lib/rosbag:/usr/lib/x86_64-linux-gnu/rosbag:/opt/ros/noetic/lib/rosbag")
    if play is None:
        raise RuntimeError("Debian's rosbag 'play' program not found")
    return run_player([play, "-q", "-d", "1", "-r", PLAY_RATE, str(bag)], env)


def paired_ratios(ours: list[dict[str, float]], theirs: list[dict[str, float]]) -> list[float]:
    """rostui's CPU over rosbag's within each round: the two ran minutes apart at most, so a machine whose speed
    drifts over a run (this VM's does, by a third) moves both sides of each ratio alike."""
    return [a["cpu"] / b["cpu"] for a, b in zip(ours, theirs)]


def main() -> int:
    """Build the bags, run the rounds, print medians and ratios."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--load", type=int, default=0, help="busy-looping processes beside the players")
    parser.add_argument("--only", choices=["none", "lz4"], help="one of the two bags")
    parser.add_argument("--dir", help="where the bags are written (kept there when given)")
    parser.add_argument("--json", help="write the results here")
    parser.add_argument("--rostui", default=ROSTUI, help="the rostui executable to measure")
    parser.add_argument("--before", help="another rostui executable (the commit before) measured in the same rounds")
    parser.add_argument("--also", action="append", default=[], metavar="LABEL=EXE",
                        help="another rostui executable measured in the same rounds (repeatable)")
    args = parser.parse_args()
    exes = {"rostui": args.rostui}
    if args.before:
        exes["before"] = args.before
    for also in args.also:
        label, _, exe = also.partition("=")
        if not exe or label in ("rostui", "rosbag", "rosbag-cpp") or label in exes:
            parser.error(f"--also {also}: give LABEL=EXE with a label of its own")
        exes[label] = exe
    for label, exe in exes.items():
        print(f"{label}: {exe} on Python {interpreter_of(exe)}", flush=True)

    folder = Path(args.dir or tempfile.mkdtemp(prefix="bench-play-cpu-"))
    folder.mkdir(parents=True, exist_ok=True)
    home = tempfile.mkdtemp(prefix="bench-play-cpu-home-")
    port = free_port()
    env = ros_env(port, home)
    compressions = [args.only] if args.only else ["none", "lz4"]
    bags = {}
    for comp in compressions:
        bag = folder / f"play_{comp}.bag"
        if not bag.exists():
            write_bag(bag, comp)
        bags[comp] = bag
        print(f"{bag.name}: {bag.stat().st_size / 1e6:.0f} MB", flush=True)

    procs: list[subprocess.Popen] = []
    results: dict[str, list[dict[str, float]]] = {}
    try:
        procs.append(subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL, start_new_session=True))
        wait_port(port)
        sub = subprocess.Popen(["/usr/bin/python3", "-c", SUBSCRIBER], env=env, stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, start_new_session=True)
        procs.append(sub)
        assert sub.stdout is not None and sub.stdin is not None
        sub.stdout.readline()
        for _ in range(args.load):
            procs.append(subprocess.Popen([sys.executable, "-c", BUSY], start_new_session=True))
        kinds = ["rosbag", "rosbag-cpp", *exes]
        for rnd in range(args.rounds):
            order = kinds[rnd % len(kinds):] + kinds[:rnd % len(kinds)]
            for comp, bag in bags.items():
                for kind in order:
                    warm_s = warm_page_cache(bag)
                    if kind == "rosbag-cpp":
                        res = cpp_play_cpu(bag, env)
                    else:
                        res = run_player(player_argv(kind, bag, exes), env)
                    time.sleep(0.5)  # the subscriber's last callbacks
                    sub.stdin.write("count\n")
                    sub.stdin.flush()
                    res["received"] = int(sub.stdout.readline())
                    res["load"] = os.getloadavg()[0]
                    res["warm_s"] = warm_s
                    results.setdefault(f"{kind} {comp}", []).append(res)
                    print(f"round {rnd + 1} {kind:10} {comp:4}: CPU {res['cpu']:.2f} s (user {res['user']:.2f},"
                          f" sys {res['sys']:.2f}), wall {res['wall']:.1f} s, {res['received']}/{MESSAGES}"
                          f" received, maxrss {res['maxrss_mb']:.0f} MB, load {res['load']:.1f}, bag read before"
                          f" {warm_s:.2f} s, preempted {res['preempted']} times", flush=True)
    finally:
        for proc in reversed(procs):
            try:
                os.killpg(proc.pid, signal.SIGINT)
            except ProcessLookupError:
                pass
        for proc in procs:
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
        shutil.rmtree(home, ignore_errors=True)
        if not args.dir:
            shutil.rmtree(folder, ignore_errors=True)

    print(f"\nmedian CPU seconds over {args.rounds} round(s), load {args.load}:")
    summary: dict[str, dict[str, float]] = {}
    for comp in bags:
        med = {k: statistics.median(r["cpu"] for r in results[f"{k} {comp}"]) for k in kinds}
        complete = all(r["received"] == MESSAGES for k in kinds for r in results[f"{k} {comp}"])
        paired = paired_ratios(results[f"rostui {comp}"], results[f"rosbag {comp}"])
        summary[comp] = {**med, "rostui/rosbag": med["rostui"] / med["rosbag"],
                         "rostui/rosbag-cpp": med["rostui"] / med["rosbag-cpp"],
                         "rostui/rosbag by round": statistics.median(paired), "complete": complete}
        print(f"  {comp:4}: rosbag play {med['rosbag']:.2f} (its C++ play alone {med['rosbag-cpp']:.2f}),"
              f" rostui {med['rostui']:.2f}: rostui/rosbag {summary[comp]['rostui/rosbag']:.2f}x"
              f" (each round: {', '.join(f'{r:.2f}' for r in paired)}; their median"
              f" {summary[comp]['rostui/rosbag by round']:.2f}x),"
              f" rostui/C++ play {summary[comp]['rostui/rosbag-cpp']:.2f}x;"
              + "".join(f" {label} {med[label]:.2f} ({med[label] / med['rosbag']:.2f}x);" for label in exes
                        if label != "rostui")
              +
              f" every message delivered: {'yes' if complete else 'NO'}")
    if args.json:
        Path(args.json).write_text(json.dumps({"runs": results, "summary": summary}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
