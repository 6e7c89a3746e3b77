"""``rostui clean``: measure and purge the ROS log directory, as rosclean does.

``check`` reports disk usage like ``du -sh`` (``404K ROS node logs``).  A purge
removes everything in the log root except the current run (the directory the
``latest`` symlink points to, and any run ids given as kept) and the ``latest``
symlink itself; with a size limit it removes oldest entries first until the
directory fits.
"""

from __future__ import annotations

import os
import shutil
from dataclasses import dataclass, field
from fractions import Fraction
from math import ceil
from pathlib import Path
from typing import Iterable, Mapping

from rostui.core.log.files import dir_size, log_root, ros_home, walk_stats

__all__ = [
    "LOG_LABEL", "PurgePlan", "PurgeResult", "active_run", "check", "check_lines",
    "confirmation_text", "disk_usage", "execute_purge", "human_size", "plan_purge",
]

#: rosclean's name for the log directory.
LOG_LABEL = "ROS node logs"

_UNITS = "KMGTPEZY"


def disk_usage(path: Path | str) -> int:
    """Bytes of disk used by ``path`` and everything under it (``du -s`` in bytes); 0 if missing."""
    return sum(getattr(info, "st_blocks", 0) * 512 for info in walk_stats(path))


def human_size(size: int) -> str:
    """A byte count as ``du -h`` prints it: ``0``, ``512``, ``4.0K``, ``404K``, ``1.1G``."""
    if size < 1024:
        return str(size)
    index = 0
    value = Fraction(size, 1024)
    while value >= 1024 and index < len(_UNITS) - 1:
        value /= 1024
        index += 1
    if value < 10:
        tenths = ceil(value * 10)
        if tenths < 100:
            return f"{tenths // 10}.{tenths % 10}{_UNITS[index]}"
        return f"10{_UNITS[index]}"
    whole = ceil(value)
    if whole >= 1024 and index < len(_UNITS) - 1:
        return f"1.0{_UNITS[index + 1]}"
    return f"{whole}{_UNITS[index]}"


def check(env: Mapping[str, str] | None = None) -> list[tuple[Path, str, int]]:
    """The directories rosclean checks that exist, as (path, label, disk usage in bytes)."""
    dirs = [(log_root(env), LOG_LABEL), (ros_home(env) / "rosmake", "rosmake logs")]
    return [(path, label, disk_usage(path)) for path, label in dirs if path.is_dir()]


def check_lines(env: Mapping[str, str] | None = None) -> list[str]:
    """``rosclean check``'s output lines: ``<du -sh size> <label>``."""
    return [f"{human_size(usage)} {label}" for _path, label, usage in check(env)]


def active_run(root: Path | str) -> Path | None:
    """The run directory ``<root>/latest`` points to, if it is a directory inside ``root``."""
    root = Path(root)
    latest = root / "latest"
    if not latest.is_symlink():
        return None
    try:
        target = latest.resolve(strict=True)
    except (OSError, RuntimeError):
        return None
    if not target.is_dir() or target.parent != root.resolve():
        return None
    return root / target.name


@dataclass
class PurgePlan:
    """What a purge would remove from ``root`` and what it keeps."""

    root: Path
    targets: list[Path] = field(default_factory=list)
    kept: list[Path] = field(default_factory=list)
    size_before: int = 0
    size_limit: int | None = None


@dataclass
class PurgeResult:
    """What a purge removed: entries, disk bytes freed, and failures as (path, reason)."""

    removed: list[Path] = field(default_factory=list)
    freed: int = 0
    failed: list[tuple[Path, str]] = field(default_factory=list)


def plan_purge(root: Path | str | None = None, *, keep_run_ids: Iterable[str] = (),
               size_limit: int | None = None, env: Mapping[str, str] | None = None) -> PurgePlan:
    """Decide what to remove from the log root (default: :func:`log_root` of ``env``).

    Never listed: the ``latest`` symlink, the run it points to, runs named in
    ``keep_run_ids``.  With ``size_limit`` (bytes, apparent size), only the
    oldest entries (by modification time) needed to get under the limit.
    """
    root = log_root(env) if root is None else Path(root)
    plan = PurgePlan(root=root, size_limit=size_limit)
    if not root.is_dir():
        return plan
    kept_names = {"latest", *keep_run_ids}
    current = active_run(root)
    if current is not None:
        kept_names.add(current.name)
    entries: list[tuple[float, Path]] = []
    for entry in os.scandir(root):
        path = root / entry.name
        if entry.name in kept_names:
            if entry.name != "latest":
                plan.kept.append(path)
            continue
        try:
            mtime = entry.stat(follow_symlinks=False).st_mtime
        except OSError:
            continue
        entries.append((mtime, path))
    entries.sort()
    if size_limit is None:
        plan.targets = [path for _mtime, path in entries]
        return plan
    plan.size_before = remaining = dir_size(root)
    for _mtime, path in entries:
        if remaining <= size_limit:
            break
        remaining -= dir_size(path)
        plan.targets.append(path)
    return plan


def confirmation_text(plan: PurgePlan) -> str:
    """rosclean's question for this plan (one ``rm -rf`` line per target), ending in ``(y/n)?``."""
    lines = ["PLEASE BE CAREFUL TO VERIFY THE COMMAND BELOW!", "Okay to perform:", ""]
    lines += [f"rm -rf {_quote(str(path))}" for path in plan.targets]
    lines.append("(y/n)?")
    return "\n".join(lines)


def _quote(text: str) -> str:
    return f'"{text}"' if " " in text else text


def execute_purge(plan: PurgePlan) -> PurgeResult:
    """Remove the plan's targets; a target that cannot be removed is reported, not raised."""
    result = PurgeResult()
    for path in plan.targets:
        size = disk_usage(path)
        try:
            if path.is_symlink() or not path.is_dir():
                path.unlink()
            else:
                shutil.rmtree(path)
        except FileNotFoundError:
            continue
        except OSError as exc:
            result.failed.append((path, exc.strerror or str(exc)))
            result.freed += size - disk_usage(path)
            continue
        result.removed.append(path)
        result.freed += size
    return result
