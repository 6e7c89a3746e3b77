"""rosbag for unmodified ROS 1 scripts, served by rostui: ``Bag`` over rostui's ``.bag`` and MCAP code.

``rosbag.Bag(path, 'r'|'w'|'a', compression=...)`` reads and writes rosbag v2.0
files (and MCAP files, chosen by their first bytes or, when writing, by a name
not ending in ``.bag``) through :mod:`rostui.core.bag`. Messages come back as
the classes ``from <pkg>.msg import X`` gives, or as classes built from the
bag's own message definitions for types rostui does not know.
"""

from __future__ import annotations

from . import bag
from .bag import *  # noqa: F401,F403  (the names rosbag.bag has)

__all__ = list(bag.__all__)
