"""``rostui bag info``: rosbag info's fields for MCAP and ``.bag`` files, as text or a JSON-ready dict."""

from __future__ import annotations

import time
from typing import Any

from rostui.core.bag.files import open_reader
from rostui.core.bag.model import BagSummary


_SIZE_UNITS = ("KB", "MB", "GB", "TB", "PB", "EB", "ZB", "YB")


def human_size(size: float) -> str:
    """``81.5 KB`` as rosbag info writes sizes: never in bytes (512 bytes are ``0.5 KB``), ``-`` past yottabytes."""
    for unit in _SIZE_UNITS:
        size /= 1024.0
        if size < 1024.0:
            return f"{size:.1f} {unit}"
    return "-"


def status_size(size: float) -> str:
    """``123 B``, ``4.5 KB``, ``6.7 MB``: a size in a live status line (whole bytes below 1 KB)."""
    for unit in ("B", "KB", "MB", "GB"):
        if size < 1024 or unit == "GB":
            return f"{int(size)} B" if unit == "B" else f"{size:.1f} {unit}"
        size /= 1024
    return f"{size:.1f} GB"


def seconds_of(ns: int) -> float:
    """A time in seconds as rospy's ``Time.to_sec`` gives it (seconds plus nanoseconds / 1e9, in floats), so
    that rounding on the printed digits falls where rosbag's does."""
    secs, nsecs = divmod(ns, 1_000_000_000)
    return float(secs) + float(nsecs) / 1e9


def human_duration(seconds: float) -> str:
    """``12.3s``, ``1:54s (114s)`` or ``1hr 2:05s (3725s)`` as rosbag info writes durations: rounded to a
    tenth under a minute, truncated to whole seconds from a minute on."""
    minutes = int(seconds / 60)
    hours = int(minutes / 60)
    whole = int(seconds)
    secs = int(seconds % 60)
    if hours > 0:
        return f"{hours}hr {minutes % 60}:{secs:02d}s ({whole}s)"
    if minutes > 0:
        return f"{minutes}:{secs:02d}s ({whole}s)"
    return f"{seconds:.1f}s"


def human_time(seconds: float) -> str:
    """``Nov 22 2026 15:11:02.32 (1795360262.32)`` in local time, as rosbag info writes a time: the clock
    part keeps the whole second and appends the fraction rounded to hundredths (``.996`` shows as ``.00``,
    the second not carried), the number in brackets is rounded as a whole."""
    fraction = f"{seconds - int(seconds):.2f}"[1:]
    clock = time.strftime("%b %d %Y %H:%M:%S", time.localtime(seconds))
    return f"{clock}{fraction} ({seconds:.2f})"


def summarize(path: str) -> BagSummary:
    """Read a file's summary (BagError for anything that is not a readable bag)."""
    reader = open_reader(path)
    try:
        return reader.summary()
    finally:
        reader.close()


def _topics(summary: BagSummary) -> list[tuple[str, int, list[str], int]]:
    """``(topic, messages, types, connections)`` per topic, sorted by name; types in connection order."""
    rows: dict[str, tuple[int, list[str], int]] = {}
    for conn in summary.connections:
        count, types, conns = rows.get(conn.topic, (0, [], 0))
        if conn.type not in types:
            types = [*types, conn.type]
        rows[conn.topic] = (count + summary.counts.get(conn.id, 0), types, conns + 1)
    return [(t, *rows[t]) for t in sorted(rows)]


def _type_md5s(summary: BagSummary) -> dict[str, str]:
    """Each type with the md5sum of its first connection, as rosbag info lists a type recorded with several."""
    types: dict[str, str] = {}
    for conn in summary.connections:
        types.setdefault(conn.type, conn.md5sum)
    return types


def info_dict(summary: BagSummary) -> dict[str, Any]:
    """The ``--json`` form of info."""
    types = {c.type: sorted({d.md5sum for d in summary.connections if d.type == c.type})
             for c in summary.connections}
    return {
        "path": summary.path,
        "format": summary.format,
        "version": summary.version,
        "closed": summary.closed,
        "problem": summary.problem or None,
        "duration": (summary.end_ns - summary.start_ns) / 1e9,
        "rosbag_duration": (lambda span: span[1] - span[0])(_span(summary)),
        "start": summary.start_ns / 1e9,
        "end": summary.end_ns / 1e9,
        "size": summary.size,
        "messages": summary.message_count,
        "compression": summary.chunk_compression,
        "chunk_bytes": {kind: {"uncompressed": plain, "stored": stored}
                        for kind, (plain, stored) in summary.chunk_bytes.items()},
        "types": [{"type": t, "md5sum": _type_md5s(summary)[t], "md5sums": types[t]} for t in sorted(types)],
        "topics": [{"topic": t, "messages": n, "types": ty, "connections": c} for t, n, ty, c in _topics(summary)],
    }


