"""Where a form's messages go: a topic, published from a node of its own, or a service, called.

Nothing is registered with the master until the first send: a form opened and closed leaves no trace on
the graph. Messages are latched (as ``rostopic pub -1`` latches its one): a subscriber that connects a moment
later still gets the last one, and going from one message to a rate keeps the same publisher, whose
subscribers are already connected, so the rate's first message is not lost to a new connection.
"""

from __future__ import annotations

import asyncio
import time
from typing import Any

from rostui.core.master_errors import MasterUnreachableError
from rostui.core.msg import Message, MessageError, get_service_class
from rostui.core.node.node import AsyncNode, Publisher
from rostui.core.node.services import ServiceException, probe_service
from rostui.core.one_line import exception_line
from rostui.core.rostime import Time
from rostui.models.calling_node import CallingNode

from .rows import FormError, MessageForm

__all__ = ["SendFailed", "TopicSender", "ServiceCaller"]


class SendFailed(Exception):
    """Why a message could not be sent or a service not called, in one line."""


class TopicSender:
    """Publishes a form's messages on a topic from ``/rostui_publish_<pid>_<ms>``; counts them for ``i``. One send
    at a time: two quick ctrl+s before the node is up start one node and one publisher."""

    def __init__(self, master_uri: str | None) -> None:
        self.master_uri = master_uri
        self.node: AsyncNode | None = None
        self.publisher: Publisher | None = None
        self.sent = 0
        self.first_sent: float | None = None
        self._lock = asyncio.Lock()

    def restart_count(self) -> None:
        """``i`` and ``t`` start again from 0 at the next message."""
        self.sent, self.first_sent = 0, None

    def message(self, form: MessageForm) -> Message:
        """The next message of ``form``: ``i`` its number (1 for the first), ``t`` seconds after the first."""
        now = time.monotonic()
        elapsed = 0.0 if self.first_sent is None else now - self.first_sent
        try:
            return form.build(i=self.sent + 1, t=elapsed, now=Time.now())
        except FormError as exc:
            raise SendFailed(str(exc)) from None

    async def send(self, topic: str, form: MessageForm) -> Message:
        """Publish the next message of ``form`` on ``topic``; the message sent."""
        msg = self.message(form)
        async with self._lock:
            publisher = await self._publisher(topic, form.cls)
        try:
            publisher.publish(msg)
        except Exception as exc:  # a value the wire format cannot hold (a float32 of 1e39, a stamp past 2106)
            raise SendFailed(f"cannot send it: {exception_line(exc)}") from None
        if self.first_sent is None:
            self.first_sent = time.monotonic()
        self.sent += 1
        return msg

    async def _publisher(self, topic: str, cls: type[Message]) -> Publisher:
        if self.node is None:
            node = AsyncNode("rostui_publish", anonymous=True, argv=[], master_uri=self.master_uri)
            node.log.console = None
            try:
                await node.start()
            except (MasterUnreachableError, OSError) as exc:
                await node.shutdown("no master")
                raise SendFailed(f"cannot publish: {exc}") from None
            self.node = node
        old = self.publisher
        if old is not None and (old.impl.topic != topic or old.msg_class._md5sum != cls._md5sum):
            await old.unregister()
            self.publisher = None
        if self.publisher is None:
            try:
                self.publisher = await self.node.advertise(topic, cls, queue_size=100, latch=True)
            except (MasterUnreachableError, OSError, ValueError) as exc:
                raise SendFailed(f"cannot advertise {topic}: {exc}") from None
        return self.publisher

    async def close(self) -> None:
        """Unregister and stop the node, if one was started."""
        if self.node is not None:
            node, self.node, self.publisher = self.node, None, None
            await node.shutdown("rostui publish closed")


class ServiceCaller(CallingNode):
    """Calls services from an unannounced node; :meth:`service_class` asks a service for its type."""

    def __init__(self, master_uri: str | None) -> None:
        super().__init__("rostui_call", master_uri, "rostui call closed", quiet=True)
        self.calls = 0

    async def service_class(self, service: str) -> Any:
        """The class of ``service`` (asked of the service itself, as rosservice does); :class:`SendFailed`."""
        await self.start()
        try:
            uri = await self.node.lookup_service(service)
            header = await probe_service(uri, service, self.node.name)
        except (ServiceException, OSError, TimeoutError) as exc:
            raise SendFailed(f"service {service}: {exc or 'does not answer'}") from None
        type_name = header.get("type", "")
        try:
            return get_service_class(type_name)
        except (MessageError, ValueError, OSError) as exc:
            raise SendFailed(f"service {service} is of type {type_name or '?'}, which is not known here: "
                             f"{exc}") from None

    async def call(self, service: str, srv_class: Any, form: MessageForm) -> Message:
        """Call ``service`` with the request ``form`` gives (``i`` this call's number, 1 for the first); the
        response."""
        try:
            request = form.build(i=self.calls + 1, now=Time.now())
        except FormError as exc:
            raise SendFailed(str(exc)) from None
        await self.start()
        try:
            response = await self.node.service_proxy(service, srv_class).call(request)
        except (ServiceException, OSError, TimeoutError) as exc:
            raise SendFailed(f"call to {service} failed: {exc}") from None
        self.calls += 1
        return response
