"""Recording options from the words of a command line: one meaning for ``bag record`` and ``bag view --record``.

Both commands take rosbag record's flags (topics, ``-a``, ``-e``, ``-x``,
``-O``/``-o``, ``-j``/``--lz4``/``--compression``, ``--split``, ``--size``,
``--duration``, ``--max-size``); :func:`record_options` checks them together
and builds the :class:`~rostui.tools.bag.recorder.RecordOptions` a
:class:`~rostui.tools.bag.recorder.Recorder` runs, or raises a one-line
:class:`~rostui.core.bag.model.BagError` that the command prints after its name.
"""

from __future__ import annotations

from collections.abc import Sequence

from rostui.core.bag.model import BagError
from rostui.tools.bag.recorder import RecordOptions, TopicFilter, parse_duration

__all__ = ["COMPRESSIONS", "record_options"]

#: What ``--compression`` takes.
COMPRESSIONS = ("none", "lz4", "zstd", "bz2")


def _compression(is_bag: bool, bz2: bool, lz4: bool, compression: str | None) -> str:
    """The chunk compression: ``--compression`` as given, else ``-j`` (bz2 in a .bag, zstd in MCAP), else ``--lz4``."""
    if compression is not None and compression not in COMPRESSIONS:
        raise BagError(f"unknown compression '{compression}' (none, lz4, zstd or bz2)")
    kind = compression or (("bz2" if is_bag else "zstd") if bz2 else "lz4" if lz4 else "none")
    if is_bag and kind == "zstd":
        raise BagError("a .bag file cannot use zstd compression (none, bz2 or lz4)")
    if kind == "bz2" and not is_bag:
        raise BagError("MCAP files use lz4 or zstd compression, not bz2 (record a .bag for bz2)")
    return kind


def record_options(topics: Sequence[str], *, all_topics: bool = False, regex: bool = False,
                   exclude: str | None = None, name: str | None = None, prefix: str | None = None,
                   bz2: bool = False, lz4: bool = False, compression: str | None = None, split: bool = False,
                   size_mb: float | None = None, duration: str | None = None,
                   max_size_mb: float | None = None, mcap: bool = False) -> RecordOptions:
    """Check a command line's recording flags together and build their RecordOptions (BagError: what is wrong).

    Files are rosbag's ``.bag`` unless ``mcap`` (``--mcap``) or the name says ``.mcap``."""
    if name and prefix:
        raise BagError("use -O NAME or -o PREFIX, not both")
    named = name or prefix or ""
    if mcap and named.endswith(".bag"):
        raise BagError(f"--mcap records MCAP, but {named} names a .bag file")
    duration_s = parse_duration(duration) if duration is not None else None
    for option, value in (("--size", size_mb), ("--max-size", max_size_mb)):
        if value is not None and not value > 0:
            raise BagError(f"{option} must be a positive number of MB, not {value:g}")
    if split and size_mb is None and duration_s is None:
        raise BagError("--split needs --size MB or --duration DURATION to know where to split")
    kind = _compression(not (mcap or named.endswith(".mcap")), bz2, lz4, compression)
    opts = RecordOptions(topics=list(topics), all_topics=all_topics, regex=regex, exclude=exclude, output_name=name,
                         output_prefix=prefix, compression=kind, split=split, size_mb=size_mb, duration_s=duration_s,
                         max_size_mb=max_size_mb, mcap=mcap)
    TopicFilter(opts, str)  # no topics at all, or a regular expression that does not compile
    return opts
