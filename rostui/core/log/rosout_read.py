"""Reading ``rosout.log`` files written by ROS's rosout node or by rostui.

Three line layouts are understood (see :mod:`rostui.core.log.rosout_log` for
the one rostui writes)::

    1795347562.722323656 INFO /talker [talker.py:6(<module>)] [topics: /chatter, /rosout] hello
    1795347562.722323656 INFO /talker [talker.py:6(<module>)] hello          (rosout/omit_topics set)
    1371234567.123456789 INFO [talker.cpp:12(main) [topics: /chatter, /rosout] hello   (rosout before Indigo)

A level rosout does not know is written as its number.  Lines that follow a
message line and are not message lines themselves continue that message (a
multi-line message); ``<stamp>  Node Startup`` lines and blank lines between
messages are rosout's session markers.  Anything else is a malformed line,
reported with its file and line number.
"""

from __future__ import annotations

import re
import sys
from collections import deque
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Iterator, NamedTuple, Sequence

from rostui.core.log.levels import Level
from rostui.core.log.rosout_log import format_rosout_line

__all__ = [
    "MalformedLine", "RosoutEntry", "RosoutLog", "RosoutLogError", "entry_line", "parse_rosout_lines",
    "read_rosout_log",
]

#: Malformed lines kept with their text (the rest are only counted).
KEPT_MALFORMED = 100

_LEVELS: dict[str, int] = {level.name: level.value for level in Level}

_STAMP = r"(?P<secs>\d+)\.(?P<frac>\d{1,9})"
_TOPICS = r"\[topics: (?P<topics>[^\]]*)\] "
_MODERN = re.compile(
    _STAMP + r" (?P<level>\S+) (?P<node>[^\s\[]\S*|) \[(?P<file>.*?):(?P<line>\d+)\((?P<function>.*?)\)\] "
    r"(?:" + _TOPICS + r")?(?P<msg>.*)\Z", re.DOTALL)
_OLD = re.compile(
    _STAMP + r" (?P<level>\S+) \[(?P<file>.*?):(?P<line>\d+)\((?P<function>.*?)\) " + _TOPICS + r"(?P<msg>.*)\Z",
    re.DOTALL)
_RECORD_START = re.compile(r"\d+\.\d+ \S+ (?:\S* )?\[")
_STARTUP = re.compile(r"\d+\.\d+  Node Startup\Z")


class RosoutLogError(Exception):
    """A log file that cannot be read, or holds no rosout.log line at all (``path[:line]: reason``)."""


class RosoutEntry(NamedTuple):
    """One log message: a rosgraph_msgs/Log's fields (or a rosout.log line's).

    ``stamp`` is nanoseconds since the epoch; ``level`` the Log level byte
    (DEBUG=1 ... FATAL=16, anything else as sent); ``source_line`` the line of
    the file it was read from (0 for live messages).
    """

    stamp: int
    level: int
    node: str
    message: str
    file: str
    line: int
    function: str
    topics: tuple[str, ...]
    source_line: int = 0

    @property
    def level_name(self) -> str:
        """``DEBUG`` ... ``FATAL``, or the number of an unknown level."""
        try:
            return Level(self.level).name
        except ValueError:
            return str(self.level)

    @property
    def location(self) -> str:
        """``file:function:line`` as rqt_console shows it (empty when the message has none)."""
        if not (self.file or self.function or self.line):
            return ""
        return f"{self.file}:{self.function}:{self.line}"


@dataclass(frozen=True)
class MalformedLine:
    """A line that is not part of any message: its 1-based number, text and what is wrong."""

    lineno: int
    text: str
    reason: str

    def where(self, path: str | Path) -> str:
        """``path:line: reason`` for one-line reports."""
        return f"{path}:{self.lineno}: {self.reason}"


@dataclass
class RosoutLog:
    """What :func:`read_rosout_log` found in one file.

    ``entries`` holds the newest ``keep`` messages at or above the minimum
    level; ``dropped`` counts older ones left out because of ``keep``,
    ``below_level`` those under the minimum level; ``malformed`` keeps the
    first :data:`KEPT_MALFORMED` bad lines, ``malformed_count`` counts all.
    """

    path: Path
    entries: list[RosoutEntry] = field(default_factory=list)
    malformed: list[MalformedLine] = field(default_factory=list)
    malformed_count: int = 0
    dropped: int = 0
    below_level: int = 0

    def malformed_summary(self) -> str:
        """One line about the bad lines (empty when there are none)."""
        if not self.malformed_count:
            return ""
        first = self.malformed[0].where(self.path)
        lines = "line" if self.malformed_count == 1 else "lines"
        return f"{self.malformed_count} malformed {lines} (first: {first})"


_interned_topics: dict[str, tuple[str, ...]] = {}


def _topics(text: str | None) -> tuple[str, ...]:
    if not text:
        return ()
    found = _interned_topics.get(text)
    if found is None:
        found = tuple(sys.intern(t) for t in text.split(", ") if t)
        if len(_interned_topics) < 10_000:
            _interned_topics[text] = found
    return found


