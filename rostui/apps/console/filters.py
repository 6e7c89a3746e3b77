"""What the console shows: level, node and text filters, and highlight rules.

A :class:`FilterSpec` is a plain value; :func:`compile_filter` turns it into
one predicate over :class:`~rostui.core.log.rosout_read.RosoutEntry` that
tests only what is switched on.  Text search is case-insensitive and looks
at the message; a regular expression is used as written (``(?i)`` for case).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace
from typing import Callable, Iterable

from rostui.core.log.levels import Level
from rostui.core.log.rosout_read import RosoutEntry

__all__ = [
    "ALL_LEVELS", "FilterError", "FilterSpec", "HighlightRule", "Predicate", "compile_filter", "compile_text",
    "first_highlight", "levels_from",
]

#: The five Log levels (DEBUG .. FATAL) as bytes.
ALL_LEVELS: frozenset[int] = frozenset(int(level) for level in Level)

Predicate = Callable[[RosoutEntry], bool]


class FilterError(ValueError):
    """A search or highlight pattern that is not a valid regular expression."""


def levels_from(min_level: int) -> frozenset[int]:
    """The levels at or above ``min_level``."""
    return frozenset(level for level in ALL_LEVELS if level >= min_level)


def compile_text(pattern: str, regex: bool) -> Callable[[str], object]:
    """A ``search(text)`` function, truthy when ``text`` matches: a regular expression, or plain text in any case.

    Raises :class:`FilterError` for an invalid regular expression.
    """
    if not regex:
        needle = pattern.lower()
        return lambda text: needle in text.lower()
    try:
        return re.compile(pattern).search
    except re.error as exc:
        raise FilterError(f"bad regular expression {pattern!r}: {exc}") from None


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


def compile_filter(spec: FilterSpec) -> Predicate | None:
    """One predicate for ``spec``, or None when it lets everything through.

    Raises :class:`FilterError` when ``spec.search`` is an invalid regular expression.
    """
    tests: list[Predicate] = []
    if not spec.levels >= ALL_LEVELS:
        hidden = ALL_LEVELS - spec.levels
        tests.append(lambda e: e.level not in hidden)
    if spec.include_nodes:
        include = spec.include_nodes
        tests.append(lambda e: e.node in include)
    if spec.exclude_nodes:
        exclude = spec.exclude_nodes
        tests.append(lambda e: e.node not in exclude)
    if spec.search:
        search = compile_text(spec.search, spec.regex)
        tests.append(lambda e: bool(search(e.message)))
    if not tests:
        return None
    if len(tests) == 1:
        return tests[0]
    frozen = tuple(tests)
    return lambda e: all(test(e) for test in frozen)


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
