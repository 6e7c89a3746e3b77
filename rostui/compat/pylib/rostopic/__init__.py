"""rostopic's Python functions that scripts call: what type a topic has and its message class.

``get_topic_class('/odom/pose/pose')`` finds the published topic the name starts with (``/odom``) when
the name itself is not one, provided its type has the rest as a field path, and returns the class, the
real topic and a function picking that field out of a message. The command line is ``rostui topic``.
"""

from __future__ import annotations

import sys
import time
from typing import Any, Callable

import rospy

from rostui.compat.lookup import get_message_class
from rostui.tools.topic.echo import field_evaluator, field_type_of

__all__ = ["ROSTopicException", "ROSTopicIOException", "get_topic_class", "get_topic_type", "msgevalgen"]

ANYTYPE = "*"


class ROSTopicException(Exception):
    """rostopic's error."""


class ROSTopicIOException(ROSTopicException):
    """The master could not be reached."""


def msgevalgen(pattern: str) -> Callable[[Any], Any] | None:
    """A function picking ``/field/sub[i]`` out of a message (None for an empty pattern)."""
    return field_evaluator(pattern)


def _topic_types() -> list[list[str]]:
    try:
        code, message, value = rospy.get_master().getTopicTypes()
    except Exception:  # noqa: BLE001 (any failure to reach the master is rostopic's one error)
        raise ROSTopicIOException("Unable to communicate with master!") from None
    if code != 1:
        raise ROSTopicIOException("Unable to communicate with master!")
    return list(value)


def _get_topic_type(topic: str) -> tuple[str | None, str | None, Callable[[Any], Any] | None]:
    """``(type, real topic, field picker)`` of ``topic`` without waiting; Nones when it is not published."""
    topic = rospy.resolve_name(topic) if not topic.startswith("/") else topic
    types = _topic_types()
    matches = [(t, kind) for t, kind in types if t == topic]
    if not matches:
        prefixed = sorted(((t, kind) for t, kind in types if topic.startswith(t + "/")), reverse=True)
        for t, kind in prefixed:
            try:
                cls = get_message_class(kind)
            except Exception:  # noqa: BLE001 (an unloadable type: take this match, as rostopic does)
                cls = None
            if cls is None or field_type_of(cls, topic[len(t):]) is not None:
                matches = [(t, kind)]
                break
    if not matches:
        return None, None, None
    real, kind = matches[0]
    if kind == ANYTYPE:
        return None, None, None
    return kind, real, (msgevalgen(topic[len(real):]) if topic != real else None)


def get_topic_type(topic: str, blocking: bool = False) -> tuple[str | None, str | None, Callable[[Any], Any] | None]:
    """``(type, real topic, field picker)``; with ``blocking``, wait (saying so) until the topic is published."""
    kind, real, pick = _get_topic_type(topic)
    if kind:
        return kind, real, pick
    if blocking:
        sys.stderr.write("WARNING: topic [%s] does not appear to be published yet\n" % topic)
        while not rospy.is_shutdown():
            kind, real, pick = _get_topic_type(topic)
            if kind:
                return kind, real, pick
            time.sleep(0.1)
    return None, None, None


def get_topic_class(topic: str, blocking: bool = False) -> tuple[Any, str | None, Callable[[Any], Any] | None]:
    """``(message class, real topic, field picker)`` of ``topic``; Nones when it is not published."""
    kind, real, pick = get_topic_type(topic, blocking=blocking)
    if kind is None:
        return None, None, None
    try:
        cls = get_message_class(kind)
    except Exception:  # noqa: BLE001
        cls = None
    if cls is None:
        raise ROSTopicException("Cannot load message class for [%s]. Are your messages built?" % kind)
    return cls, real, pick
