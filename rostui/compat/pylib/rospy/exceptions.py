"""rospy.exceptions: the errors rospy scripts catch, as rostui's runtime raises them."""

from __future__ import annotations

from rostui.core.node.services import ServiceException
from rostui.core.node.errors import ROSException, ROSInterruptException, ROSTimeMovedBackwardsException

__all__ = ["ROSException", "ROSInterruptException", "ROSTimeMovedBackwardsException", "ROSInitException",
           "ROSSerializationException", "ROSInternalException", "TransportException", "TransportInitError",
           "TransportTerminated", "ServiceException"]


class ROSInitException(ROSException):
    """The node could not be initialised."""


class ROSSerializationException(ROSException):
    """A message could not be serialised."""


class ROSInternalException(Exception):
    """An error inside the client library itself."""


class TransportException(ROSException):
    """A connection to a peer failed."""


class TransportTerminated(ROSException):
    """A connection was closed while in use."""


class TransportInitError(ROSException):
    """A connection could not be set up."""
