"""The synchronous, rospy-like face of the node engine, for user scripts.

One node per process, as in rospy::

    from rostui import client as ros
    from rostui.core.msg import get_message_class

    String = get_message_class("std_msgs/String")
    ros.init_node("talker")
    pub = ros.Publisher("chatter", String, queue_size=10)
    rate = ros.Rate(10)
    while not ros.is_shutdown():
        pub.publish(String(data="hello"))
        rate.sleep()

Subscriber callbacks run on the engine thread, one at a time, as soon as a
message arrives; keep them short.  Service handlers run in worker threads, so
they may block.  Blocking calls (service calls, parameters) work from any
thread, callbacks included.
"""

from __future__ import annotations

import asyncio
import atexit
import os
import signal
import sys
import threading
import time
from types import TracebackType
from typing import Any, Callable, Sequence

from rostui.core import names
from rostui.core.log import Console, Level, LoggerTree, NodeLog, package_logger
from rostui.core.node import node as _node
from rostui.core.node import timing as _timing
from rostui.core.node.clock import CLOCK_TOPIC, USE_SIM_TIME_PARAM, Clock
from rostui.core.node.errors import ROSException as ROSException
from rostui.core.node.errors import ROSInterruptException as ROSInterruptException
from rostui.core.node.errors import ROSTimeMovedBackwardsException as ROSTimeMovedBackwardsException
from rostui.core.node.engine import Engine
from rostui.core.master_errors import unreachable_text
from rostui.core.packages import package_of
from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node.services import ServiceException, make_response, probe_service
from rostui.core.node.topics import TopicType
from rostui.core.rostime import Duration, Time
from rostui.core.xmlrpc import RosApiError, XmlRpcClient, XmlRpcConnectionError, call_sync, ros_result


class _State:
    """The process's single node and its engine."""

    engine: Engine | None = None
    node: _node.AsyncNode | None = None
    shutdown = threading.Event()
    signalled = False
    """Set (a plain assignment, no lock) by the Ctrl-C/SIGTERM handler before the engine sets ``shutdown``."""
    reason = ""
    hooks: list[Callable[..., Any]] = []
    clock = Clock()
    console: Console | None = None


_state = _State()


def _require() -> tuple[Engine, _node.AsyncNode]:
    if _state.engine is None or _state.node is None:
        raise ROSException("init_node() has not been called")
    return _state.engine, _state.node


def _excepthook(kind: type[BaseException], value: BaseException, tb: Any) -> None:
    if isinstance(value, ROSInterruptException):
        return
    _previous_excepthook(kind, value, tb)


_previous_excepthook = sys.excepthook


def init_node(name: str, argv: Sequence[str] | None = None, anonymous: bool = False,
              log_level: int | Level | None = None, disable_signals: bool = False,
              master_uri: str | None = None, wait_for_master: bool = True,
              disable_rostime: bool = False, lenient_name: bool = False, logger_services_later: bool = False) -> None:
    """Start this process's node.

    ``argv`` is the full command line, program name first, as in rospy
    (default ``sys.argv``); its ROS arguments (remaps, ``__name:=``,
    ``_param:=``...) configure the node.  When the parameter ``/use_sim_time``
    is true the node follows simulated time from ``/clock`` (see
    :func:`get_rostime`), unless *disable_rostime* (or *wait_for_master* is
    False: without a master to ask, the node keeps the wall clock).
    ``lenient_name`` takes any name without ``/`` or ``~``, as rospy does
    (``draw_circle.py``). With ``logger_services_later`` the node's
    ``~get_loggers`` and ``~set_logger_level`` are registered by
    :func:`serve_logger_services` instead, in the background.
    """
    global _previous_excepthook
    if _state.node is not None:
        raise ROSException(f"init_node() was already called for {_state.node.name}")
    engine = Engine()
    argv = list(sys.argv if argv is None else argv)
    package = package_of(argv[0]) if argv and argv[0] and os.path.exists(argv[0]) else None
    node = _node.AsyncNode(name, argv=argv[1:], anonymous=anonymous, master_uri=master_uri, package=package,
                           busy_poll=True, lenient_name=lenient_name)
    if _state.console is not None:
        node.log.console = _state.console
    if log_level is not None:
        node.log.set_level(Level(int(log_level)))
    engine.run(node.start(announce=False))
    node.shutdown_hooks.append(_on_node_shutdown)
    _state.engine, _state.node = engine, node
    _state.shutdown.clear()
    _state.signalled = False
    if not disable_signals and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, _on_signal)
        signal.signal(signal.SIGTERM, _on_signal)
    atexit.register(_atexit)
    if sys.excepthook is not _excepthook:
        _previous_excepthook = sys.excepthook
        sys.excepthook = _excepthook
    if wait_for_master:
        def warn() -> None:
            node.log.warn("Unable to contact the master at [%s]; will keep trying.", node.master_uri)
        try:
            sim_time = engine.run(_connect(node, warn, not disable_rostime, not logger_services_later))
        except _WaitFailed as failed:
            if node.is_shutdown:
                raise ROSInterruptException("shutdown while waiting for the master") from None
            raise failed.error from None
        if sim_time:
            _start_sim_time(engine, node)


