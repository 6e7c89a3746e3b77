"""tf.transformations for unmodified ROS 1 scripts: rostui's :mod:`rostui.tools.tf.transformations` under tf's name.

Quaternions are (x, y, z, w), angles default to the ``sxyz`` convention, results are numpy arrays, as in tf.
"""

from __future__ import annotations

from rostui.tools.tf.transformations import *  # noqa: F403 (the module is its facade's names)
from rostui.tools.tf.transformations import __all__  # noqa: F401
