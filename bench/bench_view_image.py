#!/usr/bin/env python3
"""`rostui view` on a 640x480 rgb8 camera at 30 Hz in a 100x40 terminal: CPU, bytes to the terminal, frames drawn.

A publisher process (this script in ``publish`` mode: rostui's AsyncNode,
60 precomputed frames of a moving scene, stamped) sends sensor_msgs/Image
at ``--rate`` Hz on the CPUs other than CPU 0; the master (`rostui core`)
runs there too.  The real `rostui view /camera/image_raw` runs on a
``--cols`` x ``--rows`` pseudo-terminal pinned to CPU 0 (cells of 10x20
pixels, given in TIOCSWINSZ), drawing with ``--graphics``: half blocks
(the default), ``kitty`` or ``sixel`` (``ROSTUI_VIEW_GRAPHICS``; a pty
answers no graphics query, so the choice is forced).
After a warm-up, over ``--seconds``:

- the viewer's CPU (psutil user+system time of its process), as cores and per frame drawn;
- the bytes it wrote to the terminal per second;
- frames sent (the publisher's count) and frames drawn and received (the
  view's own "N fps (M drawn)" line, averaged over the window).

In the same run, with the same publisher, real ``rostopic hz`` (rospy) is
measured on the same topic for the same time, pinned to CPU 0: what merely
receiving the camera costs a ROS tool.  The load average is printed: the
machine is shared.

    .venv/bin/python bench/bench_view_image.py
    .venv/bin/python bench/bench_view_image.py --rate 30 --seconds 20 --json out.json
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

TOPIC = "/camera/image_raw"
WIDTH, HEIGHT = 640, 480
RATES = re.compile(rb"([\d.]+) fps \(([\d.]+) drawn\)")


# -- publish mode (a separate process) --------------------------------------------------------
def scene(count: int) -> list[bytes]:
    """``count`` frames of a moving scene: colour gradients, a bright box sliding across, noise-free."""
    import numpy as np

    ys, xs = np.mgrid[0:HEIGHT, 0:WIDTH]
    frames = []
    for i in range(count):
        rgb = np.zeros((HEIGHT, WIDTH, 3), dtype=np.uint8)
        rgb[..., 0] = (xs * 255 // WIDTH + i * 4) % 256
        rgb[..., 1] = ys * 255 // HEIGHT
        rgb[..., 2] = 128 + ((xs + ys + i * 8) % 128)
        x0 = (i * 10) % (WIDTH - 120)
        rgb[180:300, x0:x0 + 120] = (255, 255, 0)
        frames.append(rgb.tobytes())
    return frames


async def publish(rate: float) -> None:
    """Publish the scene on :data:`TOPIC` at ``rate`` Hz until SIGINT; print how many frames went out."""
    frames = scene(60)

    def make(image: Any, n: int, period: float) -> Any:
        msg = image(height=HEIGHT, width=WIDTH, encoding="rgb8", is_bigendian=0, step=WIDTH * 3,
                    data=frames[n % len(frames)])
        msg.header.frame_id = "camera"
        return msg

    await publish_at(rate, "bench_camera", TOPIC, "sensor_msgs/Image", make)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rate", type=float, default=30.0)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--warmup", type=float, default=5.0)
    parser.add_argument("--cols", type=int, default=100)
    parser.add_argument("--rows", type=int, default=40)
    parser.add_argument("--graphics", choices=("halfblock", "kitty", "sixel"), default="halfblock")
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()

    results: dict[str, object] = {"graphics": args.graphics, "rate": args.rate, "seconds": args.seconds,
                                  "cols": args.cols, "rows": args.rows}
    figures = measure_view(__file__, TOPIC, RATES, rate=args.rate, seconds=args.seconds, warmup=args.warmup,
                           cols=args.cols, rows=args.rows, ROSTUI_VIEW_GRAPHICS=args.graphics)
    results.update(figures)

    load = os.getloadavg()
    print(f"rostui view {TOPIC}: {WIDTH}x{HEIGHT} rgb8 at {args.rate:g} Hz, {args.cols}x{args.rows} terminal, "
          f"{args.graphics}, {args.seconds:g} s (load average {load[0]:.1f} {load[1]:.1f})")
    print(f"  frames sent {results['sent_fps']:.1f}/s, received {results['received_fps']:.1f}/s, "
          f"drawn {results['drawn_fps']:.1f}/s")
    print(f"  viewer CPU {results['viewer_cores']:.2f} cores, {results['viewer_cpu_ms_per_frame_drawn']:.1f} ms "
          f"per frame drawn (target: under 0.5 cores)")
    print(f"  written to the terminal {results['bytes_per_second'] / 1e6:.2f} MB/s")
    print_peer(figures)
    if args.json:
        args.json.write_text(json.dumps(results, indent=2))
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "publish":
        sys.path.insert(0, str(REPO))
        asyncio.run(publish(float(sys.argv[sys.argv.index("--rate") + 1]) if "--rate" in sys.argv else 30.0))
    else:
        sys.exit(main())
