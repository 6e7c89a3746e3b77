"""What `rostui bag play` and `rostui bag record` run once their command line is read, without Typer.

`bag play` is read here too when its command line is plain
(:mod:`rostui.cli.bag_play_fast`): a player started from a script or a launch
file skips Typer's 16 ms of CPU.
"""

from __future__ import annotations

import os
import sys
import time
from typing import Callable, TextIO

from rostui.cli.common import fail


def ros_log(text: str) -> None:
    """``[ INFO] [secs]: text`` on stdout, as rosbag reports what it does."""
    print(f"[ INFO] [{time.time():.6f}]: {text}", flush=True)


def status_writer(stream: TextIO) -> Callable[[str], None]:
    """A status-line printer: rewritten in place on a terminal, cut short of its width (a line that wraps makes
    the terminal scroll at every update; the last columns are left for the terminal's echo of ^C), one line a
    second otherwise."""
    tty = stream.isatty()
    last = [0.0]

    def show(line: str) -> None:
        if tty:
            try:
                width = max(1, os.get_terminal_size(stream.fileno()).columns - 1 - len("^C"))
            except OSError:
                width = len(line)
            stream.write("\r" + line.rstrip()[:width].ljust(width))
            stream.flush()
            return
        now = time.monotonic()
        if now - last[0] >= 1.0:
            last[0] = now
            stream.write(line.rstrip() + "\n")
            stream.flush()
    return show


def split_ros_args(items: list[str]) -> tuple[list[str], list[str]]:
    """Separate ``name:=value`` (remappings, ``__name:=``...) from plain arguments."""
    ros = [a for a in items if ":=" in a]
    return [a for a in items if ":=" not in a], ros


def run_play(args: list[str], *, rate: float, loop_play: bool, pause: bool, start: float,
             duration: float | None, delay: float, clock: bool, hz: float, topics: list[str] | None,
             queue: int, quiet: bool) -> int:
    """Play bags; 1 with one line on error."""
    from rostui.core.bag.model import BagError
    from rostui.cli.bag_keys import TerminalKeys
    from rostui.core.node.engine import new_event_loop
    from rostui.tools.bag.player import PlayOptions, play

    files, ros_args = split_ros_args(args)
    opts = PlayOptions(files=files, rate=rate, loop=loop_play, start_paused=pause, start_s=start,
                       duration_s=duration, delay_s=delay, clock=clock, clock_hz=hz, topics=list(topics or []),
                       queue_size=queue)
    for path in files:
        ros_log(f"Opening {path}")
    if sys.stdin.isatty() and not quiet:
        print("\nWaiting %.1f seconds after advertising topics... done.\n\nHit space to toggle paused, "
              "or 's' to step." % delay, flush=True)
    status = None if quiet else status_writer(sys.stdout)
    # asyncio's loop: the player sleeps and sends without it, and it spares uvloop's import and OpenSSL's
    # (8 of 83 ms of CPU of a start; bench/README.md, "Bag play CPU", fifth pass)
    ev = new_event_loop(uvloop_wanted=False)
    try:
        ev.run_until_complete(play(opts, ros_args, status=status, controls=TerminalKeys()))
    except BagError as exc:
        fail(f"rostui bag play: {exc}")
    finally:
        ev.close()
    if not quiet:
        print("\nDone.", flush=True)
    return 0
