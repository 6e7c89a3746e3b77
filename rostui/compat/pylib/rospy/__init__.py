"""rospy for unmodified ROS 1 scripts, on rostui's node engine (:mod:`rostui.core.node.sync`).

Nodes, topics, services, parameters, logging, ``Rate``, ``Timer`` and times
keep rospy's names and arguments; message classes a script imports
(``from std_msgs.msg import String``) are rostui's own, so they go through
rostui's publishers and subscribers unchanged.
"""

from __future__ import annotations

import abc
import os
import warnings
from typing import Any, Callable, Mapping, Sequence

from rostui.compat.deferred import import_lean, pause_gc, resume_gc

_collecting = pause_gc()  # the imports below make thousands of objects and no garbage: no collections
try:
    import_lean()  # before the engine's modules: a node that opens no TLS connection never loads OpenSSL

    from rostui.core.node import engine as _engine

    _engine.prefer_uvloop = False  # uvloop loads OpenSSL; ROSTUI_EVENT_LOOP=uvloop still picks it

    from rostui.core.msg import Message
    from rostui.core.node import sync as _sync
    from rostui.core.node.anymsg import AnyMsg
    from rostui.core.rostime import Duration as _Duration
    from rostui.core.rostime import Time as _Time
    from rostui.core.node.sync import (
        get_master_uri, get_node_uri, get_param_cached, is_shutdown, logdebug, logdebug_once, logdebug_throttle, logerr, logerr_once, logerr_throttle, logfatal,
        logfatal_once, logfatal_throttle, loginfo, loginfo_once, loginfo_throttle, logwarn, logwarn_once,
        logwarn_throttle, myargv, on_shutdown, signal_shutdown, sleep, spin,
        wait_for_message,
    )
    from rostui.core.master_errors import unreachable_text
    from rostui.core.node.services import parse_rosrpc_uri
    from rostui.core.xmlrpc import XmlRpcConnectionError, call_sync, ros_result
    from rostui.compat.rospy_console import RospyConsole, RospyConsoleBeforeInit

    from . import exceptions, msproxy, names, rostime
    from ._params import delete_param, get_param, get_param_names, has_param, search_param, set_param
    from ._callback_thread import CallbackThread
    from ._impl import PublisherImpl, SubscriberImpl
    from ._nodeless import caller as _nodeless_caller
    from ._peers import ListenerRelay, rospy_service_header
    from .exceptions import (
        ROSException, ROSInitException, ROSInternalException, ROSInterruptException, ROSSerializationException,
        ROSTimeMovedBackwardsException, ServiceException, TransportException, TransportInitError, TransportTerminated,
    )
    from .msproxy import MasterProxy, get_master
    from ._node_name import check_node_name
    from .names import get_caller_id, get_name, get_namespace, remap_name, resolve_name
    from .rostime import Duration, Time, get_rostime, get_time
finally:
    # frozen: the modules just imported live as long as the script, and the first collection after a pause would
    # walk every object they made (8 ms of a talker's start here)
    resume_gc(_collecting, freeze=True)

__all__ = [
    "AnyMsg", "DEBUG", "Duration", "ERROR", "FATAL", "INFO", "MasterProxy", "Message", "Publisher", "ROSException",
    "ROSInitException", "ROSInternalException", "ROSInterruptException", "ROSSerializationException",
    "ROSTimeMovedBackwardsException", "Rate", "Service", "SubscribeListener", "TransportInitError",
    "TransportTerminated", "Header", "logout", "parse_rosrpc_uri", "ServiceException", "ServiceProxy", "Subscriber",
    "Time", "Timer", "TimerEvent", "TransportException", "WARN", "delete_param", "exceptions",
    "get_caller_id", "get_master", "get_master_uri", "get_name", "get_namespace", "get_node_uri", "get_param",
    "get_param_cached", "get_param_names", "get_published_topics", "get_ros_root", "get_rostime", "get_time", "has_param",
    "init_node", "is_shutdown", "logdebug", "logdebug_once", "logdebug_throttle", "logerr", "logerr_once",
    "logerr_throttle", "logfatal", "logfatal_once", "logfatal_throttle", "loginfo", "loginfo_once",
    "loginfo_throttle", "logwarn", "logwarn_once", "logwarn_throttle", "myargv", "names", "on_shutdown",
    "remap_name", "resolve_name", "rostime", "search_param", "set_param", "signal_shutdown", "sleep", "spin",
    "wait_for_message", "wait_for_service",
]

