"""``bag compress`` / ``bag decompress``: rewrite bags with other chunk compression, as rosbag's commands do.

In place the original is kept as ``<name>.orig.<ext>`` (a bag whose backup already exists is skipped unless
forced); with an output folder the new file goes there under the same name and the original stays. The
format stays what it was (rosbag ``.bag`` or MCAP); messages are written in time order.
"""

from __future__ import annotations

import contextlib
import os
from dataclasses import dataclass

from rostui.core.bag.files import copy_messages, open_reader
from rostui.core.bag.model import BagError
from rostui.core.bag.progress import Progress
from rostui.tools.bag.rewrite import new_file
from rostui.core.bag.rosbag2_0 import BagReader

#: What ``--bz2`` (rosbag's default) means in each format: MCAP has no bz2, zstd is its strong compression.
STRONG = {"rosbag": "bz2", "mcap": "zstd"}


@dataclass(frozen=True)
class Outcome:
    """What happened to one bag: the file written (or '' when skipped) and a note for the user."""

    written: str
    count: int = 0
    skipped: str = ""


def target_paths(path: str, output_dir: str | None) -> tuple[str, str | None]:
    """Where the new file goes and, when that is ``path`` itself, the backup name (rosbag's ``.orig``)."""
    out = path if output_dir is None else os.path.join(output_dir, os.path.basename(path))
    if os.path.abspath(out) != os.path.abspath(path):
        return out, None
    root, ext = os.path.splitext(path)
    return out, f"{root}.orig{ext}"


def change_compression(path: str, kind: str, *, output_dir: str | None = None, force: bool = False,
                       progress: Progress | None = None) -> Outcome:
    """Rewrite ``path`` with chunks compressed as ``kind`` (``none``, ``lz4``, or ``strong``: bz2 in a
    ``.bag``, zstd in MCAP). BagError when it cannot be read or written; the original is then as it was."""
    reader = open_reader(path)
    rosbag = isinstance(reader, BagReader)
    reader.close()
    compression = STRONG["rosbag" if rosbag else "mcap"] if kind == "strong" else kind
    out, backup = target_paths(path, output_dir)
    if output_dir is not None and not os.path.isdir(output_dir):
        raise BagError(f"{output_dir}: no such folder")
    source = path
    if backup is not None:
        if os.path.exists(backup) and not force:
            return Outcome("", skipped=f"Skipping {path}. Backup path {backup} already exists.")
        try:
            os.replace(path, backup)
        except OSError as exc:
            raise BagError(f"cannot move {path} to {backup}: {exc.strerror}") from None
        source = backup
    try:
        reader = open_reader(source)
        try:
            with new_file(out, compression, rosbag=rosbag) as writer:
                count = copy_messages(reader, writer, progress)
        finally:
            reader.close()
    except BaseException:
        if backup is not None:
            with contextlib.suppress(OSError):
                os.replace(backup, path)
        raise
    return Outcome(out, count)