class _WaitFailed(Exception):
    """The master did not answer :func:`_connect`'s wait (*error* says why)."""

    def __init__(self, error: _node.MasterError) -> None:
        super().__init__(str(error))
        self.error = error


async def _connect(node: _node.AsyncNode, on_wait: Callable[[], None], ask_sim_time: bool,
                   logger_services: bool = True) -> bool:
    """Wait for the master, announce the node's logging (its logger services too, with *logger_services*), and
    say whether the master's ``/use_sim_time`` is true (when *ask_sim_time*): one trip to the engine thread,
    and over the node's own connection to the master.
    Only Exceptions leave it: a BaseException (ROSInterruptException) raised on the engine thread ends its loop."""
    try:  # at once: a master that answers it needs no getPid first (one trip fewer on the way to the first publish)
        await node.announce(logger_services=logger_services)
    except _node.MasterError:  # none answers yet, or not as a master: wait for one, as before, then announce again
        try:
            await node.wait_for_master(on_wait=on_wait)
        except _node.MasterError as exc:
            raise _WaitFailed(exc) from None
        await node.announce(logger_services=logger_services)
    if not ask_sim_time:
        return False
    try:
        return bool(await node.get_param(USE_SIM_TIME_PARAM, False))
    except _node.MasterError as exc:
        raise ROSException(unreachable_text(node.master_uri, str(exc))) from exc


def serve_logger_services() -> None:
    """Register the node's ``~get_loggers`` and ``~set_logger_level`` in the background, now (after
    ``init_node(logger_services_later=True)``); returns at once.

    rospy registers them as the last step of its ``init_node``; two calls to the master (with the
    services' classes built) are 2-4 ms that a script's first publish need not wait for. Here they are
    registered a few milliseconds after ``init_node`` returns, on the engine thread, over the node's own
    connection to the master. If the master does not take them (it went away), the node's master watch
    registers them with the next master that answers.
    """
    engine, node = _require()

    def start() -> None:
        task = node.loop.create_task(_serve_loggers(node))
        _background.add(task)  # the loop keeps only a weak reference
        task.add_done_callback(_background.discard)

    engine.call_soon(start)


_background: set[asyncio.Task[None]] = set()


async def _serve_loggers(node: _node.AsyncNode) -> None:
    try:
        await node.logging.serve_loggers()
    except Exception as exc:  # the master went away: its successor gets them (the watch's hooks do only what is left)
        if node.is_shutdown or node.master_watch is None:
            return
        node.log.debug("logger services not registered yet (%s); the next master that answers gets them", exc)
        node.master_watch.on_connect.append(node.logging.serve_loggers)


