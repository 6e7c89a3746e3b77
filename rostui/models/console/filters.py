"""What the console shows: level, node and text filters, and highlight rules.

A :class:`FilterSpec` is a plain value; :func:`compile_filter` turns it into
one predicate over :class:`~rostui.core.log.rosout_read.RosoutEntry` that
tests only what is switched on.  Text search is case-insensitive and looks
at the message; a regular expression is used as written (``(?i)`` for case).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from itertools import repeat
from operator import contains, itemgetter, not_
from typing import Callable, Iterable, Sequence

from rostui.core.log.levels import Level
from rostui.core.log.rosout_read import RosoutEntry

__all__ = [
    "ALL_LEVELS", "LEVEL", "MESSAGE", "NODE", "FilterError", "FilterSpec", "HighlightRule", "Predicate", "Selector",
    "compile_filter", "compile_selector", "compile_text", "first_highlight",
]

#: Positions of the fields filters read, in a RosoutEntry or the plain tuple the model keeps.
LEVEL = RosoutEntry._fields.index("level")
NODE = RosoutEntry._fields.index("node")
MESSAGE = RosoutEntry._fields.index("message")

#: The five Log levels (DEBUG .. FATAL) as bytes.
ALL_LEVELS: frozenset[int] = frozenset(int(level) for level in Level)

#: A test on a message: a RosoutEntry, or the plain tuple of its fields.
Predicate = Callable[[tuple], bool]

#: Truthy values for a list of messages, one per message (see :func:`compile_selector`).
Selector = Callable[[Sequence[tuple]], Iterable[object]]

_level, _node, _message = itemgetter(LEVEL), itemgetter(NODE), itemgetter(MESSAGE)


class FilterError(ValueError):
    """A search or highlight pattern that is not a valid regular expression."""


def _regex(pattern: str) -> re.Pattern[str]:
    try:
        return re.compile(pattern)
    except re.error as exc:
        raise FilterError(f"bad regular expression {pattern!r}: {exc}") from None


def compile_text(pattern: str, regex: bool) -> Callable[[str], object]:
    """A ``search(text)`` function, truthy when ``text`` matches: a regular expression, or plain text in any case.

    Raises :class:`FilterError` for an invalid regular expression.
    """
    if regex:
        return _regex(pattern).search
    needle = pattern.lower()
    return lambda text: needle in text.lower()


@dataclass(frozen=True)
class FilterSpec:
    """The console's filters; messages must pass all of them to be shown.

    ``levels`` are the level bytes shown (a level outside DEBUG..FATAL is
    always shown); ``include_nodes``, when not empty, are the only nodes
    shown; ``exclude_nodes`` are hidden; ``search`` must occur in the message.
    """

    levels: frozenset[int] = ALL_LEVELS
    include_nodes: frozenset[str] = frozenset()
    exclude_nodes: frozenset[str] = frozenset()
    search: str = ""
    regex: bool = False

    def toggle_level(self, level: int) -> "FilterSpec":
        """This spec with ``level`` shown if it was hidden and hidden if it was shown."""
        return replace(self, levels=self.levels ^ {level})

    def toggle_include(self, node: str) -> "FilterSpec":
        """Add ``node`` to the nodes shown exclusively, or take it out again."""
        return replace(self, include_nodes=self.include_nodes ^ {node}, exclude_nodes=self.exclude_nodes - {node})

    def toggle_exclude(self, node: str) -> "FilterSpec":
        """Hide ``node``'s messages, or show them again."""
        return replace(self, exclude_nodes=self.exclude_nodes ^ {node}, include_nodes=self.include_nodes - {node})

    def without_nodes(self) -> "FilterSpec":
        """This spec with no node filters."""
        return replace(self, include_nodes=frozenset(), exclude_nodes=frozenset())

    @property
    def is_open(self) -> bool:
        """True when nothing is filtered out."""
        return (self.levels >= ALL_LEVELS and not self.include_nodes and not self.exclude_nodes
                and not self.search)


def compile_selector(spec: FilterSpec) -> Selector | None:
    """A function giving, for a list of messages, one truthy value per message that passes ``spec``.

    None when ``spec`` lets everything through.  The work runs in C-level
    ``map`` chains, so filtering 100 000 messages takes milliseconds.
    Raises :class:`FilterError` when ``spec.search`` is an invalid regular expression.
    """
    parts: list[Selector] = []
    if not spec.levels >= ALL_LEVELS:
        hidden = (ALL_LEVELS - spec.levels).__contains__
        parts.append(lambda msgs: map(not_, map(hidden, map(_level, msgs))))
    if spec.include_nodes:
        include = spec.include_nodes.__contains__
        parts.append(lambda msgs: map(include, map(_node, msgs)))
    if spec.exclude_nodes:
        exclude = spec.exclude_nodes.__contains__
        parts.append(lambda msgs: map(not_, map(exclude, map(_node, msgs))))
    if spec.search and spec.regex:
        search = _regex(spec.search).search
        parts.append(lambda msgs: map(search, map(_message, msgs)))
    elif spec.search:
        needle = spec.search.lower()
        parts.append(lambda msgs: map(contains, map(str.lower, map(_message, msgs)), repeat(needle)))
    if not parts:
        return None
    if len(parts) == 1:
        return parts[0]
    frozen = tuple(parts)
    return lambda msgs: map(all, zip(*(part(msgs) for part in frozen)))


def compile_filter(spec: FilterSpec) -> Predicate | None:
    """One predicate for single messages (see :func:`compile_selector`), or None when everything passes."""
    select = compile_selector(spec)
    if select is None:
        return None
    return lambda entry: bool(next(iter(select((entry,)))))


@dataclass(frozen=True)
class HighlightRule:
    """Messages whose text matches ``pattern`` are marked with the rule's colour."""

    pattern: str
    regex: bool = False
    search: Callable[[str], object] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "search", compile_text(self.pattern, self.regex))

    def matches(self, entry: RosoutEntry) -> bool:
        """True when the entry's message matches."""
        return bool(self.search(entry.message))


def first_highlight(rules: Iterable[HighlightRule], entry: RosoutEntry) -> int:
    """The index of the first rule matching ``entry``, or -1."""
    for index, rule in enumerate(rules):
        if rule.search(entry.message):
            return index
    return -1
