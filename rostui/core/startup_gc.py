"""The cyclic garbage collector while a command starts: rare collections, then its start-up left alone for good.

A command's start (Typer, asyncio, a node's modules, a bag's index, the node's registration) makes a few
hundred thousand objects and next to no garbage.  At Python's default first threshold (a collection every
700 new objects) the collector walks them again and again, and at exit the interpreter's teardown walks
them once more: 27 ms of the 120 ms of CPU that ``rostui bag play`` spent on a ten-message bag
(bench/README.md, "Bag play CPU", fifth pass).  The CLI calls :func:`collect_rarely` before its commands
load; a node calls :func:`start_up_done` once it has started, which freezes what is alive (``gc.freeze``:
later collections and the teardown skip it) and restores the threshold.  A command that starts no node
keeps collecting, every :data:`START_THRESHOLD` new objects.
"""

from __future__ import annotations

import gc

START_THRESHOLD = 100_000
"""The collector's first threshold while a command starts (new container objects between two collections)."""

_saved: tuple[int, int, int] | None = None


def collect_rarely() -> None:
    """Raise the collector's first threshold to :data:`START_THRESHOLD` until :func:`start_up_done`."""
    global _saved
    if _saved is None:
        _saved = gc.get_threshold()
        gc.set_threshold(START_THRESHOLD, _saved[1], _saved[2])


def start_up_done() -> None:
    """After :func:`collect_rarely`: move every object alive now out of the collector's reach for good and
    restore its thresholds.  Nothing otherwise (a script's own node leaves its collector as it was)."""
    global _saved
    if _saved is not None:
        gc.freeze()
        gc.set_threshold(*_saved)
        _saved = None