def _start_sim_time(engine: Engine, node: _node.AsyncNode) -> None:
    """Follow ``/clock`` (the master's ``/use_sim_time`` is true): zero until the first message."""
    clock = _state.clock
    clock.set(Time(0, 0))
    node.log.clock = clock.now_ns

    def tick(msg: Any) -> None:
        clock.set(msg.clock)

    engine.run(node.subscribe(CLOCK_TOPIC, get_message_class("rosgraph_msgs/Clock"), tick, queue_size=1))


def _on_signal(signum: int, _frame: Any) -> None:
    """Ctrl-C or SIGTERM: begin the shutdown on the engine thread.

    A signal handler runs between two bytecodes of the main thread, which may at that moment hold the lock of
    the shutdown Event it sleeps on (``Rate.sleep``, ``spin``): threading.Event's lock is not reentrant, so
    setting the Event here could block the main thread for good. The handler only schedules; the engine thread
    sets the Event, wakes the sleepers and unregisters the node (an exit waits for that, see :func:`_atexit`).
    """
    _state.signalled = True  # seen by is_shutdown() at once, even if the engine thread were stuck
    engine, node = _state.engine, _state.node
    if engine is not None and node is not None:
        engine.call_soon(_begin_shutdown, node, "signal-interrupt" if signum == signal.SIGINT else "signal-terminate")


def _begin_shutdown(node: _node.AsyncNode, reason: str) -> None:
    """On the engine thread: say the node is shutting down and start its shutdown."""
    _state.shutdown.set()
    _state.clock.wake()
    if node.shutdown_reason is None:
        node.loop.create_task(node.shutdown(reason))


def _on_node_shutdown(reason: str) -> None:
    _state.reason = reason
    _state.shutdown.set()
    _state.clock.wake()
    for hook in list(_state.hooks):
        try:
            hook(reason) if _accepts_arg(hook) else hook()
        except Exception as exc:
            sys.stderr.write(f"error in shutdown hook: {exc}\n")


def _accepts_arg(fn: Callable[..., Any]) -> bool:
    try:
        import inspect
        return len(inspect.signature(fn).parameters) >= 1
    except (TypeError, ValueError):
        return False


def _atexit() -> None:
    if _state.node is not None and not _state.node.is_shutdown:
        signal_shutdown("atexit")
    _wait_shutdown_done()


def _wait_shutdown_done() -> None:
    """Block until a shutdown that has begun has unregistered everything."""
    engine, node = _state.engine, _state.node
    if engine is None or node is None or not node.is_shutdown or engine.on_engine_thread:
        return
    try:
        engine.run(node.wait_shutdown(), timeout=5)
    except Exception:
        pass


def signal_shutdown(reason: str) -> None:
    """Shut the node down: unregister everything, close connections."""
    engine, node = _state.engine, _state.node
    _state.shutdown.set()
    _state.clock.wake()
    if engine is None or node is None:
        return
    if engine.on_engine_thread:
        node.request_shutdown(reason)
        return
    try:
        engine.run(node.shutdown(reason), timeout=5)
    except Exception:
        pass


def on_shutdown(hook: Callable[..., Any]) -> None:
    """Call ``hook()`` (or ``hook(reason)``) when the node shuts down."""
    _state.hooks.append(hook)


def is_shutdown() -> bool:
    """True once the node has begun shutting down (or Ctrl-C has asked it to)."""
    return _state.signalled or _state.shutdown.is_set()


def ok() -> bool:
    """The opposite of is_shutdown(), as roscpp's ros::ok()."""
    return not is_shutdown()


def spin() -> None:
    """Block until the node shuts down (Ctrl-C, or the master's shutdown request)."""
    _require()
    try:
        while not _state.shutdown.wait(0.5) and not _state.signalled:
            pass
    except KeyboardInterrupt:
        signal_shutdown("keyboard interrupt")
    _wait_shutdown_done()


def get_name() -> str:
    """This node's global name."""
    return _require()[1].name


def get_namespace() -> str:
    """This node's namespace, with leading and trailing slash."""
    return _require()[1].namespace


def get_node_uri() -> str:
    """This node's slave API URI."""
    return _require()[1].uri


