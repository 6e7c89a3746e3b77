"""A raw ROS 1 publisher that lies in its connection header, run on threads of the test process (stdlib only).

It registers a topic with the master under any type, answers ``requestTopic`` with a TCPROS port, and to every
subscriber that connects sends the header the test chose (``type``, ``md5sum``, ``message_definition``: any of
them false), then the same frame over and over.  Nothing of rostui is used, so the lies reach the subscriber
exactly as written.
"""

from __future__ import annotations

import hashlib
import socket
import struct
import threading
import xmlrpc.client
from dataclasses import dataclass, field
from typing import Any
from xmlrpc.server import SimpleXMLRPCServer

#: The line between types in a ``message_definition``.
SEPARATOR = "\n" + "=" * 80 + "\n"


def header_bytes(fields: dict[str, str]) -> bytes:
    """A TCPROS connection header: its length, then each ``key=value`` with its length."""
    body = b"".join(struct.pack("<I", len(item)) + item for item in (f"{k}={v}".encode() for k, v in fields.items()))
    return struct.pack("<I", len(body)) + body


def md5_of_text(text: str) -> str:
    """The hex md5 of ``text``: what an attacker computes to make a definition agree with its md5sum."""
    return hashlib.md5(text.encode()).hexdigest()


@dataclass
class LyingPublisher:
    """Publishes ``frame`` on ``topic`` every ``period`` seconds to whoever connects, under a chosen header.

    ``registered_type`` is the type the master is told (``type_name`` by default).  Use it in a ``with`` block.
    """

    master_uri: str
    topic: str
    type_name: str
    md5sum: str
    definition: str
    frame: bytes
    period: float = 0.05
    callerid: str = "/liar"
    registered_type: str | None = None
    connections: int = 0
    frames_sent: int = 0
    _stop: threading.Event = field(default_factory=threading.Event)
    _socks: list[socket.socket] = field(default_factory=list)

    def __enter__(self) -> LyingPublisher:
        self._tcp = socket.socket()
        self._tcp.bind(("127.0.0.1", 0))
        self._tcp.listen(16)
        self._port = self._tcp.getsockname()[1]
        self._slave = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
        self._slave.register_instance(_Slave(self._port))
        self.uri = f"http://127.0.0.1:{self._slave.server_address[1]}/"
        threading.Thread(target=self._accept, daemon=True).start()
        threading.Thread(target=self._slave.serve_forever, kwargs={"poll_interval": 0.05}, daemon=True).start()
        xmlrpc.client.ServerProxy(self.master_uri).registerPublisher(
            self.callerid, self.topic, self.registered_type or self.type_name, self.uri)
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        try:
            xmlrpc.client.ServerProxy(self.master_uri).unregisterPublisher(self.callerid, self.topic, self.uri)
        except (OSError, xmlrpc.client.Error):
            pass
        self._slave.shutdown()
        self._slave.server_close()
        self._tcp.close()
        for sock in list(self._socks):
            sock.close()

    def _accept(self) -> None:
        while not self._stop.is_set():
            try:
                conn, _ = self._tcp.accept()
            except OSError:
                return
            self._socks.append(conn)
            threading.Thread(target=self._serve, args=(conn,), daemon=True).start()

    def _serve(self, conn: socket.socket) -> None:
        try:
            size = struct.unpack("<I", conn.recv(4, socket.MSG_WAITALL))[0]
            conn.recv(size, socket.MSG_WAITALL)
            conn.sendall(header_bytes({"callerid": self.callerid, "topic": self.topic, "type": self.type_name,
                                       "md5sum": self.md5sum, "message_definition": self.definition,
                                       "latching": "0"}))
            self.connections += 1
            framed = struct.pack("<I", len(self.frame)) + self.frame
            while not self._stop.wait(self.period):
                conn.sendall(framed)
                self.frames_sent += 1
        except OSError:
            pass
        finally:
            conn.close()


class _Slave:
    """The few slave API calls a subscriber makes of a publisher."""

    def __init__(self, port: int) -> None:
        self.port = port

    def requestTopic(self, caller: str, topic: str, protocols: Any) -> list[Any]:  # noqa: N802 (ROS's name)
        return [1, "", ["TCPROS", "127.0.0.1", self.port]]

    def getPid(self, caller: str) -> list[Any]:  # noqa: N802
        return [1, "", 0]

    def getBusInfo(self, caller: str) -> list[Any]:  # noqa: N802
        return [1, "", []]

    def publisherUpdate(self, caller: str, topic: str, publishers: Any) -> list[Any]:  # noqa: N802
        return [1, "", 0]

    def shutdown(self, caller: str, msg: str = "") -> list[Any]:
        return [1, "", 0]
