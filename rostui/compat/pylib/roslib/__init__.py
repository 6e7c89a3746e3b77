"""roslib for unmodified ROS 1 scripts, served by rostui: ``load_manifest`` and ``roslib.message``."""

from __future__ import annotations

from . import message, packages

__all__ = ["load_manifest", "message", "packages"]


def load_manifest(package_name: str, bootstrap_version: str = "0.7") -> None:
    """Nothing to do: rostui's import hook already serves every package's messages (rosbuild scripts call this)."""
