"""The ROS 1 master: Master API and Parameter Server API, wire-compatible with rosmaster.

``Master`` serves :class:`MasterHandler` over :mod:`rostui.core.xmlrpc`;
``run_master_forever`` runs one standalone under uvloop.
"""

from __future__ import annotations

from .handler import MasterHandler
from .master import DEFAULT_ROSDISTRO, DEFAULT_ROSVERSION, Master
from .notify import Notifier
from .run import run_master_forever

__all__ = [
    "DEFAULT_ROSDISTRO",
    "DEFAULT_ROSVERSION",
    "Master",
    "MasterHandler",
    "Notifier",
    "run_master_forever",
]
