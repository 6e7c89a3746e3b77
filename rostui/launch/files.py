"""Command-line launch arguments -> launch file paths and ``name:=value`` args, as roslaunch reads them."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from rostui.core import packages
from rostui.launch.errors import LaunchError


@dataclass
class LaunchRequest:
    """What to launch: the files, and the args and ``__ns`` given on the command line."""

    files: list[str]
    args: dict[str, str] = field(default_factory=dict)
    namespace: str = "/"
    strict: bool = False
    """Unknown elements and attributes are errors (``--strict``), not warnings."""


def split_mappings(words: list[str]) -> tuple[list[str], dict[str, str]]:
    """Split ``name:=value`` words (roslaunch's args; ``_private:=`` ones ignored) from the others."""
    plain: list[str] = []
    mappings: dict[str, str] = {}
    for word in words:
        if ":=" in word:
            src, dst = (part.strip() for part in word.split(":=", 1))
            if src and dst and not (len(src) > 1 and src[0] == "_" and src[1] != "_"):
                mappings[src] = dst
            continue
        plain.append(word)
    return plain, mappings


def find_in_package(package: str, filename: str) -> list[Path]:
    """Files below ``package``'s directory whose path ends with ``filename``."""
    root = packages.find_package(package)
    if root is None:
        return []
    wanted = Path(filename)
    found: list[Path] = []
    for dirpath, dirnames, files in os.walk(root, followlinks=True):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
        for name in sorted(files):
            if name == wanted.name:
                path = Path(dirpath) / name
                if len(wanted.parts) == 1 or path.as_posix().endswith("/" + wanted.as_posix()):
                    found.append(path)
    return found


def resolve_request(words: list[str]) -> LaunchRequest:
    """``[PKG] FILE [FILE ...] [name:=value ...]`` -> a :class:`LaunchRequest`; raises :class:`LaunchError`."""
    plain, mappings = split_mappings(words)
    namespace = mappings.pop("__ns", os.environ.get("ROS_NAMESPACE", "/")) or "/"
    if not plain:
        raise LaunchError("you must specify at least one input file")
    if len(plain) >= 2:
        matches = find_in_package(plain[0], plain[1])
        if len(matches) > 1:
            listing = ", ".join(str(m) for m in matches)
            raise LaunchError(f"multiple files named [{plain[1]}] in package [{plain[0]}]: {listing}; "
                              "give the full path instead")
        if len(matches) == 1:
            return LaunchRequest([str(matches[0]), *plain[2:]], mappings, namespace)
    if os.path.isfile(plain[0]):
        missing = [f for f in plain[1:] if not os.path.isfile(f)]
        if missing:
            raise LaunchError(f"The following input files do not exist: {', '.join(missing)}")
        return LaunchRequest(plain, mappings, namespace)
    if len(plain) >= 2:
        raise LaunchError(f"[{plain[1]}] is neither a launch file in package [{plain[0]}] nor is [{plain[0]}] "
                          "a launch file name")
    raise LaunchError(f"[{plain[0]}] is not a launch file name")
