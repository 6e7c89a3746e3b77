"""The median period of each topic of a bag (rosbag's ``frequency`` is 1 / it), exact, in memory bounded by a budget.

rosbag takes every message's stamp of a topic, in time order, as seconds (a
float), and the median of the differences between consecutive ones. Here the
differences are streamed from the bag's index a block at a time: a topic with at
most ``held`` periods has them gathered and sorted in the first pass; for a
longer one, each pass counts the periods by the leading bits of their float's
bit pattern (which orders non-negative floats as their values) around the
rank wanted (the range narrowed to the values seen), until the values around the
median are few enough to gather, or one value. Each pass reads the index again
(no payload): two for a steady rate, a few more for jittered periods.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
from typing import Any

BITS = 12
"""Each pass splits what is left of a rank's range into 2^BITS buckets."""


class _Target:
    """One rank wanted among a topic's periods, and the range of bit patterns known to hold it."""

    def __init__(self, rank: int, held: int) -> None:
        self.rank = rank
        self.lo = 0
        self.hi = (1 << 64) - 1
        self.below = 0  # periods below lo
        self.held = held
        self.value: int | None = None
        self.start_pass()

    def start_pass(self) -> None:
        import numpy as np

        self.shift = max(0, (self.hi - self.lo).bit_length() - BITS)
        self.hist = np.zeros(1 << BITS, dtype=np.int64)
        self.seen = 0
        self.least = self.hi
        self.most = self.lo
        self.kept: list[Any] | None = []

    def add(self, bits: Any) -> None:
        import numpy as np

        inside = bits[(bits >= np.uint64(self.lo)) & (bits <= np.uint64(self.hi))]
        if not inside.shape[0]:
            return
        self.seen += int(inside.shape[0])
        self.least = min(self.least, int(inside.min()))
        self.most = max(self.most, int(inside.max()))
        self.hist += np.bincount(((inside - np.uint64(self.lo)) >> np.uint64(self.shift)).astype(np.int64),
                                 minlength=1 << BITS)
        if self.kept is not None:
            if self.seen > self.held:
                self.kept = None
            else:
                self.kept.append(inside)

    def end_pass(self) -> None:
        import numpy as np

        want = self.rank - self.below
        if self.kept is not None:
            self.value = int(np.sort(np.concatenate(self.kept))[want]) if self.kept else None
            return
        if self.least == self.most:  # one value fills the range (a steady rate's period, to the last bit)
            self.value = self.least
            return
        cum = np.cumsum(self.hist)
        bucket = int(np.searchsorted(cum, want, side="right"))
        self.below += int(cum[bucket - 1]) if bucket else 0
        lo = self.lo + (bucket << self.shift)
        # the bucket, narrowed to the values seen: the next pass splits only the bits in which they differ
        self.lo, self.hi = max(lo, self.least), min(self.hi, lo + (1 << self.shift) - 1, self.most)
        if self.lo == self.hi:
            self.value = self.lo
        else:
            self.start_pass()


def _float(bits: int | None) -> float:
    """The float whose bit pattern is ``bits``."""
    import numpy as np

    return float(np.array([bits or 0], dtype=np.uint64).view(np.float64)[0])


def median_periods(passes: Callable[[], Iterator[tuple[Any, Any]]], topic_conns: Mapping[str, Iterable[int]],
                   held: int) -> dict[str, float]:
    """The median period (seconds) of each topic in ``topic_conns`` (its connection ids) with at least two
    messages.

    ``passes()`` reads the bag's index once: ``(times, connection ids)`` arrays, in time order; ``held`` bounds
    the periods gathered at once, over all topics.
    """
    import numpy as np

    each = max(64, held // max(1, 2 * len(topic_conns)))
    # the two middle ranks (the same one for an odd count), known once the first pass has counted the periods
    targets = {topic: [_Target(-1, each), _Target(-1, each)] for topic in topic_conns}
    conns = {topic: np.array(sorted(ids), dtype=np.uint32) for topic, ids in topic_conns.items()}
    medians: dict[str, float] = {}
    first = True
    while targets:
        last: dict[str, float] = {}
        for times, conn_ids in passes():
            for topic, mine_targets in targets.items():
                mine = np.isin(conn_ids, conns[topic])
                if not mine.any():
                    continue
                stamps = times[mine] / 1e9  # as rosbag: the stamp in seconds, then the difference
                before = last.get(topic)
                periods = np.diff(stamps, prepend=before) if before is not None else np.diff(stamps)
                last[topic] = float(stamps[-1])
                bits = periods.view(np.uint64)
                for target in mine_targets:
                    if target.value is None:
                        target.add(bits)
        for topic in list(targets):
            pair = targets[topic]
            if first:
                n = pair[0].seen
                if not n:
                    del targets[topic]
                    continue
                pair[0].rank, pair[1].rank = (n - 1) // 2, n // 2
                if n % 2:
                    pair[1].value = -1  # the same rank as the first: its value is the first's
            for target in pair:
                if target.value is None:
                    target.end_pass()
        first = False
        done = [topic for topic, pair in targets.items() if all(t.value is not None for t in pair)]
        for topic in done:
            first_rank, second_rank = targets.pop(topic)
            a = _float(first_rank.value)
            medians[topic] = a if second_rank.value == -1 else float(a + _float(second_rank.value)) / 2
    return medians
