"""Statuses as rows to draw: the aggregator's paths as a tree, or the flat topic's names in order, filtered.

The aggregator's names are paths; each row sits under the row of its path's parent, children in name order,
drawn with the same branches as the tf tree. A group the aggregator did not publish a status for still gets a
row, at the worst level of what it holds. The flat topic's statuses are one list in name order. A filter keeps
the rows at or above a level whose names hold a text, with the groups above them, so a kept row is never
without its place in the tree.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from datetime import datetime, timezone
from functools import cached_property
from typing import Callable

from .levels import level_name, severity
from .store import StatusRecord, StatusTable

__all__ = ["DiagRow", "Filter", "tree_rows", "flat_rows", "counts", "format_tree", "format_rosdiagnostic"]


@dataclass(frozen=True)
class Filter:
    """Rows shown: at least ``level`` (by severity) and, when ``text`` is given, names it matches.

    ``text`` is a regular expression searched in the name, as rosdiagnostic's ``--filter``, with smart case: it
    ignores case unless it holds a capital letter. Text that is not a valid expression (``[`` while it is being
    typed) matches as plain text.
    """

    level: int = 0
    text: str = ""

    def keeps(self, name: str, level: int) -> bool:
        """Whether a status called ``name`` at ``level`` is shown for itself."""
        return severity(level) >= severity(self.level) and (not self.text or self._matcher(name))

    @cached_property
    def _matcher(self) -> Callable[[str], bool]:
        flags = 0 if any(c.isupper() for c in self.text) else re.IGNORECASE
        try:
            pattern = re.compile(self.text, flags)
        except re.error:
            needle = self.text if flags == 0 else self.text.lower()
            return lambda name: needle in (name if flags == 0 else name.lower())
        return lambda name: pattern.search(name) is not None

    @property
    def active(self) -> bool:
        """Whether it hides anything at all."""
        return bool(self.level or self.text)


@dataclass(frozen=True)
class DiagRow:
    """One row: the status's full ``name`` (its key), the branches and ``short`` name to draw, its level at the
    moment the rows were made, and its record (None for a group the aggregator did not publish)."""

    name: str
    short: str
    prefix: str
    depth: int
    level: int
    record: StatusRecord | None

    @property
    def label(self) -> str:
        """The branches and the short name."""
        return self.prefix + self.short

    @property
    def message(self) -> str:
        """What the status says (a group without a status of its own: nothing)."""
        return self.record.message if self.record is not None else ""


def _parts(name: str) -> list[str]:
    return [part for part in name.split("/") if part] or [name]


def tree_rows(table: StatusTable, now: float, stale_after: float, only: Filter = Filter()) -> list[DiagRow]:
    """The aggregator's statuses as a tree (walked without recursion), filtered by ``only``."""
    levels: dict[str, int] = {}
    children: dict[str, set[str]] = {"": set()}
    for name, record in table.records.items():
        path = "/" + "/".join(_parts(name))
        levels[path] = record.level_at(now, stale_after)
        parent = ""
        for part in _parts(name):
            node = f"{parent}/{part}"
            children.setdefault(parent, set()).add(node)
            children.setdefault(node, set())
            parent = node
    records = {"/" + "/".join(_parts(name)): record for name, record in table.records.items()}
    level_of = _fill_levels(children, levels)
    kept = _kept(children, level_of, only)
    rows: list[DiagRow] = []
    stack: list[tuple[str, int, tuple[bool, ...], bool]] = [
        (top, 0, (), False) for top in sorted(children[""], reverse=True) if top in kept]
    while stack:
        node, depth, marks, last = stack.pop()
        prefix = "" if depth == 0 else "".join("   " if done else "│  " for done in marks) + ("└─ " if last else "├─ ")
        rows.append(DiagRow(node, node.rsplit("/", 1)[1], prefix, depth, level_of[node], records.get(node)))
        kids = sorted(kid for kid in children[node] if kid in kept)
        below = () if depth == 0 else marks + (last,)
        for i in range(len(kids) - 1, -1, -1):
            stack.append((kids[i], depth + 1, below, i == len(kids) - 1))
    return rows


def _fill_levels(children: dict[str, set[str]], levels: dict[str, int]) -> dict[str, int]:
    """Each node's level: its own status's, or for a group without one the worst of what it holds."""
    filled = dict(levels)
    order: list[str] = []
    stack = [""]
    while stack:
        node = stack.pop()
        order.append(node)
        stack.extend(children[node])
    for node in reversed(order):
        if node and node not in filled:
            kids = [filled[kid] for kid in children[node] if kid in filled]
            filled[node] = max(kids, key=severity) if kids else 0
    return filled


def _kept(children: dict[str, set[str]], level_of: dict[str, int], only: Filter) -> set[str]:
    """The nodes the filter keeps for themselves, and every group above them."""
    if not only.active:
        return set(level_of) - {""}
    kept: set[str] = set()
    for node, level in level_of.items():
        if node and only.keeps(node, level):
            parts = node.split("/")[1:]
            kept.update("/" + "/".join(parts[:i]) for i in range(1, len(parts) + 1))
    return kept


def flat_rows(table: StatusTable, now: float, stale_after: float, only: Filter = Filter()) -> list[DiagRow]:
    """The flat topic's statuses in name order, filtered by ``only``."""
    rows = []
    for name in sorted(table.records):
        record = table.records[name]
        level = record.level_at(now, stale_after)
        if only.keeps(name, level):
            rows.append(DiagRow(name, name, "", 0, level, record))
    return rows


def counts(rows: list[DiagRow]) -> dict[str, int]:
    """How many statuses (not groups without one) are at each level, by the level's name."""
    said: dict[str, int] = {}
    for row in rows:
        if row.record is not None:
            said[level_name(row.level)] = said.get(level_name(row.level), 0) + 1
    return said


def format_tree(rows: list[DiagRow], *, values: bool = False) -> str:
    """The rows as text for a terminal or a script: ``[LEVEL] label: message``, and with ``values`` each
    status's hardware id and key/values under it."""
    width = max((len(level_name(row.level)) for row in rows), default=0) + 2
    lines = []
    for row in rows:
        level = f"[{level_name(row.level)}]".ljust(width)
        lines.append(f"{level} {row.label}" + (f": {row.message}" if row.message else ""))
        if values and row.record is not None:
            pad = " " * (width + 1 + len(row.prefix) + 2)
            if row.record.hardware_id:
                lines.append(f"{pad}hardware_id: {row.record.hardware_id}")
            lines.extend(f"{pad}{key}: {value}" for key, value in row.record.values)
    return "\n".join(lines)


#: rosdiagnostic's level marks, plain and in colour.
_MARKS = {0: " OK  ", 1: "WARN ", 2: "ERROR", 3: "STALE"}
_COLOURS = {0: "92", 1: "93", 2: "91", 3: "94"}
_RULE, _THIN = "=" * 69, "-" * 69


def _local_time(seconds: float) -> str:
    return str(datetime.fromtimestamp(seconds, timezone.utc).astimezone())


def format_rosdiagnostic(table: StatusTable, only: Filter, *, detail: bool = False, color: bool = False) -> str:
    """The table's last message as ``rosdiagnostic`` prints one: its leaves (statuses no other is under), the
    worst first, at least ``only.level`` and matching ``only.text``, between the banners; with ``detail`` the
    stamp, hardware id and key/values of each."""
    records = list(table.records.values())
    parents = {record.name.rsplit("/", 1)[0] if "/" in record.name else "" for record in records}
    leaves = [record for record in records if record.name not in parents]
    stamp = table.stamp if table.stamp is not None else 0.0
    lines = [_RULE, f"Diagnostics generated on: {_local_time(stamp)}", _THIN]
    for record in sorted(leaves, key=lambda r: r.level, reverse=True):
        if record.level < only.level or not only.keeps(record.name, record.level):
            continue
        mark = _MARKS.get(record.level, str(record.level).center(5))
        if color:
            mark = f"\033[{_COLOURS.get(record.level, '91')}m{mark}\033[0m"
        lines.append(f"[ {mark} ] {record.name} - {record.message}")
        if detail:
            lines.append(f"    timestamp:   {_local_time(stamp)}")
            lines.append(f"    hardware_id: {record.hardware_id}")
            lines.extend(f"    - {key}: {value}" for key, value in record.values)
    lines.append(_RULE)
    return "\n".join(lines)
