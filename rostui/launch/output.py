"""A node's captured output: the last lines it wrote to stdout and stderr, kept in a bounded ring.

With ``rostui launch --tui`` the terminal belongs to the monitor, so each
node's stdout and stderr come through pipes: :func:`pump` reads one pipe,
splits it into lines, appends them to the node's :class:`OutputBuffer` and,
for stdout that roslaunch would log, also writes the bytes to the node's
``-stdout.log`` file.  Lines carry a sequence number so a reader can ask for
everything written since the last line it saw.
"""

from __future__ import annotations

import asyncio
from collections import deque
from dataclasses import dataclass
from typing import IO, Iterator

#: Lines a node's buffer keeps (the oldest are dropped first).
DEFAULT_MAX_LINES = 5000
#: Bytes read from a pipe at once.
CHUNK = 65536
#: A line longer than this is cut into pieces (a node writing without newlines cannot grow memory).
MAX_LINE = 16384


@dataclass(frozen=True, slots=True)
class OutputLine:
    """One line of output: its sequence number, where it came from (stdout, stderr or launch) and its text."""

    seq: int
    stream: str
    text: str


class OutputBuffer:
    """The last ``max_lines`` lines of one node (or of the launcher itself), oldest first."""

    def __init__(self, max_lines: int = DEFAULT_MAX_LINES) -> None:
        """An empty buffer keeping at most ``max_lines`` lines."""
        self._lines: deque[OutputLine] = deque(maxlen=max_lines)
        self.next_seq = 0

    def append(self, stream: str, text: str) -> None:
        """Add one line (without its newline)."""
        self._lines.append(OutputLine(self.next_seq, stream, text))
        self.next_seq += 1

    @property
    def dropped(self) -> int:
        """How many lines fell out of the ring."""
        return self.next_seq - len(self._lines)

    def since(self, seq: int) -> Iterator[OutputLine]:
        """The kept lines whose sequence number is ``seq`` or later."""
        first = self.next_seq - len(self._lines)
        start = max(0, seq - first)
        for index in range(start, len(self._lines)):
            yield self._lines[index]

    def __len__(self) -> int:
        return len(self._lines)


async def pump(reader: asyncio.StreamReader, buffer: OutputBuffer, stream: str,
               log: IO[bytes] | None = None) -> None:
    """Copy a pipe into ``buffer`` line by line (and its raw bytes into ``log``) until end of file."""
    pending = b""
    while True:
        chunk = await reader.read(CHUNK)
        if not chunk:
            break
        if log is not None and not log.closed:
            log.write(chunk)
            log.flush()
        pending += chunk
        *complete, pending = pending.split(b"\n")
        for raw in complete:
            _append(buffer, stream, raw)
        while len(pending) > MAX_LINE:
            _append(buffer, stream, pending[:MAX_LINE])
            pending = pending[MAX_LINE:]
        await asyncio.sleep(0)  # a node that never stops writing must not starve the rest of the loop
    if pending:
        _append(buffer, stream, pending)


def _append(buffer: OutputBuffer, stream: str, raw: bytes) -> None:
    buffer.append(stream, raw.rstrip(b"\r").decode("utf-8", errors="replace"))
