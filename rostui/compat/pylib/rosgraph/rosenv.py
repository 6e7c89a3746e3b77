"""rosgraph.rosenv: the ROS environment variables' names and the master URI a program uses."""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping, Sequence

__all__ = ["DEFAULT_MASTER_URI", "ROS_HOSTNAME", "ROS_IP", "ROS_IPV6", "ROS_MASTER_URI", "ROS_NAMESPACE", "get_master_uri"]

ROS_MASTER_URI = "ROS_MASTER_URI"
ROS_IP = "ROS_IP"
ROS_IPV6 = "ROS_IPV6"
ROS_HOSTNAME = "ROS_HOSTNAME"
ROS_NAMESPACE = "ROS_NAMESPACE"
DEFAULT_MASTER_URI = "http://localhost:11311/"
_MASTER_ARG = "__master:="


def get_master_uri(env: Mapping[str, str] | None = None, argv: Sequence[str] | None = None) -> str:
    """``__master:=`` from *argv* (``sys.argv`` by default), else ``ROS_MASTER_URI``, else ROS's default.

    A ``__master:=`` without one plain value is a ValueError, as in rosgraph."""
    for arg in sys.argv if argv is None else argv:
        if arg.startswith(_MASTER_ARG):
            parts = arg.split(":=")
            if len(parts) != 2 or not parts[1]:
                raise ValueError(f"__master remapping argument '{arg}' improperly specified")
            return parts[1]
    return (os.environ if env is None else env).get(ROS_MASTER_URI, DEFAULT_MASTER_URI)