DEBUG = 1
"""Log level constants, rosgraph_msgs/Log's values (``init_node(..., log_level=rospy.DEBUG)``)."""
INFO = 2
WARN = 4
ERROR = 8
FATAL = 16


logout = loginfo
"""rospy's old name of :func:`loginfo`."""

_sync.use_console(RospyConsole(), before_init=RospyConsoleBeforeInit())  # lines look like rospy's: [INFO] [1700...]: ...


def __getattr__(name: str) -> Any:
    """``rospy.Header``: std_msgs/Header, built on first use so ``import rospy`` stays quick."""
    if name == "Header":
        from rostui.core.msg import get_message_class

        return get_message_class("std_msgs/Header")
    raise AttributeError(f"module 'rospy' has no attribute {name!r}")


class SubscribeListener:
    """The base class of a Publisher's *subscriber_listener*: told of each subscriber that comes or goes."""

    def peer_subscribe(self, topic_name: str, topic_publish: Callable[[Any], None],
                       peer_publish: Callable[[Any], None]) -> None:
        """A subscriber connected: *topic_publish* sends to every subscriber, *peer_publish* to this one."""

    def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
        """A subscriber disconnected; *num_peers* are still connected."""


def init_node(name: str, argv: Sequence[str] | None = None, anonymous: bool = False,
              log_level: int | None = None, disable_rostime: bool = False, disable_rosout: bool = False,
              disable_signals: bool = False, xmlrpc_port: int = 0, tcpros_port: int = 0) -> None:
    """Start this process's node, as rospy's ``init_node``; its console lines look like rospy's.

    With the parameter ``/use_sim_time`` true the node follows ``/clock``
    unless *disable_rostime*.  *disable_rosout*, *xmlrpc_port* and
    *tcpros_port* are accepted and have no effect: the node always logs to
    ``/rosout`` and listens on free ports.  As rospy, a name that is not a
    legal base name (``draw_circle.py``) is taken with a warning; an empty one
    or one with a namespace raises ValueError.
    """
    check_node_name(name)
    _sync.init_node(name, argv=argv, anonymous=anonymous, log_level=log_level, disable_signals=disable_signals,
                    disable_rostime=disable_rostime, lenient_name=True, logger_services_later=True)
    try:
        _Topic.start_pending()
    finally:
        _sync.serve_logger_services()  # in the background: the script's first publish does not wait for them


class _Topic(abc.ABC):
    """A topic handle that, made before ``init_node`` as rospy allows, registers once the node starts."""

    _pending: list[_Topic] = []

    def __init__(self) -> None:
        self._impl: Any = None
        if _initialized():
            self._start()
        else:
            _Topic._pending.append(self)

    @abc.abstractmethod
    def _start(self) -> None:
        """Register with the node that now runs."""

    def _handle(self) -> Any:
        if self._impl is None:
            raise ROSException("ROS node has not been initialized")
        return self._impl

    @classmethod
    def start_pending(cls) -> None:
        """Register every handle made before ``init_node``."""
        pending, cls._pending = cls._pending, []
        for topic in pending:
            topic._start()

    def get_num_connections(self) -> int:
        """The number of connected peers."""
        return int(self._handle().get_num_connections())

    def unregister(self) -> None:
        """Stop publishing or receiving."""
        if self._impl is None:
            _Topic._pending.remove(self)
        else:
            self._impl.unregister()


