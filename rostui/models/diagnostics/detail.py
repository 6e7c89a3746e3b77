"""What the diagnostics app says about the status under the cursor: its word, its values and its history."""

from __future__ import annotations

import time

from .levels import level_name, severity
from .tree import DiagRow

__all__ = ["detail_lines", "summary_text", "format_age"]


def format_age(seconds: float) -> str:
    """``0.4 s``, ``12 s``, ``3 min``, ``2 h``: how long ago, to a sensible grain."""
    if seconds < 10:
        return f"{seconds:.1f} s"
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.0f} h"


def _clock(seconds: float) -> str:
    return time.strftime("%H:%M:%S", time.localtime(seconds))


def detail_lines(row: DiagRow | None, rows: list[DiagRow], now: float, *, history: int = 8) -> list[str]:
    """Lines about ``row`` (one of ``rows``): its name, level, message, hardware id, age and updates, its key/values,
    and the newest ``history`` changes of what it said; for a group without a status, what it holds."""
    if row is None:
        return ["no status selected"]
    record = row.record
    if record is None:
        below = [other for other in rows if other.name.startswith(row.name + "/") and other.record is not None]
        worst = max((other.level for other in below), key=severity, default=row.level)
        return [row.name, f"group: {len(below)} status{'' if len(below) == 1 else 'es'} below, the worst "
                          f"{level_name(worst)}"]
    said = f"{level_name(row.level)}"
    if row.level != record.level:
        said += f" (it said {level_name(record.level)}; nothing came for {format_age(record.age(now))})"
    lines = [record.name, f"{said} · {record.message or '(no message)'}",
             f"hardware id {record.hardware_id or '(none)'} · updated {format_age(record.age(now))} ago · "
             f"{record.updates} update{'' if record.updates == 1 else 's'}"]
    width = max((len(key) for key, _ in record.values), default=0)
    lines.extend(f"  {key:<{width}}  {value}" for key, value in record.values)
    changes = list(record.history)[-history:]
    if len(record.history) > 1 or (changes and changes[0].times > 1):
        lines.append("history (newest first):")
        for entry in reversed(changes):
            times = f" ×{entry.times}" if entry.times > 1 else ""
            lines.append(f"  {_clock(entry.since)}  {level_name(entry.level):<5}  {entry.message}{times}")
    return lines


def summary_text(topic: str, aggregated: bool, counts: dict[str, int]) -> str:
    """The line above the table: the topic shown and how many statuses are at each level, the worst first."""
    source = f"{topic} tree" if aggregated else f"{topic} flat (no aggregator)"
    if not counts:
        return f"{source} · no status yet"
    order = ["ERROR", "STALE", "WARN", "OK"]
    names = [name for name in order if counts.get(name)] + sorted(name for name in counts if name not in order)
    return f"{source} · " + ", ".join(f"{counts[name]} {name}" for name in names)
