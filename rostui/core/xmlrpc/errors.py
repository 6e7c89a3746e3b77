"""Exception types raised by the XML-RPC client and by :func:`ros_result`."""

from __future__ import annotations


class XmlRpcError(Exception):
    """Base class of every error the XML-RPC layer raises."""


class XmlRpcFault(XmlRpcError):
    """The server answered with an XML-RPC ``<fault>``."""

    def __init__(self, code: int, string: str, uri: str = "") -> None:
        self.code = code
        self.string = string
        self.uri = uri
        where = f" from {uri}" if uri else ""
        super().__init__(f"XML-RPC fault {code}{where}: {string}")


class XmlRpcConnectionError(XmlRpcError):
    """The server could not be reached: refused, unreachable, reset or timed out."""

    def __init__(self, uri: str, reason: str) -> None:
        self.uri = uri
        self.reason = reason
        super().__init__(f"cannot communicate with {uri}: {reason}")


class XmlRpcProtocolError(XmlRpcError):
    """The server answered something that is not a valid XML-RPC HTTP response."""

    def __init__(self, uri: str, reason: str) -> None:
        self.uri = uri
        self.reason = reason
        super().__init__(f"bad XML-RPC response from {uri}: {reason}")


class RosApiError(Exception):
    """A ROS API call returned a status code other than 1 (success)."""

    def __init__(self, code: int, message: str) -> None:
        self.code = code
        self.message = message
        super().__init__(message if message else f"ROS API error code {code}")