_EXPECTED = "expected '<secs>.<nsecs> <LEVEL> <node> [<file>:<line>(<function>)] [topics: ...] <message>'"


def _parse_record(text: str, lineno: int) -> RosoutEntry | MalformedLine | None:
    """The message on a line, a MalformedLine for a line that starts like one but is not, or None."""
    match = _MODERN.match(text)
    if match is not None:
        secs, frac, level_text, node, file, line, function, topics, msg = match.groups()
    else:
        match = _OLD.match(text)
        if match is None:
            return MalformedLine(lineno, text, _EXPECTED) if _RECORD_START.match(text) else None
        secs, frac, level_text, file, line, function, topics, msg = match.groups()
        node = ""
    level = _LEVELS.get(level_text)
    if level is None:
        if not level_text.isdigit():
            return MalformedLine(lineno, text, f"unknown level '{level_text}'")
        level = int(level_text)
    nsecs = int(frac) if len(frac) == 9 else int(frac.ljust(9, "0"))
    return RosoutEntry(int(secs) * 1_000_000_000 + nsecs, level, sys.intern(node), msg, sys.intern(file), int(line),
                       sys.intern(function), _topics(topics), lineno)


def parse_rosout_lines(lines: Iterable[str]) -> Iterator[RosoutEntry | MalformedLine]:
    """Messages and malformed lines of a rosout.log, in file order.

    ``lines`` are the file's lines with or without their line ends.  A
    message's continuation lines are joined to it with ``\\n``; blank lines
    count as part of a message only when more text of it follows.
    """
    current: RosoutEntry | None = None
    extra: list[str] = []
    blanks = 0
    last_bad = 0
    for lineno, raw in enumerate(lines, 1):
        text = raw.rstrip("\n").removesuffix("\r")
        if "\x00" in text:
            result: RosoutEntry | MalformedLine | None = MalformedLine(lineno, text, "binary data (NUL bytes)")
        elif not text:
            blanks += 1
            continue
        elif text[0].isdigit() and (result := _parse_record(text, lineno)) is not None:
            pass
        elif _STARTUP.match(text):
            result = None
        elif current is not None:
            extra.extend([""] * blanks)
            extra.append(text)
            blanks = 0
            continue
        elif last_bad:
            result = MalformedLine(lineno, text, f"not a rosout.log line (follows malformed line {last_bad})")
        else:
            result = MalformedLine(lineno, text, "not a rosout.log line (no message line before it)")
        blanks = 0
        last_bad = lineno if isinstance(result, MalformedLine) else 0
        if current is not None:
            yield current._replace(message="\n".join([current.message, *extra])) if extra else current
            current, extra = None, []
        if isinstance(result, RosoutEntry):
            current = result
        elif result is not None:
            yield result
    if current is not None:
        yield current._replace(message="\n".join([current.message, *extra])) if extra else current


def read_rosout_log(path: str | Path, *, min_level: int = Level.DEBUG, keep: int | None = None) -> RosoutLog:
    """Read a rosout.log: messages at or above ``min_level`` (or of a level it cannot rank), the newest ``keep``.

    Raises :class:`RosoutLogError` when the file cannot be read, or when it has
    lines but none of them is a rosout.log message (the error names the first
    bad line as ``path:line``).  An empty file is an empty log.
    """
    path = Path(path)
    result = RosoutLog(path)
    entries: deque[RosoutEntry] = deque(maxlen=keep)
    try:
        with open(path, encoding="utf-8", errors="replace", newline="\n") as handle:
            for item in parse_rosout_lines(handle):
                if isinstance(item, MalformedLine):
                    result.malformed_count += 1
                    if len(result.malformed) < KEPT_MALFORMED:
                        result.malformed.append(item)
                elif item.level < min_level and item.level in _LEVELS.values():
                    result.below_level += 1
                else:
                    if keep is not None and len(entries) == keep:
                        result.dropped += 1
                    entries.append(item)
    except IsADirectoryError:
        raise RosoutLogError(f"{path}: is a directory, not a rosout.log") from None
    except OSError as exc:
        raise RosoutLogError(f"{path}: cannot read: {exc.strerror or exc}") from None
    result.entries = list(entries)
    seen = len(result.entries) + result.dropped + result.below_level
    if result.malformed_count and not seen:
        raise RosoutLogError(f"{result.malformed[0].where(path)} (not a rosout.log)")
    return result


def entry_line(entry: RosoutEntry) -> str:
    """The rosout.log line (with newline) for ``entry``, as rosout writes it."""
    return format_rosout_line(entry.stamp // 1_000_000_000, entry.stamp % 1_000_000_000, entry.level, entry.node,
                              entry.file, entry.line, entry.function, entry.topics, entry.message)


def entries_text(entries: Sequence[RosoutEntry]) -> str:
    """The rosout.log lines of ``entries`` joined (for saving a selection)."""
    return "".join(entry_line(e) for e in entries)
