"""Unwrapping of ROS's ``[code, statusMessage, value]`` return convention."""

from __future__ import annotations

from .errors import RosApiError, XmlRpcProtocolError

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

#: ROS API status codes.
SUCCESS = 1
FAILURE = 0
ERROR = -1


def ros_result(value: Any) -> Any:
    """Return the value of a ROS API triple, or raise :class:`RosApiError`.

    ``value`` is what a Master or Slave API call returned: ``[code, message,
    value]``.  A code other than 1 raises ``RosApiError(code, message)``; a
    reply of any other shape raises :class:`XmlRpcProtocolError`.
    """
    if not isinstance(value, (list, tuple)) or len(value) != 3 or not isinstance(value[0], int):
        raise XmlRpcProtocolError("", f"expected [code, statusMessage, value], got {value!r:.200}")
    code, message, result = value
    if code != SUCCESS:
        raise RosApiError(code, str(message))
    return result