def get_master_uri() -> str:
    """The master URI this node uses."""
    return _require()[1].master_uri


def resolve_name(name: str) -> str:
    """Resolve a name in this node's namespace, applying remappings."""
    return _require()[1].resolve(name)


def myargv(argv: Sequence[str] | None = None) -> list[str]:
    """``argv`` (default sys.argv) without ROS arguments; keeps the program name."""
    argv = list(sys.argv if argv is None else argv)
    return argv[:1] + names.parse_argv(argv[1:]).args


# -- time ---------------------------------------------------------------------------
def get_rostime() -> Time:
    """The current ROS time: the wall clock, or under ``/use_sim_time`` the last ``/clock`` (zero before one)."""
    return _state.clock.now()


def get_time() -> float:
    """The current ROS time in float seconds."""
    return _state.clock.now().to_sec()


def is_wallclock() -> bool:
    """True unless this node follows simulated time from ``/clock``."""
    return _state.clock.is_wallclock


def sleep(duration: float | Duration) -> None:
    """Sleep *duration* seconds of ROS time; ROSInterruptException on shutdown.

    Under simulated time it waits for the first ``/clock`` message, then until
    ``/clock`` has advanced by *duration*; ROSTimeMovedBackwardsException when
    the clock jumps back meanwhile.
    """
    _timing.sleep(_state.clock, _state.shutdown, duration)


class Rate(_timing.Rate):
    """Keeps a loop at *hz* cycles a second of ROS time (like rospy.Rate / ros::Rate).

    With *reset*, a jump back of simulated time restarts the cycle instead of
    raising ROSTimeMovedBackwardsException.
    """

    def __init__(self, hz: float, reset: bool = False) -> None:
        super().__init__(hz, _state.clock, _state.shutdown, reset=reset)


TimerEvent = _timing.TimerEvent


class Timer(_timing.Timer):
    """Calls ``callback(TimerEvent)`` every *period* seconds of ROS time, on the timer's own thread.

    With *reset*, a jump back of simulated time restarts the period; without
    it the timer stops.
    """

    def __init__(self, period: float | Duration, callback: Callable[[Any], Any], oneshot: bool = False,
                 reset: bool = False) -> None:
        _require()
        super().__init__(period, callback, _state.clock, _state.shutdown, oneshot=oneshot, reset=reset)


# -- topics -----------------------------------------------------------------------------
def _unregister(engine: Engine, handle: _node.Publisher | _node.Subscriber) -> None:
    """Unregister a topic handle: wait from user threads, schedule from callbacks."""
    if engine.on_engine_thread:
        engine.loop.create_task(handle.unregister())
    else:
        engine.run(handle.unregister())


class Publisher:
    """Publish messages on a topic (rospy.Publisher)."""

    def __init__(self, name: str, data_class: Any, queue_size: int | None = None, latch: bool = False,
                 tcp_nodelay: bool = False, topic_type: TopicType | None = None) -> None:
        engine, node = _require()
        self._engine = engine
        self._impl = engine.run(node.advertise(name, data_class, queue_size=queue_size, latch=latch,
                                               tcp_nodelay=tcp_nodelay, topic_type=topic_type))
        self.name = self._impl.name
        self.resolved_name = self._impl.name
        self.data_class = data_class
        self.type = (topic_type.type if topic_type else data_class._type)
        self._publication = self._impl.impl

    def publish(self, *args: Any, **kwargs: Any) -> None:
        """Publish a message, or one built from fields; never blocks on slow subscribers."""
        if len(args) == 1 and not kwargs and args[0].__class__ is self.data_class and not self._impl._closed:
            self._publication.publish(args[0])
        else:
            self._impl.publish(*args, **kwargs)

    def get_num_connections(self) -> int:
        """Connected subscribers."""
        return self._impl.get_num_connections()

    def subscriber_names(self) -> set[str]:
        """Node names of the connected subscribers."""
        return self._impl.subscriber_names()

    def unregister(self) -> None:
        """Stop publishing."""
        _unregister(self._engine, self._impl)


