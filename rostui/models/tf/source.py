"""TfSource: a node that listens to /tf and /tf_static and fills a :class:`TfBuffer`.

The node (``/<name>_<pid>_<ms>``, kept registered by a :class:`MasterLink`) subscribes to both
topics with ``AnyMsg``, so every message carries its publisher's connection header: the
``callerid`` there is the edge's broadcaster. Messages are decoded here as
``tf2_msgs/TFMessage``, rostui's version of it: a publisher whose header says another type or
md5sum is refused (its connection dropped, never decoded) and a message of garbage dropped; each
is reported in :attr:`TfSource.problems`, nothing else.
"""

from __future__ import annotations

import time
from collections import deque
from typing import Any, Callable

from rostui.core.msg import get_message_class
from rostui.core.node import AnyMsg, AsyncNode
from rostui.core.node.header_check import RefusalLog, of_type
from rostui.models.master_link import LinkedSource, MasterLink, SourceState
from rostui.tools.tf.buffer import TfBuffer

__all__ = ["TF_TOPIC", "TF_STATIC_TOPIC", "TF_TYPE", "TfSource", "feed_raw"]

TF_TOPIC = "/tf"
TF_STATIC_TOPIC = "/tf_static"
TF_TYPE = "tf2_msgs/TFMessage"


def feed_raw(buffer: TfBuffer, raw: AnyMsg, *, static: bool, received: float) -> list[str]:
    """Decode one raw TFMessage and add it to ``buffer``; returns why anything was refused."""
    header = raw._connection_header or {}
    caller = header.get("callerid", "") or "?"
    sent_type = header.get("type", TF_TYPE)
    if sent_type not in (TF_TYPE, "*"):
        return [f"[{caller}] publishes {sent_type}, not {TF_TYPE}; ignored"]
    msg_class = get_message_class(TF_TYPE)
    sent_md5 = header.get("md5sum", "*")
    if sent_md5 not in (msg_class._md5sum, "*"):
        return [f"[{caller}] publishes {TF_TYPE} with md5sum {sent_md5}, not rostui's {msg_class._md5sum}; ignored"]
    try:
        msg = msg_class.deserialize(raw.serialize())
    except Exception as exc:  # a peer's garbage: drop the message, keep listening
        return [f"undecodable {TF_TYPE} from [{caller}]: {exc}"]
    return buffer.add_message(msg, static=static, broadcaster=caller, received=received)


class TfSource(LinkedSource):
    """/tf and /tf_static of the master at ``master_uri`` in :attr:`buffer`; run :meth:`run` as a task.

    ``on_change()`` runs after each message is taken (on the caller's loop); ``clock`` stamps
    arrivals (wall seconds; tests pass their own).
    """

    def __init__(self, master_uri: str, *, node_name: str = "rostui_tf", buffer: TfBuffer | None = None,
                 on_change: Callable[[], None] | None = None,
                 on_state: Callable[[SourceState], None] | None = None,
                 clock: Callable[[], float] = time.time) -> None:
        self.buffer = buffer if buffer is not None else TfBuffer()
        self.clock = clock
        self.on_change = on_change or (lambda: None)
        self.problems: deque[str] = deque(maxlen=50)
        self.messages = 0
        self.refused = RefusalLog(of_type(TF_TYPE), self.problems.append)
        """Publishers of /tf or /tf_static refused for another type or md5sum (each also a line of problems)."""
        self.link = MasterLink(node_name, master_uri, on_connect=self._subscribe, on_state=on_state)

    async def _subscribe(self, node: AsyncNode) -> None:
        """After each registration with a master: subscribed once (the node registers them again itself)."""
        if TF_TOPIC not in node.subscriptions:
            await node.subscribe(TF_TOPIC, AnyMsg, self._on_message, callback_args=False, check=self.refused)
        if TF_STATIC_TOPIC not in node.subscriptions:
            await node.subscribe(TF_STATIC_TOPIC, AnyMsg, self._on_message, callback_args=True, check=self.refused)

    def _on_message(self, raw: Any, static: bool) -> None:
        self.messages += 1
        self.problems.extend(feed_raw(self.buffer, raw, static=static, received=self.clock()))
        self.on_change()

    async def run(self) -> None:
        """Keep the node registered and subscribed until :meth:`stop`."""
        await self.link.run()

    async def stop(self) -> None:
        """Unsubscribe and shut the node down."""
        await self.link.stop()
