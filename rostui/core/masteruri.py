"""The master URI a process uses: an explicit override, ROS_MASTER_URI, or ROS's default.

Kept apart from :mod:`rostui.core.network` (which re-exports it) so that a
one-shot command can find its master without importing ``typing`` or ``urllib``.
"""

from __future__ import annotations

import os

__all__ = ["DEFAULT_MASTER_URI", "master_uri_from_env"]

DEFAULT_MASTER_URI = "http://localhost:11311"


def master_uri_from_env(override: str | None = None) -> str:
    """The master URI: an explicit override, else ROS_MASTER_URI, else the ROS default."""
    uri = override or os.environ.get("ROS_MASTER_URI") or DEFAULT_MASTER_URI
    return uri if uri.endswith("/") else uri + "/"
