#!/usr/bin/env python3
"""rostui's ``rosbag`` module against Debian's in the same run: reading 100k messages, and appending to a bag.

A bag of ``--messages`` messages (std_msgs/String, std_msgs/Int32 and geometry_msgs/PoseStamped in turn,
1 ms apart) is written by Debian's rosbag. The same read script then runs under Debian's ``/usr/bin/python3``
and under ``rostui python --rostui``, in alternating order for ``--rounds`` rounds:

- ``read``: ``for topic, msg, t in bag.read_messages()`` (every message deserialised);
- ``raw``: the same with ``raw=True``;
- ``read mcap``: rostui only, the same messages from an MCAP copy;
- ``append``: open the bag with ``'a'``, write one message, close (the time includes the interpreter's start).

Each figure is the median over rounds, in messages per second (``append``: seconds), measured inside the
script from just before ``rosbag.Bag(...)`` to after the loop; the ratio is rostui / Debian.

    .venv/bin/python bench/bench_rosbag_api.py [--messages 100000] [--rounds 3] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SYSTEM_PYTHON = "/usr/bin/python3"

WRITE = textwrap.dedent('''
    import sys, rosbag, genpy
    from std_msgs.msg import Int32, String
    from geometry_msgs.msg import PoseStamped
    with rosbag.Bag(sys.argv[1], 'w') as bag:
        for i in range(int(sys.argv[2])):
            t = genpy.Time(1000 + i * 0.001)
            if i % 3 == 0:
                bag.write('/chatter', String(data='hello %d' % i), t)
            elif i % 3 == 1:
                bag.write('/numbers', Int32(data=i), t)
            else:
                p = PoseStamped()
                p.header.seq, p.header.stamp, p.header.frame_id = i, t, 'map'
                p.pose.position.x = i
                bag.write('/pose', p, t)
''')

READ = textwrap.dedent('''
    import sys, time, rosbag
    start = time.perf_counter()
    n = 0
    with rosbag.Bag(sys.argv[1]) as bag:
        for topic, msg, t in bag.read_messages(raw=sys.argv[2] == 'raw'):
            n += 1
    print(n, time.perf_counter() - start)
''')

APPEND = textwrap.dedent('''
    import sys, rosbag, genpy
    from std_msgs.msg import Int32
    with rosbag.Bag(sys.argv[1], 'a') as bag:
        bag.write('/added', Int32(data=1), genpy.Time(5000))
''')


def _env() -> dict[str, str]:
    return {k: v for k, v in os.environ.items()
            if k not in ("PYTHONPATH", "ROS_PACKAGE_PATH") and not k.startswith("ROSTUI_PYTHON")}


def _cmd(who: str) -> list[str]:
    if who == "debian":
        return [SYSTEM_PYTHON]
    return [sys.executable, "-m", "rostui", "python", "--rostui"]


def _run(who: str, args: list[str], cwd: Path) -> str:
    r = subprocess.run([*_cmd(who), *args], env=_env(), cwd=cwd, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        raise SystemExit(f"{who} {' '.join(args)} failed:\n{r.stderr}")
    return r.stdout


def _rate(who: str, bag: str, mode: str, cwd: Path, expected: int) -> float:
    count, seconds = _run(who, ["read.py", bag, mode], cwd).split()
    if int(count) != expected:
        raise SystemExit(f"{who} read {count} of {expected} messages from {bag}")
    return expected / float(seconds)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--messages", type=int, default=100_000)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()
    results: dict[str, dict[str, list[float]]] = {"debian": {}, "rostui": {}}
    with tempfile.TemporaryDirectory(prefix="rostui-bench-rosbag-") as tmp:
        work = Path(tmp)
        for name, text in (("write.py", WRITE), ("read.py", READ), ("append.py", APPEND)):
            (work / name).write_text(text)
        _run("debian", ["write.py", "in.bag", str(args.messages)], work)
        _run("rostui", ["write.py", "in.mcap", str(args.messages)], work)
        print(f"{args.messages} messages: in.bag {(work / 'in.bag').stat().st_size / 1e6:.1f} MB", flush=True)
        for round_ in range(args.rounds):
            order = ["debian", "rostui"] if round_ % 2 == 0 else ["rostui", "debian"]
            for who in order:
                rows = results[who]
                rows.setdefault("read", []).append(_rate(who, "in.bag", "read", work, args.messages))
                rows.setdefault("raw", []).append(_rate(who, "in.bag", "raw", work, args.messages))
                if who == "rostui":
                    rows.setdefault("read mcap", []).append(_rate(who, "in.mcap", "read", work, args.messages))
                shutil.copy(work / "in.bag", work / f"append-{who}.bag")
                start = time.perf_counter()
                _run(who, ["append.py", f"append-{who}.bag"], work)
                rows.setdefault("append", []).append(time.perf_counter() - start)
    print(f"{'':12} {'debian':>12} {'rostui':>12} {'ratio':>8}")
    summary: dict[str, dict[str, float]] = {}
    for metric in ("read", "raw", "read mcap", "append"):
        deb = statistics.median(results["debian"][metric]) if metric in results["debian"] else None
        ours = statistics.median(results["rostui"][metric])
        unit = "s" if metric == "append" else "msg/s"
        ratio = f"{ours / deb:.2f}x" if deb else "-"
        print(f"{metric:12} {f'{deb:,.0f}' if deb and unit == 'msg/s' else (f'{deb:.2f}' if deb else '-'):>12} "
              f"{f'{ours:,.0f}' if unit == 'msg/s' else f'{ours:.2f}':>12} {ratio:>8}  ({unit}, median of "
              f"{args.rounds})")
        summary[metric] = {"debian": deb or 0.0, "rostui": ours}
    if args.json:
        args.json.write_text(json.dumps({"messages": args.messages, "rounds": args.rounds, "results": results,
                                         "median": summary}, indent=2))


if __name__ == "__main__":
    main()
