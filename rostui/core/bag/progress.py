"""Progress of a whole-bag rewrite (convert, reindex, filter, compress), reported to a callback the caller gives."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Iterator
from typing import TypeVar

Progress = Callable[[int, int], None]
"""``progress(done, total)``: messages handled so far and the messages the file holds."""

_T = TypeVar("_T")
_EVERY_S = 0.1


def counted(items: Iterable[_T], total: int, progress: Progress | None) -> Iterator[_T]:
    """Yield ``items``, telling ``progress`` how many went by at most ten times a second, and once at the end."""
    if progress is None:
        yield from items
        return
    done = 0
    last = time.monotonic()
    progress(0, total)
    for item in items:
        yield item
        done += 1
        now = time.monotonic()
        if now - last >= _EVERY_S:
            last = now
            progress(done, total)
    progress(done, max(total, done))
