"""Which publishers a callback hears: checks of a publisher's connection header, asked once per connection.

A subscriber of md5sum ``*`` (:class:`~rostui.core.node.anymsg.AnyMsg`) is offered every publisher of its topic,
whatever it declares.  A callback subscribed with a *check* hears only the publishers whose header the check
accepts; a connection that no callback of the subscription accepts is refused, as ROS refuses a publisher of
another md5sum: it loses its connection, and is not asked again while the master lists it under the same URI
(:class:`~rostui.core.node.topics.Subscription`).  The others are served as before.

A check is ``check(header) -> None`` (accepted) or one line saying why not.  Two are here:

- :func:`decodable`: the header's type, md5sum and definition give a class by the wire's rule
  (:func:`rostui.core.msg.connection_class`): what a tool that prints any type needs (``topic echo``, the
  monitor);
- :func:`of_type`: exactly one type, rostui's version of it: what a view drawing that type by its fields needs.

:class:`RefusalLog` wraps a check and remembers (and reports once) what it refused.
"""

from __future__ import annotations

from collections import deque
from typing import Callable, Mapping

from rostui.core.msg import MessageError, UnknownMessageTypeError, connection_class, rostui_md5
from rostui.core.msg.spec import shown
from rostui.core.one_line import exception_line

__all__ = ["HeaderCheck", "RefusalLog", "decodable", "of_type", "publisher_name"]

#: ``check(header)``: None when the publisher whose connection header it is may be heard, else why not (one line).
HeaderCheck = Callable[[Mapping[str, str]], "str | None"]


def publisher_name(header: Mapping[str, str]) -> str:
    """``publisher [/talker]``: the publisher a connection header comes from, as errors name it."""
    return f"publisher [{shown(str(header.get('callerid') or '?'), 80)}]"


def decodable(header: Mapping[str, str]) -> str | None:
    """None when the header's type, md5sum and definition give a class by the wire's rule, else why not (a line
    naming the publisher)."""
    sender = publisher_name(header)
    try:
        connection_class(header.get("type", ""), header.get("md5sum", ""), header.get("message_definition", ""),
                         sender=sender)
    except MessageError as exc:
        why = exception_line(exc, None)
        return why if why.startswith(sender) else f"{sender}: {why}"
    return None


def of_type(type_name: str) -> HeaderCheck:
    """A check accepting only publishers of ``type_name`` (a type rostui knows) under rostui's md5sum (or ``*``).

    Raises :class:`~rostui.core.msg.UnknownMessageTypeError` when rostui does not know ``type_name``.
    """
    ours = rostui_md5(type_name)
    if ours is None:
        raise UnknownMessageTypeError(type_name)

    def check(header: Mapping[str, str]) -> str | None:
        sent_type, sent_md5 = header.get("type", ""), header.get("md5sum", "")
        if sent_type == type_name and sent_md5 in (ours, "*"):
            return None
        return (f"{publisher_name(header)} has datatype/md5sum [{shown(str(sent_type), 80)}/{shown(str(sent_md5), 40)}]"
                f", not [{type_name}/{ours}]")

    return check


class RefusalLog:
    """``check`` that remembers the newest ``keep`` distinct lines it refused with and tells ``on_refusal`` each
    new one once (on the subscriber's loop): give it where a check goes, read :attr:`lines`."""

    def __init__(self, check: HeaderCheck, on_refusal: Callable[[str], None] | None = None, *, keep: int = 20) -> None:
        self.check = check
        self.on_refusal = on_refusal
        self.lines: deque[str] = deque(maxlen=keep)
        """The distinct refusals, oldest first."""

    def __call__(self, header: Mapping[str, str]) -> str | None:
        """The wrapped check's answer, remembered and reported when it is a refusal not heard before."""
        why = self.check(header)
        if why is not None and why not in self.lines:
            self.lines.append(why)
            if self.on_refusal is not None:
                self.on_refusal(why)
        return why

    @property
    def latest(self) -> str:
        """The newest refusal ('' before any)."""
        return self.lines[-1] if self.lines else ""
