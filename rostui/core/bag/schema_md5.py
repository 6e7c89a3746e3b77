"""The md5sum of a ROS 1 message type computed from its definition, for files that do not store it.

Standard ROS 1 MCAP files (written by the ``mcap`` tools, Foxglove, ``mcap-ros1-support``) keep each
type's full definition in a schema (encoding ``ros1msg``: the type's own text, then a ``MSG: pkg/Type``
section per nested type) but no md5sum.  ROS 1 needs one to connect a publisher to a subscriber, so it is
computed here as genmsg does, from the definition alone (never from locally installed types, which may
differ from what was recorded): :func:`rostui.core.msg.definition_md5`, the hash every received definition is
checked with.
"""

from __future__ import annotations

from functools import lru_cache

from rostui.core.msg import MessageError, definition_md5
from rostui.core.one_line import exception_line

__all__ = ["UNKNOWN_MD5", "ROS1_SCHEMA_ENCODING", "definition_md5", "schema_md5"]

UNKNOWN_MD5 = "*"
"""The md5sum given to a type whose definition cannot be read: ROS's wildcard (see docs/bag.md)."""

ROS1_SCHEMA_ENCODING = "ros1msg"


@lru_cache(maxsize=1024)
def schema_md5(type_name: str, encoding: str, data: bytes) -> tuple[str, str]:
    """``(md5sum, problem)`` of an MCAP schema: the computed md5 and ``''``, or :data:`UNKNOWN_MD5` and why.

    Cached on the schema's name, encoding and bytes, so a file with many channels of one type, or many
    files of the same types, parse each definition once.
    """
    if encoding != ROS1_SCHEMA_ENCODING:
        return UNKNOWN_MD5, f"schema encoding {encoding or '(none)'!r} is not {ROS1_SCHEMA_ENCODING!r}"
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        return UNKNOWN_MD5, f"definition is not UTF-8 text (byte {exc.start})"
    try:
        return definition_md5(type_name, text), ""
    except MessageError as exc:
        return UNKNOWN_MD5, exception_line(exc, None)