class Subscriber:
    """Receive messages of a topic in a callback (rospy.Subscriber)."""

    def __init__(self, name: str, data_class: Any, callback: Callable[..., Any] | None = None,
                 callback_args: Any = None, queue_size: int | None = None, buff_size: int = 65536,
                 tcp_nodelay: bool = False) -> None:
        engine, node = _require()
        self._engine = engine
        self._impl = engine.run(node.subscribe(name, data_class, callback, callback_args=callback_args,
                                               queue_size=queue_size, tcp_nodelay=tcp_nodelay))
        self.name = self._impl.name
        self.resolved_name = self._impl.name
        self.data_class = data_class

    def get_num_connections(self) -> int:
        """Connected publishers."""
        return self._impl.get_num_connections()

    def publisher_names(self) -> set[str]:
        """Node names of the connected publishers."""
        return self._impl.publisher_names()

    def unregister(self) -> None:
        """Stop receiving."""
        _unregister(self._engine, self._impl)


def wait_for_message(topic: str, topic_type: Any, timeout: float | None = None) -> Any:
    """Block until one message arrives on a topic and return it."""
    box: list[Any] = []
    got = threading.Event()

    def take(msg: Any) -> None:
        if not box:
            box.append(msg)
            got.set()

    sub = Subscriber(topic, topic_type, take)
    try:
        deadline = None if timeout is None else time.monotonic() + timeout
        while not got.wait(0.05):
            if _state.shutdown.is_set():
                raise ROSInterruptException("ROS shutdown request")
            if deadline is not None and time.monotonic() > deadline:
                raise ROSException(f"timeout exceeded while waiting for a message on topic {sub.resolved_name}")
        return box[0]
    finally:
        sub.unregister()


# -- services --------------------------------------------------------------------------
ErrorHandler = Callable[[BaseException, "type[BaseException]", BaseException, "TracebackType | None"], Any]
"""A Service's *error_handler*: ``(exception, type, value, traceback)``, as rospy calls it."""


def _reporting(handler: Callable[[Any], Any], service_class: Any, error_handler: ErrorHandler) -> Callable[[Any], Any]:
    """*handler*, handing any error but a ServiceException to *error_handler* (in the worker thread).

    The caller gets the error as always; *error_handler* replaces the error line the node would log.
    """
    def serve(request: Any) -> Any:
        try:
            return make_response(service_class, handler(request))
        except ServiceException:
            raise
        except Exception as exc:
            error_handler(exc, type(exc), exc, exc.__traceback__)
            raise ServiceException(f"error processing request: {exc}") from exc
    return serve


class Service:
    """Serve a service; ``handler(request)`` runs in a worker thread (rospy.Service)."""

    def __init__(self, name: str, service_class: Any, handler: Callable[[Any], Any],
                 error_handler: ErrorHandler | None = None) -> None:
        engine, node = _require()
        if error_handler is not None:
            handler = _reporting(handler, service_class, error_handler)
        self._engine, self._node = engine, node
        self._server = engine.run(node.advertise_service(name, service_class, handler, threaded=True))
        self.resolved_name = self._server.name

    def shutdown(self, reason: str = "") -> None:
        """Stop serving."""
        self._engine.run(self._node.unadvertise_service(self._server))


class DetachedCaller:
    """The minimum of a node a ServiceProxy needs (a caller id and the master), on a private loop."""

    def __init__(self, name: str, master_uri: str) -> None:
        self.name = name
        self.master_uri = master_uri

    async def lookup_service(self, service: str) -> str:
        """The ``rosrpc://`` URI of *service*; ServiceException when it is not registered."""
        async with XmlRpcClient(self.master_uri) as client:
            try:
                return str(ros_result(await client.call("lookupService", self.name, service)))
            except XmlRpcConnectionError as exc:
                raise ServiceException(unreachable_text(self.master_uri, str(exc))) from exc
            except RosApiError as exc:
                raise ServiceException(f"service [{service}] unavailable") from exc


