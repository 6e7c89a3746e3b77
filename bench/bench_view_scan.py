#!/usr/bin/env python3
"""`rostui view /scan` on a 720-point LaserScan at 40 Hz in a 100x40 terminal: CPU, bytes to the terminal, frames.

A publisher process (this script in ``publish`` mode: rostui's AsyncNode)
sends sensor_msgs/LaserScan (720 beams over 360 degrees: a 6 m x 4 m room
with a moving box, ranges recomputed each scan) at ``--rate`` Hz on the CPUs
other than CPU 0; the master (`rostui core`) runs there too.  The real
`rostui view /scan` runs on a ``--cols`` x ``--rows`` pseudo-terminal pinned to
CPU 0 (braille top-down view, at most 20 frames a second).  After a warm-up,
over ``--seconds``:

- the viewer's CPU (psutil user+system time of its process), as cores and per frame drawn;
- the bytes it wrote to the terminal per second;
- scans sent (the publisher's count), and scans received and frames drawn per
  second (the view's own "N msg/s (M drawn)" status, averaged over the window).

In the same run, with the same publisher, real ``rostopic hz`` (rospy) is
measured on the same topic for the same time, pinned to CPU 0: what merely
receiving the scans costs a ROS tool.  The load average is printed: the
machine is shared.

    .venv/bin/python bench/bench_view_scan.py
    .venv/bin/python bench/bench_view_scan.py --rate 40 --seconds 20 --json out.json
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import re
import sys
from pathlib import Path
from typing import Any


from _common import REPO
from _view_common import measure_view, print_peer, publish_at

TOPIC = "/scan"
BEAMS = 720
RATES = re.compile(rb"([\d.]+) msg/s \(([\d.]+) drawn\)")


# -- publish mode (a separate process) --------------------------------------------------------
def room_ranges(i: int) -> list[float]:
    """Scan ``i``: ranges from the centre of a 6 m x 4 m room with a 0.5 m box circling at 1.2 m."""
    import numpy as np

    angles = -np.pi + np.arange(BEAMS) * (2 * np.pi / BEAMS)
    c, s = np.cos(angles), np.sin(angles)
    with np.errstate(divide="ignore"):
        walls = np.minimum(np.where(c != 0, 3.0 / np.abs(c), np.inf), np.where(s != 0, 2.0 / np.abs(s), np.inf))
    centre = 1.2 * np.array([np.cos(i / 40), np.sin(i / 40)])
    bearing = np.arctan2(centre[1], centre[0])
    box = np.abs((angles - bearing + np.pi) % (2 * np.pi) - np.pi) < 0.2
    ranges = np.where(box, np.hypot(*centre) - 0.25, walls)
    return [float(r) for r in ranges]


async def publish(rate: float) -> None:
    """Publish scans on :data:`TOPIC` at ``rate`` Hz until SIGINT; print how many went out."""
    import math

    scans = [room_ranges(i) for i in range(250)]

    def make(scan_type: Any, n: int, period: float) -> Any:
        msg = scan_type(angle_min=-math.pi, angle_max=math.pi - 2 * math.pi / BEAMS,
                        angle_increment=2 * math.pi / BEAMS, time_increment=0.0, scan_time=period,
                        range_min=0.05, range_max=30.0, ranges=scans[n % len(scans)])
        msg.header.frame_id = "laser"
        return msg

    await publish_at(rate, "bench_laser", TOPIC, "sensor_msgs/LaserScan", make)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rate", type=float, default=40.0)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--warmup", type=float, default=5.0)
    parser.add_argument("--cols", type=int, default=100)
    parser.add_argument("--rows", type=int, default=40)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()

    results: dict[str, object] = {"rate": args.rate, "seconds": args.seconds,
                                  "cols": args.cols, "rows": args.rows}
    figures = measure_view(__file__, TOPIC, RATES, rate=args.rate, seconds=args.seconds, warmup=args.warmup,
                           cols=args.cols, rows=args.rows)
    results.update(figures)

    load = os.getloadavg()
    print(f"rostui view {TOPIC}: {BEAMS}-beam LaserScan at {args.rate:g} Hz, {args.cols}x{args.rows} terminal, "
          f"braille, {args.seconds:g} s (load average {load[0]:.1f} {load[1]:.1f})")
    print(f"  scans sent {results['sent_fps']:.1f}/s, received {results['received_fps']:.1f}/s, "
          f"frames drawn {results['drawn_fps']:.1f}/s")
    print(f"  viewer CPU {results['viewer_cores']:.2f} cores, {results['viewer_cpu_ms_per_frame_drawn']:.1f} ms "
          f"per frame drawn, {results['viewer_cpu_ms_per_message_received']:.1f} ms per scan received")
    print(f"  written to the terminal {results['bytes_per_second'] / 1e3:.1f} kB/s")
    print_peer(figures)
    if args.json:
        args.json.write_text(json.dumps(results, indent=2))
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "publish":
        sys.path.insert(0, str(REPO))
        asyncio.run(publish(float(sys.argv[sys.argv.index("--rate") + 1]) if "--rate" in sys.argv else 40.0))
    else:
        sys.exit(main())