def _compression_lines(summary: BagSummary, seconds: float) -> list[tuple[str, str]]:
    """rosbag info's compression row (each kind with its chunk count, most used first, and the stored
    fraction for compressed kinds) and, when any chunk is compressed, the uncompressed and compressed totals
    (with bytes per second of the ``seconds`` info shows as the duration, when positive)."""
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


def _span(summary: BagSummary, exact: bool = False) -> tuple[float, float]:
    """Start and end in seconds: from the first and last chunk where the file has chunk infos, as rosbag's
    (``exact``: of the earliest and the latest message)."""
    start_ns, end_ns = (summary.start_ns, summary.end_ns) if exact else summary.info_span or (summary.start_ns,
                                                                                              summary.end_ns)
    return seconds_of(start_ns), seconds_of(end_ns)


def rosbag_duration(summary: BagSummary) -> str | None:
    """rosbag info's duration when it is not the messages' span (chunks out of time order: rosbag takes the
    first and the last chunk of the file), as rosbag writes it; None when the two agree."""
    if summary.info_span is None or summary.info_span == (summary.start_ns, summary.end_ns):
        return None
    start, end = _span(summary)
    return human_duration(end - start)


def span_note(summary: BagSummary) -> str | None:
    """The footnote of ``bag info`` (on stderr, so its text stays rosbag's) when rosbag's duration is not the
    messages' span; None when they agree."""
    rosbag = rosbag_duration(summary)
    if rosbag is None:
        return None
    start, end = _span(summary, exact=True)
    return (f"note: {summary.path}: the duration {rosbag} is rosbag's (its first and last chunk); the messages "
            f"span {human_duration(end - start)}: `rostui bag info --exact` shows their start and end")


def _topic_row(topic: str, count: int, type_name: str, conns: int, widths: tuple[int, int, int]) -> str:
    """One topic as rosbag info lists it: name, count, ``msg``/``msgs``, the first connection's type, and the
    number of connections when more than one (no frequency column: rosbag info shows it only with --freq)."""
    topic_width, count_width, type_width = widths
    unit = "msgs" if count > 1 else "msg "
    extra = f" ({conns} connections)" if conns > 1 else ""
    return f"{topic:<{topic_width}}   {count:>{count_width}} {unit}    : {type_name:<{type_width}}{extra}"


def format_info(summary: BagSummary, exact: bool = False) -> str:
    """rosbag info's text: path, version, duration, start, end, size, messages, compression, types, topics.

    ``exact``: duration, start and end of the earliest and the latest message, where rosbag takes the first
    and the last chunk of the file (they differ when chunks are out of time order).

    A file with neither connections nor chunks shows path, version and size only. Rows keep rosbag's
    padding (a type column is padded even at a line's end); only the text's end is stripped.
    """
    rows: list[tuple[str, str]] = [("path", summary.path), ("version", summary.version)]
    if not summary.connections and not summary.chunk_count:
        rows.append(("size", human_size(summary.size)))
    else:
        start, end = _span(summary, exact)
        rows += [("duration", human_duration(end - start)), ("start", human_time(start)), ("end", human_time(end)),
                 ("size", human_size(summary.size)), ("messages", str(summary.message_count))]
        rows += _compression_lines(summary, end - start)
        types = _type_md5s(summary)
        type_width = max((len(t) for t in types), default=0)
        rows += [("types" if i == 0 else "", f"{t:<{type_width}} [{types[t]}]") for i, t in enumerate(sorted(types))]
        topics = _topics(summary)
        widths = (max((len(t) for t, *_ in topics), default=0),
                  max((len(str(n)) for _, n, _, _ in topics), default=0), type_width)
        rows += [("topics" if i == 0 else "", _topic_row(topic, count, tlist[0], conns, widths))
                 for i, (topic, count, tlist, conns) in enumerate(topics)]
    if not summary.closed:
        why = f" ({summary.problem})" if summary.problem else ""
        rows.append(("warning", f"the file was not closed (recording interrupted){why}; it reads up to its last "
                                "complete message; `rostui bag reindex` rewrites it with an index"))
    width = max(len(k) for k, _ in rows) + 1
    return "".join(f"{(k + ':') if k else '':<{width}} {v}\n" for k, v in rows).rstrip()