class ServiceProxy:
    """Call a service like a function (rospy.ServiceProxy)."""

    def __init__(self, name: str, service_class: Any, persistent: bool = False,
                 headers: dict[str, str] | None = None) -> None:
        engine, node = _require()
        self._engine = engine
        self._node = node
        self._proxy = node.service_proxy(name, service_class, persistent=persistent, headers=headers)
        self.resolved_name = self._proxy.name
        self.service_class = service_class

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        """Call the service; ServiceException on failure."""
        return self.call(*args, **kwargs)

    def call(self, *args: Any, **kwargs: Any) -> Any:
        """Call the service; ServiceException on failure."""
        if self._engine.on_engine_thread:
            from rostui.core.node.services import ServiceProxy as AsyncProxy
            caller = DetachedCaller(self._node.name, self._node.master_uri)
            proxy = AsyncProxy(caller, self.resolved_name, self.service_class)  # type: ignore[arg-type]
            return self._engine.run_detached(lambda: proxy.call(*args, **kwargs))
        return self._engine.run(self._proxy.call(*args, **kwargs))

    def wait_for_service(self, timeout: float | None = None) -> None:
        """Wait until the service is available."""
        wait_for_service(self.resolved_name, timeout)

    def close(self) -> None:
        """Close a persistent connection."""
        if not self._engine.on_engine_thread:
            self._engine.run(self._proxy.close())


def wait_for_service(service: str, timeout: float | None = None) -> None:
    """Block until a service is registered and reachable; ROSException on timeout."""
    engine, node = _require()
    try:
        if engine.on_engine_thread:
            raise ROSException("wait_for_service() cannot be called from a subscriber callback")
        engine.run(node.wait_for_service(service, timeout))
    except TimeoutError as exc:
        raise ROSException(str(exc)) from None
    except _node.MasterError:
        if node.is_shutdown:
            raise ROSInterruptException("shutdown while waiting for a service") from None
        raise


def probe_service_header(service: str, timeout: float = 5.0) -> dict[str, str]:
    """The header a service server sends (its type and md5sum)."""
    engine, node = _require()
    resolved = node.resolve(service)

    async def probe() -> dict[str, str]:
        uri = await node.lookup_service(resolved)
        return await probe_service(uri, resolved, node.name, timeout)
    return engine.run(probe())


# -- parameters --------------------------------------------------------------------------
def _param_call(method: str, *args: Any) -> Any:
    _, node = _require()
    try:
        return ros_result(call_sync(node.master_uri, method, node.name, *args))
    except XmlRpcConnectionError as exc:
        raise ROSException(unreachable_text(node.master_uri, str(exc))) from exc


_MISSING: Any = object()


def get_param(name: str, default: Any = _MISSING) -> Any:
    """A parameter's value; KeyError if unset and no default."""
    key = resolve_name(name)
    try:
        return _param_call("getParam", key)
    except RosApiError:
        if default is _MISSING:
            raise KeyError(key) from None
        return default


def get_param_cached(name: str, default: Any = _MISSING) -> Any:
    """A parameter's value, subscribed once and then read from the cache."""
    engine, node = _require()
    if engine.on_engine_thread:
        return get_param(name, default)
    try:
        return engine.run(node.get_param_cached(name, ... if default is _MISSING else default))
    except _node.MasterError as exc:
        raise ROSException(str(exc)) from None


def set_param(name: str, value: Any) -> None:
    """Set a parameter (a dict sets a whole namespace)."""
    _param_call("setParam", resolve_name(name), value)


def has_param(name: str) -> bool:
    """True when the parameter exists."""
    return bool(_param_call("hasParam", resolve_name(name)))


def delete_param(name: str) -> None:
    """Delete a parameter; KeyError if it does not exist."""
    key = resolve_name(name)
    try:
        _param_call("deleteParam", key)
    except RosApiError:
        raise KeyError(key) from None


