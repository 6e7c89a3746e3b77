"""rosgraph for unmodified ROS 1 scripts: the master's API (``rosgraph.Master``), names and the environment.

``rosgraph.Master(caller_id)`` and ``rosgraph.masterapi`` call the master's XML-RPC API and raise
``MasterError``/``MasterFailure`` on a refusal; ``is_master_online()`` says whether it answers;
``rosgraph.names`` has rosgraph's name functions and ``get_master_uri``/``myargv`` what scripts use them for.
rosgraph's own program (``rosgraph`` the command), ``rosgraph.network`` and ``rosgraph.roslogging`` are
not here.
"""

from __future__ import annotations

import sys

from . import names
from .masterapi import Master, MasterError, MasterException, MasterFailure
from .masterapi import is_online as is_master_online
from .rosenv import ROS_HOSTNAME, ROS_IP, ROS_IPV6, ROS_MASTER_URI, ROS_NAMESPACE, get_master_uri

__all__ = [
    "Master", "MasterError", "MasterException", "MasterFailure", "ROS_HOSTNAME", "ROS_IP", "ROS_IPV6",
    "ROS_MASTER_URI", "ROS_NAMESPACE", "get_master_uri", "is_master_online", "myargv", "names",
]


def myargv(argv: list[str] | None = None) -> list[str]:
    """*argv* (``sys.argv`` by default) without the ROS remapping arguments (those holding ``:=``)."""
    return [arg for arg in (sys.argv if argv is None else argv) if names.REMAP not in arg]
