"""``rostui topic echo -b BAG [TOPIC]``: a bag's messages printed as ``rostopic echo -b`` prints them, no master."""

from __future__ import annotations

import os
from typing import Callable

from rostui.tools.topic.common import Out, TopicToolError, resolve_topic
from rostui.tools.topic.echo import EchoFormatter


def _field_of(want: str, topic: str) -> str | None:
    """What of ``topic``'s messages ``want`` asks for: '' the whole message, ``/x`` a field, None nothing."""
    if topic == want:
        return ""
    if want.startswith(topic + "/"):
        return want[len(topic):]
    return None


def echo_bag(path: str, topic: str | None, formatter: EchoFormatter, out: Out,
             warn: Callable[[str], None] | None = None) -> int:
    """Print the messages of ``topic`` (or of every topic when None) in ``path``, in time order.

    ``topic`` may name a field (``/pose/x``); the formatter's count stops it early. Returns how many
    messages were printed; TopicToolError for a bag that cannot be read or holds no readable message (a file
    cut short before its first message). A file cut short later is echoed up to the cut, and ``warn`` gets
    one line saying so.
    """
    from rostui.core.bag.files import merged_messages, open_reader
    from rostui.core.bag.decode import Decoder
    from rostui.core.bag.model import BagError, MalformedRecord

    if not os.path.exists(path):
        raise TopicToolError(f"bag file [{path}] does not exist")
    want = topic.rstrip("/") if topic else None
    try:
        reader = open_reader(path)
    except BagError as exc:
        raise TopicToolError(f"unable to use bag file: {exc}") from None
    decode = Decoder()
    resolved: dict[str, str] = {}
    try:
        summary = reader.summary()
        if not summary.closed:
            why = f" ({summary.problem})" if summary.problem else ""
            if not summary.message_count:
                raise TopicToolError(f"unable to use bag file: {path} was cut short and holds no messages{why}")
            if warn is not None:
                warn(f"WARNING: {path} was cut short{why}: its {summary.message_count} messages before the cut "
                     "are echoed")
        for conn, time_ns, data, _source in merged_messages([reader]):
            name = resolved.get(conn.topic)
            if name is None:
                name = resolved[conn.topic] = conn.topic if conn.topic.startswith("/") else resolve_topic(conn.topic)
            field = "" if want is None else _field_of(want, name)
            if field is None:
                continue
            formatter.select(field)
            text = formatter.format(decode(conn, data), now_nsec=time_ns)
            if text is not None:
                out(text)
            if formatter.done:
                break
    except MalformedRecord as exc:  # its line names the file and the byte
        raise TopicToolError(str(exc)) from None
    except BagError as exc:
        raise TopicToolError(f"{path}: {exc}") from None
    finally:
        reader.close()
    return formatter.count
