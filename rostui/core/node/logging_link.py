"""Connects a node's NodeLog to ROS: /rosout, its log file, and the logger-level services.

Once the master answers, a node publishes every record it logs on ``/rosout``
as rosgraph_msgs/Log, appends it to its own file in the run's log directory,
and serves ``~get_loggers`` / ``~set_logger_level`` (roscpp's services) so
that levels can be read and changed from outside at run time.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from typing import Any, Callable, Protocol

from rostui.core.log import Level, LogRecord, NodeLog, NodeLogFile, log_root, run_log_dir
from rostui.core.msg import Message, Service, get_message_class, get_service_class
from rostui.core.names import NodeArgs
from rostui.core.node.services import ServiceException
from rostui.core.rostime import Time

ROSOUT_QUEUE = 100


class MessagePublisher(Protocol):
    """A handle that publishes messages on one topic."""

    def publish(self, msg: Message, /) -> None:
        """Send one message."""


class LoggingHost(Protocol):
    """What a node's logging link needs from its node (an AsyncNode is one)."""

    @property
    def name(self) -> str:
        """The node's name."""

    @property
    def args(self) -> NodeArgs:
        """The node's ROS arguments (``__log:=`` names its log file)."""

    @property
    def log(self) -> NodeLog:
        """The node's log."""

    @property
    def is_shutdown(self) -> bool:
        """True once shutdown began."""

    @property
    def publications(self) -> Mapping[str, object]:
        """The node's publications by topic (a /rosout record lists the topics)."""

    async def advertise(self, topic: str, msg_class: type[Message], *, queue_size: int | None = None
                        ) -> MessagePublisher:
        """Publish on a topic."""

    async def advertise_service(self, name: str, srv_class: type[Service], handler: Callable[[Any], Any]) -> object:
        """Serve a service."""

    async def get_param(self, name: str, default: Any = ...) -> Any:
        """A parameter's value, or ``default`` when it is unset."""


_PY_TO_ROS = {logging.DEBUG: Level.DEBUG, logging.INFO: Level.INFO, logging.WARNING: Level.WARN,
              logging.ERROR: Level.ERROR, logging.CRITICAL: Level.FATAL}


class LibraryLogForwarder(logging.Handler):
    """Sends rostui's own diagnostics (stdlib ``logging`` under ``rostui``) into a node's log.

    So a dropped connection appears on the console in ROS's format and on
    /rosout, like roscpp's own warnings do.
    """

    def __init__(self, node: LoggingHost) -> None:
        super().__init__(logging.WARNING)
        self.node = node

    def emit(self, record: logging.LogRecord) -> None:
        """Forward one record at its ROS level."""
        level = _PY_TO_ROS.get(record.levelno, Level.WARN)
        try:
            self.node.log.log(level, "%s", record.getMessage(), logger="rostui")
        except Exception:
            self.handleError(record)


def attach_library_log(node: LoggingHost) -> LibraryLogForwarder | None:
    """Forward rostui's library warnings to ``node`` unless another node already receives them."""
    library = logging.getLogger("rostui")
    if any(isinstance(h, LibraryLogForwarder) for h in library.handlers):
        return None
    handler = LibraryLogForwarder(node)
    library.addHandler(handler)
    library.propagate = False
    return handler


def detach_library_log(handler: LibraryLogForwarder | None) -> None:
    """Stop forwarding (the node shut down)."""
    if handler is not None:
        library = logging.getLogger("rostui")
        library.removeHandler(handler)
        if not any(isinstance(h, LibraryLogForwarder) for h in library.handlers):
            library.propagate = True


class NodeLogging:
    """The ROS side of one node's logging."""

    def __init__(self, node: LoggingHost) -> None:
        self.node = node
        self.log_class = get_message_class("rosgraph_msgs/Log")
        self.header_class = get_message_class("std_msgs/Header")
        self.rosout: MessagePublisher | None = None
        self.file: NodeLogFile | None = None
        #: The logger services announced so far (``~get_loggers``, ``~set_logger_level``).
        self.served: set[str] = set()
        self.forwarder: LibraryLogForwarder | None = None

    def attach(self) -> None:
        """Start receiving rostui's library warnings (called when the node starts)."""
        self.forwarder = attach_library_log(self.node)

    async def announce(self, *, publish_rosout: bool = True, services: bool = True) -> None:
        """Register /rosout and the logger services; open the node's log file.

        Without *services*, the logger services wait for :meth:`serve_loggers`. Called again after a failure
        (the master went away half-way), it does only what is left.
        """
        node = self.node
        if publish_rosout and self.rosout is None:
            self.rosout = await node.advertise("/rosout", self.log_class, queue_size=ROSOUT_QUEUE)
            node.log.add_sink(self.publish)
        if services:
            await self.serve_loggers()
        if self.file is None:
            run_id = await node.get_param("/run_id", None)
            folder = run_log_dir(str(run_id)) if run_id else log_root()
            self.file = NodeLogFile.for_node(node.name, folder, node.args.log)
            node.log.add_sink(self.file)

    async def serve_loggers(self) -> None:
        """Serve and register ``~get_loggers`` and ``~set_logger_level`` (those not served yet); none once the
        node is shutting down."""
        services = (("~get_loggers", "roscpp/GetLoggers", self.get_loggers),
                    ("~set_logger_level", "roscpp/SetLoggerLevel", self.set_logger_level))
        for name, srv_type, handler in services:
            if name not in self.served and not self.node.is_shutdown:
                await self.node.advertise_service(name, get_service_class(srv_type), handler)
                self.served.add(name)

    def publish(self, record: LogRecord) -> None:
        """The /rosout sink: one rosgraph_msgs/Log per record."""
        if self.rosout is None or self.node.is_shutdown:
            return
        msg = self.log_class(header=self.header_class(stamp=Time(record.secs, record.nsecs)),
                             level=int(record.level), name=record.node, msg=record.message, file=record.file,
                             function=record.function, line=record.line, topics=sorted(self.node.publications))
        self.rosout.publish(msg)

    def get_loggers(self, _request: Any) -> Any:
        """roscpp/GetLoggers: every logger with its effective level."""
        logger_class = get_message_class("roscpp/Logger")
        loggers = [logger_class(name=name, level=level.text) for name, level in self.node.log.tree.loggers()]
        return get_service_class("roscpp/GetLoggers")._response_class(loggers=loggers)

    def set_logger_level(self, request: Any) -> Any:
        """roscpp/SetLoggerLevel: change a logger's level now; unknown levels are an error."""
        try:
            level = Level.parse(request.level)
            self.node.log.tree.set_level(request.logger, level)
        except ValueError as exc:
            raise ServiceException(str(exc)) from None
        return get_service_class("roscpp/SetLoggerLevel")._response_class()

    def close(self) -> None:
        """Stop writing the log file and forwarding library warnings."""
        detach_library_log(self.forwarder)
        self.forwarder = None
        if self.file is not None:
            self.node.log.remove_sink(self.file)
            self.file.close()
        if self.rosout is not None:
            self.node.log.remove_sink(self.publish)