def search_param(name: str) -> str | None:
    """The closest parameter of that name up this node's namespace, or None."""
    try:
        return _param_call("searchParam", name) or None
    except RosApiError:
        return None


def get_param_names() -> list[str]:
    """Every parameter name on the server."""
    return list(_param_call("getParamNames"))


# -- logging ----------------------------------------------------------------------------------
_console_only = NodeLog("", package_logger(None), LoggerTree(), Console())


def use_console(console: Console, before_init: Console | None = None) -> None:
    """Write this process's log lines with *console* (rospy's look, for one); before ``init_node`` with
    *before_init* if given, else with *console* too."""
    _state.console = console
    _console_only.console = console if before_init is None else before_init
    if _state.node is not None:
        _state.node.log.console = console


def _log() -> NodeLog:
    """The node's log, or a console-only one before init_node()."""
    return _state.node.log if _state.node is not None else _console_only


def logdebug(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at DEBUG (formatted only when DEBUG is enabled)."""
    _log().debug(msg, *args, logger=logger, stacklevel=2)


def loginfo(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at INFO: console, /rosout and the node's log file."""
    _log().info(msg, *args, logger=logger, stacklevel=2)


def logwarn(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at WARN."""
    _log().warn(msg, *args, logger=logger, stacklevel=2)


def logerr(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at ERROR."""
    _log().error(msg, *args, logger=logger, stacklevel=2)


def logfatal(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at FATAL."""
    _log().fatal(msg, *args, logger=logger, stacklevel=2)


def logdebug_once(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at DEBUG the first time this line runs, never again."""
    _log().log_once(1, msg, *args, logger=logger, stacklevel=2)


def loginfo_once(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at INFO the first time this line runs."""
    _log().log_once(2, msg, *args, logger=logger, stacklevel=2)


def logwarn_once(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at WARN the first time this line runs."""
    _log().log_once(4, msg, *args, logger=logger, stacklevel=2)


def logerr_once(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at ERROR the first time this line runs."""
    _log().log_once(8, msg, *args, logger=logger, stacklevel=2)


def logfatal_once(msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at FATAL the first time this line runs."""
    _log().log_once(16, msg, *args, logger=logger, stacklevel=2)


def logdebug_throttle(period: float, msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at DEBUG at most once per ``period`` seconds from this line."""
    _log().log_throttle(period, 1, msg, *args, logger=logger, stacklevel=2)


def loginfo_throttle(period: float, msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at INFO at most once per ``period`` seconds from this line."""
    _log().log_throttle(period, 2, msg, *args, logger=logger, stacklevel=2)


def logwarn_throttle(period: float, msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at WARN at most once per ``period`` seconds from this line."""
    _log().log_throttle(period, 4, msg, *args, logger=logger, stacklevel=2)


def logerr_throttle(period: float, msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at ERROR at most once per ``period`` seconds from this line."""
    _log().log_throttle(period, 8, msg, *args, logger=logger, stacklevel=2)


def logfatal_throttle(period: float, msg: Any, *args: Any, logger: str | None = None) -> None:
    """Log at FATAL at most once per ``period`` seconds from this line."""
    _log().log_throttle(period, 16, msg, *args, logger=logger, stacklevel=2)


def get_loggers(node_name: str) -> list[tuple[str, str]]:
    """``(logger, level)`` pairs of any node (rostui, roscpp or rospy) via its ``get_loggers`` service."""
    srv = get_service_class("roscpp/GetLoggers")
    proxy = ServiceProxy(_join(node_name, "get_loggers"), srv)
    return [(item.name, item.level) for item in proxy().loggers]


def set_logger_level(node_name: str, logger: str, level: str) -> None:
    """Set a logger's level on any node via its ``set_logger_level`` service; ServiceException on failure."""
    srv = get_service_class("roscpp/SetLoggerLevel")
    ServiceProxy(_join(node_name, "set_logger_level"), srv)(logger=logger, level=level)


def _join(node_name: str, service: str) -> str:
    return node_name.rstrip("/") + "/" + service