class Publisher(_Topic):
    """Publish messages on a topic, as ``rospy.Publisher``; may be made before ``init_node``.

    *subscriber_listener* (a :class:`SubscribeListener`) is told of each
    subscriber that connects or leaves; *headers* go into the connection
    header every subscriber receives (``msg._connection_header`` there). A
    message with a Header gets rospy's sequence numbers: from 1, counting
    only messages sent while a subscriber is connected.
    """

    def __init__(self, name: str, data_class: Any, subscriber_listener: Any = None, tcp_nodelay: bool = False,
                 latch: bool = False, headers: dict[str, str] | None = None, queue_size: int | None = None) -> None:
        self.name = self.resolved_name = resolve_name(name)
        self.data_class, self.type = data_class, data_class._type
        self.queue_size, self.latch, self.tcp_nodelay = queue_size, latch, tcp_nodelay
        self._listener, self._headers = subscriber_listener, dict(headers or {})
        super().__init__()

    def _start(self) -> None:
        self._impl = _sync.Publisher(self.resolved_name, self.data_class, queue_size=self.queue_size,
                                     latch=self.latch, tcp_nodelay=self.tcp_nodelay)
        publication = self._impl._publication
        publication.seq_when_connected = True
        publication.extra_header.update(self._headers)
        if self._listener is not None:
            publication.peer_listeners.append(ListenerRelay(self._listener, self.publish))

    def publish(self, *args: Any, **kwargs: Any) -> None:
        """Publish a message, or one built from its fields given positionally or as keywords."""
        self._handle().publish(*args, **kwargs)

    @property
    def impl(self) -> PublisherImpl:
        """The connections, as rospy's ``Publisher.impl`` shows them (``has_connection(callerid)``)."""
        return PublisherImpl(self)


class Subscriber(_Topic):
    """Call *callback* with each message of a topic, as ``rospy.Subscriber``; may be made before ``init_node``.

    With *callback_args* the callback gets ``(message, callback_args)``; *buff_size* is accepted. As in
    rospy, the callback runs on a thread of this subscriber's own, so it may block.
    """

    def __init__(self, name: str, data_class: Any, callback: Callable[..., Any] | None = None,
                 callback_args: Any = None, queue_size: int | None = None, buff_size: int = 65536,
                 tcp_nodelay: bool = False) -> None:
        self.name = self.resolved_name = resolve_name(name)
        self.data_class, self.callback, self.callback_args = data_class, callback, callback_args
        self.queue_size, self.tcp_nodelay = queue_size, tcp_nodelay
        super().__init__()

    def _start(self) -> None:
        self._calls = None if self.callback is None else CallbackThread(
            self.callback, self.queue_size, self.resolved_name, logerr)
        self._impl = _sync.Subscriber(self.resolved_name, self.data_class, self._calls,
                                      callback_args=self.callback_args, queue_size=self.queue_size,
                                      tcp_nodelay=self.tcp_nodelay)

    @property
    def impl(self) -> SubscriberImpl:
        """The connections, as rospy's ``Subscriber.impl`` shows them (``connections[i].callerid_pub``)."""
        return SubscriberImpl(self)

    def unregister(self) -> None:
        """Stop receiving; a callback under way finishes, queued messages are dropped."""
        super().unregister()
        calls: CallbackThread | None = getattr(self, "_calls", None)
        if calls is not None:
            calls.stop()


class Service(_sync.Service):
    """Serve a service, as ``rospy.Service``; the handler runs in a worker thread.

    The request carries the client's connection header as
    ``_connection_header``; clients get rospy's server header. *buff_size*
    is accepted (rostui reads whole requests).  A handler that
    raises anything but ServiceException has *error_handler* called as
    ``error_handler(exception, type, value, traceback)`` before the caller
    gets the error, as rospy does.
    """

    def __init__(self, name: str, service_class: Any, handler: Callable[[Any], Any], buff_size: int = 65536,
                 error_handler: _sync.ErrorHandler | None = None) -> None:
        super().__init__(name, service_class, handler, error_handler=error_handler)
        self._server.header_fields = rospy_service_header(self.resolved_name, service_class, get_caller_id())


_initialized = names.is_initialized


