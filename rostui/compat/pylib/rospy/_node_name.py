"""What rospy's ``init_node`` checks of a node's name before it starts the node."""

from __future__ import annotations

import warnings

from rostui.core.names import is_legal_base_name

__all__ = ["check_node_name"]


def check_node_name(name: str) -> None:
    """ValueError for an empty name or one with a namespace; a warning for any other name ROS calls illegal.

    The messages are rospy's own.
    """
    if not name:
        raise ValueError("name must not be empty")
    if "/" in name:
        raise ValueError("namespaces are not allowed in node names")
    if not is_legal_base_name(name):
        warnings.warn(f"'{name}' is not a legal ROS base name. This may cause problems with other ROS tools.",
                      stacklevel=3)
