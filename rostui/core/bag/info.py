"""``rostui bag info``: rosbag info's fields for MCAP and ``.bag`` files, as text or a JSON-ready dict."""

from __future__ import annotations

import time
from typing import Any

from rostui.core.bag.files import open_reader
from rostui.core.bag.model import BagSummary


def human_size(size: float) -> str:
    """``81.5 KB`` as rosbag info writes sizes (never in bytes: 512 bytes are ``0.5 KB``)."""
    for unit in ("KB", "MB", "GB", "TB"):
        size /= 1024.0
        if size < 1024.0 or unit == "TB":
            break
    return f"{size:.1f} {unit}"


def status_size(size: float) -> str:
    """``123 B``, ``4.5 KB``, ``6.7 MB``: a size in a live status line (whole bytes below 1 KB)."""
    for unit in ("B", "KB", "MB", "GB"):
        if size < 1024 or unit == "GB":
            return f"{int(size)} B" if unit == "B" else f"{size:.1f} {unit}"
        size /= 1024
    return f"{size:.1f} GB"


def human_duration(seconds: float) -> str:
    """``12.3s``, ``1:05s (65s)`` or ``1:01:05s (3665s)`` as rosbag info writes durations."""
    if seconds < 60:
        return f"{seconds:.1f}s"
    whole = int(round(seconds))
    hours, rest = divmod(whole, 3600)
    minutes, secs = divmod(rest, 60)
    clock = f"{hours}:{minutes:02d}:{secs:02d}" if hours else f"{minutes}:{secs:02d}"
    return f"{clock}s ({whole}s)"


def human_time(ns: int) -> str:
    """``Nov 22 2026 15:11:02.32 (1795360262.32)`` in local time."""
    hundredths = round(ns / 1e7)
    whole, frac = divmod(hundredths, 100)
    return f"{time.strftime('%b %d %Y %H:%M:%S', time.localtime(whole))}.{frac:02d} ({whole}.{frac:02d})"


def summarize(path: str) -> BagSummary:
    """Read a file's summary (BagError for anything that is not a readable bag)."""
    reader = open_reader(path)
    try:
        return reader.summary()
    finally:
        reader.close()


def _topics(summary: BagSummary) -> list[tuple[str, int, list[str], int]]:
    """``(topic, messages, types, connections)`` per topic, sorted by name."""
    rows: dict[str, tuple[int, list[str], int]] = {}
    for conn in summary.connections:
        count, types, conns = rows.get(conn.topic, (0, [], 0))
        if conn.type not in types:
            types = [*types, conn.type]
        rows[conn.topic] = (count + summary.counts.get(conn.id, 0), types, conns + 1)
    return [(t, *rows[t]) for t in sorted(rows)]


def info_dict(summary: BagSummary) -> dict[str, Any]:
    """The ``--json`` form of info."""
    types = {c.type: c.md5sum for c in summary.connections}
    return {
        "path": summary.path,
        "format": summary.format,
        "version": summary.version,
        "closed": summary.closed,
        "problem": summary.problem or None,
        "duration": (summary.end_ns - summary.start_ns) / 1e9,
        "start": summary.start_ns / 1e9,
        "end": summary.end_ns / 1e9,
        "size": summary.size,
        "messages": summary.message_count,
        "compression": summary.chunk_compression,
        "chunk_bytes": {kind: {"uncompressed": plain, "stored": stored}
                        for kind, (plain, stored) in summary.chunk_bytes.items()},
        "types": [{"type": t, "md5sum": types[t]} for t in sorted(types)],
        "topics": [{"topic": t, "messages": n, "types": ty, "connections": c} for t, n, ty, c in _topics(summary)],
    }


def _compression_lines(summary: BagSummary) -> list[tuple[str, str]]:
    """rosbag info's compression row (each kind with its chunk count, most used first, and the stored
    fraction for compressed kinds) and, when any chunk is compressed, the uncompressed and compressed totals."""
    kinds = summary.chunk_compression
    chunks = sum(kinds.values())
    if not chunks:
        return [("compression", "none")]
    parts = []
    for kind in sorted(kinds, key=lambda k: (kinds[k], k), reverse=True):
        plain, stored = summary.chunk_bytes.get(kind, (0, 0))
        ratio = f"; {100.0 * stored / plain:.2f}%" if kind != "none" and plain else ""
        parts.append(f"{kind} [{kinds[kind]}/{chunks} chunks{ratio}]")
    rows = [("compression", ", ".join(parts))]
    if all(kind == "none" for kind in kinds):
        return rows
    plain = sum(p for p, _ in summary.chunk_bytes.values())
    stored = sum(s for _, s in summary.chunk_bytes.values())
    plain_text, stored_text = human_size(plain), human_size(stored)
    size_width = max(len(plain_text), len(stored_text))
    seconds = (summary.end_ns - summary.start_ns) / 1e9
    if seconds > 0:
        plain_rate, stored_rate = human_size(plain / seconds), human_size(stored / seconds)
        rate_width = max(len(plain_rate), len(stored_rate))
        rows.append(("uncompressed", f"{plain_text:>{size_width}} @ {plain_rate:>{rate_width}}/s"))
        rows.append(("compressed", f"{stored_text:>{size_width}} @ {stored_rate:>{rate_width}}/s "
                                   f"({100.0 * stored / plain:.2f}%)"))
    else:
        rows.append(("uncompressed", f"{plain_text:>{size_width}}"))
        rows.append(("compressed", f"{stored_text:>{size_width}}"))
    return rows


def format_info(summary: BagSummary) -> str:
    """rosbag info's layout: path, version, duration, start, end, size, messages, compression, types, topics."""
    lines = [("path", summary.path), ("version", summary.version)]
    if summary.message_count:
        lines += [("duration", human_duration((summary.end_ns - summary.start_ns) / 1e9)),
                  ("start", human_time(summary.start_ns)), ("end", human_time(summary.end_ns))]
    lines += [("size", human_size(summary.size)), ("messages", str(summary.message_count))]
    lines += _compression_lines(summary)
    types = {c.type: c.md5sum for c in summary.connections}
    type_width = max((len(t) for t in types), default=0)
    type_lines = [f"{t:<{type_width}} [{types[t]}]" for t in sorted(types)]
    topics = _topics(summary)
    topic_width = max((len(t) for t, *_ in topics), default=0)
    count_width = max((len(str(n)) for _, n, _, _ in topics), default=0)
    topic_lines = []
    for topic, count, tlist, conns in topics:
        extra = f" ({conns} connections)" if conns > 1 else ""
        unit = "msg " if count == 1 else "msgs"
        topic_lines.append(f"{topic:<{topic_width}}   {count:>{count_width}} {unit}    : "
                           f"{', '.join(tlist):<{type_width}}{extra}")
    width = max(len(k) for k, _ in lines) + 1
    out = [f"{k + ':':<{width}} {v}" for k, v in lines]
    for key, rows in (("types", type_lines), ("topics", topic_lines)):
        for i, row in enumerate(rows):
            out.append(f"{(key + ':') if i == 0 else '':<{width}} {row}")
    if not summary.closed:
        why = f" ({summary.problem})" if summary.problem else ""
        out.append(f"warning:     the file was not closed (recording interrupted){why}; "
                   "it reads up to its last complete message; `rostui bag reindex` rewrites it with an index")
    return "\n".join(out)