class ServiceProxy:
    """Call a service like a function, as ``rospy.ServiceProxy``; works before ``init_node`` too.

    Call it with the request's fields positionally, as keywords, or with a
    request object; *persistent* keeps one connection for every call.
    """

    def __init__(self, name: str, service_class: Any, persistent: bool = False,
                 headers: dict[str, str] | None = None) -> None:
        self.service_class = service_class
        self.request_class = service_class._request_class
        self.response_class = service_class._response_class
        self.persistent = persistent
        self.resolved_name = resolve_name(name)
        self._node_proxy: _sync.ServiceProxy | None = None
        if _initialized():
            self._node_proxy = _sync.ServiceProxy(name, service_class, persistent=persistent, headers=headers)
        else:
            self._caller = _nodeless_caller()
            self._proxy = self._caller.proxy(self.resolved_name, service_class, persistent, headers)

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        """Call the service and return its response; ServiceException on failure."""
        return self.call(*args, **kwargs)

    def call(self, *args: Any, **kwargs: Any) -> Any:
        """Call the service and return its response; ServiceException on failure."""
        if self._node_proxy is not None:
            return self._node_proxy.call(*args, **kwargs)
        return self._caller.engine.run(self._proxy.call(*args, **kwargs))

    def wait_for_service(self, timeout: float | None = None) -> None:
        """Block until the service is available; ROSException after *timeout* seconds."""
        wait_for_service(self.resolved_name, timeout)

    def close(self) -> None:
        """Close a persistent connection."""
        if self._node_proxy is not None:
            self._node_proxy.close()
        else:
            self._caller.engine.run(self._proxy.close())


def wait_for_service(service: str, timeout: float | None = None) -> None:
    """Block until *service* is registered and reachable; ROSException after *timeout* seconds.

    Works before ``init_node``, as in rospy.
    """
    if _initialized():
        _sync.wait_for_service(service, timeout)
        return
    resolved = resolve_name(service)
    if not _nodeless_caller().wait_for_service(resolved, timeout):
        raise ROSException(f"timeout exceeded while waiting for service {resolved}")


class Rate(_sync.Rate):
    """Keep a loop at *hz* cycles a second of ROS time, as ``rospy.Rate``.

    With *reset*, simulated time jumping back restarts the cycle instead of
    raising ROSTimeMovedBackwardsException.
    """

    def __init__(self, hz: float, reset: bool = False) -> None:
        super().__init__(hz, reset=reset)

    def remaining(self) -> Duration:
        """ROS time left in the current cycle."""
        left = super().remaining()
        return Duration(left.secs, left.nsecs)


class TimerEvent:
    """What a :class:`Timer` callback receives: expected and real times of this and the last call."""

    def __init__(self, last_expected: Time | None, last_real: Time | None, current_expected: Time,
                 current_real: Time, last_duration: float | None) -> None:
        self.last_expected = last_expected
        self.last_real = last_real
        self.current_expected = current_expected
        self.current_real = current_real
        self.last_duration = last_duration


def _time(stamp: _Time | None) -> Time | None:
    return None if stamp is None else Time(stamp.secs, stamp.nsecs)


class Timer(_sync.Timer):
    """Call ``callback(TimerEvent)`` every *period* of ROS time on its own thread, as ``rospy.Timer``.

    With *reset*, simulated time jumping back restarts the period; without it the timer stops.
    """

    def __init__(self, period: _Duration | float, callback: Callable[[TimerEvent], Any],
                 oneshot: bool = False, reset: bool = False) -> None:
        super().__init__(period, callback, oneshot=oneshot, reset=reset)

    def make_event(self, last_expected: _Time | None, last_real: _Time | None, current_expected: _Time,
                   current_real: _Time, last_duration: float | None) -> TimerEvent:
        """rospy's TimerEvent, its times ``rospy.Time``."""
        return TimerEvent(_time(last_expected), _time(last_real), Time(current_expected.secs, current_expected.nsecs),
                          Time(current_real.secs, current_real.nsecs), last_duration)


def get_ros_root(required: bool = False, env: Mapping[str, str] | None = None) -> str | None:
    """``ROS_ROOT`` from *env* (default the environment); ROSException when *required* and unset.

    Deprecated in rospy, so it warns as rospy does.
    """
    warnings.warn("Call to deprecated function get_ros_root.", category=DeprecationWarning, stacklevel=2)
    root = (os.environ if env is None else env).get("ROS_ROOT")
    if required and not root:
        raise ROSException("ROS_ROOT is not set")
    return root


def get_published_topics(namespace: str = "/") -> list[list[str]]:
    """``[topic, type]`` pairs of every topic published under *namespace*."""
    master = get_master_uri() if _initialized() else _nodeless_caller().master_uri
    try:
        return [list(pair) for pair in ros_result(call_sync(master, "getPublishedTopics", get_caller_id(), namespace))]
    except XmlRpcConnectionError as exc:
        raise ROSException(unreachable_text(master, str(exc))) from exc
