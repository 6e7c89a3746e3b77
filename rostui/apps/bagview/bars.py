"""Texts of the bag view's one-line bars: the file header, the transport status and key help."""

from __future__ import annotations

import time

from rich.text import Text

from rostui.core.bag.index import BagIndex
from rostui.apps.widgets.keys import key_line
from rostui.tools.bag.info import status_size

#: Key help in play mode.
PLAY_KEYS = key_line("space play  s step  ←→ ±1s  PgUp/Dn ±10%  Home/End  0-9 %  g go to  +- rate  l loop  "
                     "↑↓ topic  t publish it  a publish all  i inspect")

#: Key help in record mode.
RECORD_KEYS = key_line("r start/stop  n split (new file)")


def wall_text(t_ns: int) -> str:
    """The bag time as a local date and time with milliseconds: ``2023-11-14 22:13:20.250``."""
    secs, ns = divmod(t_ns, 1_000_000_000)
    return time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(secs)) + f".{ns // 1_000_000:03d}"


def header_text(names: list[str], index: BagIndex | None, link: str = "", rosbag_duration: str | None = None,
                width: int = 0) -> Text:
    """``square.bag · 12.3 KB · 1234 msgs · 2 topics · 9.000 s │ LINK`` and a warning for files cut short; the
    span is the messages'; ``rosbag_duration``, when given, is what bag info says instead (chunks out of time
    order), and the header says so.  When the line would pass ``width`` columns, LINK starts a line of its own
    (a wrap inside it split "t" from what t does)."""
    text = Text()
    text.append(" · ".join(names), style="bold")
    if index is None:
        text.append(f" · reading… {link}")
        return text
    span = (index.end_ns - index.start_ns) / 1e9
    text.append(f" · {status_size(index.file_size)} · {len(index)} msgs · {len(index.tracks)} topics · {span:.3f} s")
    if rosbag_duration is not None:
        text.append(f" (bag info: {rosbag_duration}, first and last chunk)")
    if link:
        text.append(f"\n{link}" if width and text.cell_len + 3 + len(link) > width else f" │ {link}")
    for notice in index.notices:
        text.append(f"  ⚠ {notice}", style="bold yellow")
    return text


def play_status(*, paused: bool, at_end: bool, rate: float, loop: bool, bag_ns: int, start_ns: int, end_ns: int,
                published: int, problem: str = "") -> Text:
    """``▶ PLAYING ×1 loop │ bag 1700000001.230000 │ 2023-11-14 22:13:21.230 │ +1.230 / 2.000 s 61% │ published 7``;
    ``published`` below 0 leaves the count out (nothing is published); a ``problem`` (the line of a message
    that could not be read) comes right after the state, where a narrow terminal still shows it."""
    state = "■ END" if paused and at_end else "❚❚ PAUSED" if paused else "▶ PLAYING"
    text = Text(f" {state} ", style="bold reverse")
    text.append(f" ×{rate:g}")
    if loop:
        text.append(" loop", style="bold")
    if problem:
        text.append(f" │ ⚠ {problem}", style="bold yellow")
    span = max(end_ns - start_ns, 0)
    pct = 100.0 * (bag_ns - start_ns) / span if span else 0.0
    text.append(f" │ bag {bag_ns / 1e9:.6f} │ {wall_text(bag_ns)} │ +{(bag_ns - start_ns) / 1e9:.3f} / "
                f"{span / 1e9:.3f} s {pct:3.0f}%")
    if published >= 0:
        text.append(f" │ published {published}")
    return text
