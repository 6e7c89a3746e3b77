"""AsyncNode: one ROS node on an asyncio loop (the engine behind both API faces).

The node serves the slave XML-RPC API and one TCPROS server for topics and
services, registers with the master, and keeps every publication,
subscription and service it owns so that shutdown can unregister them all.

It also outlives its master, which ROS 1 nodes do not: its
:class:`~rostui.core.node.master_watch.MasterWatch` asks the master about every
second who it is, and when another master answers (either changed, or it did
not answer and now does) the node registers again everything it has:
publishers, subscribers, services and parameter subscriptions.  A restarted
master then knows every rostui node, and sends publisherUpdate as usual.  The
check runs beside the node's traffic, on its own connection; nothing is added
per message.
"""

from __future__ import annotations

import asyncio
import itertools
import logging
import threading
from typing import Any, Callable, Sequence
from urllib.parse import urlparse

from rostui.core import names
from rostui.core.log import Console, LoggerTree, NodeLog, package_logger
from rostui.core.memory import TUNE_DELAY, tune_allocator
from rostui.core.network import Addressing, connect_host, master_uri_from_env, resolve_addressing
from rostui.core.startup_gc import start_up_done
from rostui.core.node.anymsg import AnyMsg
from rostui.core.node.busypoll import BusyPoll, busy_poll_for
from rostui.core.node.logging_link import NodeLogging
from rostui.core.master_errors import MasterError as MasterError
from rostui.core.master_errors import MasterRefusedError as MasterRefusedError
from rostui.core.master_errors import MasterUnreachableError as MasterUnreachableError
from rostui.core.node.master_watch import CHECK_PERIOD, MasterWatch
from rostui.core.node.header_check import HeaderCheck
from rostui.core.node.params import ParamCache
from rostui.core.node.services import ServiceException, ServiceProxy, ServiceServer, probe_header
from rostui.core.tcpros import encode_header
from rostui.core.node.slave import SlaveApi
from rostui.core.node.topics import Publication, Subscription, TopicType
from rostui.core.node.transport import InboundConnection, InboundHandler
from rostui.core.xmlrpc import RosApiError, XmlRpcClient, XmlRpcConnectionError, XmlRpcServer, ros_result

log = logging.getLogger("rostui.node")

_LOCAL_NODES: dict[str, "AsyncNode"] = {}


class Publisher:
    """A handle to publish on a topic; several handles may share a Publication."""

    def __init__(self, node: "AsyncNode", publication: Publication, msg_class: Any) -> None:
        self.node = node
        self.impl = publication
        self.msg_class = msg_class
        self.name = publication.topic
        self.resolved_name = publication.topic
        self._closed = False

    def publish(self, *args: Any, **kwargs: Any) -> None:
        """Publish a message, or build one from positional/keyword fields."""
        if self._closed:
            raise RuntimeError(f"publish() to an unregistered topic [{self.name}]")
        if len(args) == 1 and not kwargs and (isinstance(args[0], self.msg_class) or isinstance(args[0], AnyMsg)):
            msg = args[0]
        else:
            msg = self.msg_class(*args, **kwargs)
        self.impl.publish(msg)

    def get_num_connections(self) -> int:
        """How many subscribers are connected."""
        return self.impl.num_subscribers

    def subscriber_names(self) -> set[str]:
        """Node names of the connected subscribers."""
        return self.impl.subscriber_names()

    async def unregister(self) -> None:
        """Stop publishing; the last handle unregisters the topic."""
        if not self._closed:
            self._closed = True
            await self.node.release_publication(self.impl)


class Subscriber:
    """A handle to a subscription with one callback."""

    def __init__(self, node: "AsyncNode", subscription: Subscription, callback: Callable[..., Any] | None,
                 callback_args: Any) -> None:
        self.node = node
        self.impl = subscription
        self.callback = callback
        self.callback_args = callback_args
        self.name = subscription.topic
        self.resolved_name = subscription.topic
        self._closed = False

    def get_num_connections(self) -> int:
        """How many publishers are connected."""
        return sum(1 for c in self.impl.connections.values() if c is not None) + len(self.impl.local_pubs)

    def publisher_names(self) -> set[str]:
        """Node names of the connected publishers."""
        return self.impl.publisher_names()

    async def unregister(self) -> None:
        """Stop receiving; the last handle unregisters the topic."""
        if not self._closed:
            self._closed = True
            if self.callback is not None:
                self.impl.remove_callback(self.callback, self.callback_args)
            await self.node.release_subscription(self.impl)


class AsyncNode:
    """A ROS node driven by the running asyncio loop.

    ``argv`` is the node's command line without the program name; ROS
    arguments in it (``a:=b``, ``__name:=``, ``__ns:=``, ``_param:=``, ...) are
    applied, the rest are left in ``self.argv``.  With ``busy_poll`` the loop
    spins briefly between densely arriving messages instead of sleeping
    (:mod:`rostui.core.node.busypoll`); the sync API turns it on.  With
    ``watch_master`` (the default) the node registers everything again when
    a new master answers at its URI (see the module's docstring), checking
    every ``master_check_period`` seconds; :attr:`master_watch` tells where
    the node stands with its master.
    """

    def __init__(self, name: str, *, argv: Sequence[str] | None = None, anonymous: bool = False,
                 master_uri: str | None = None, package: str | None = None, busy_poll: bool = False,
                 watch_master: bool = True, master_check_period: float = CHECK_PERIOD,
                 lenient_name: bool = False) -> None:
        args = names.parse_argv(list(argv or []))
        self.args = args
        self.argv = list(args.args)
        self.namespace = names.node_namespace(args)
        self.name = names.node_global_name(name, args, anonymous=anonymous, lenient=lenient_name)
        self.remappings = names.resolve_remappings(args.remaps, self.namespace, self.name)
        self.master_uri = master_uri_from_env(args.master or master_uri)
        self.addressing: Addressing = resolve_addressing(self.master_uri, args.ip, args.hostname)
        self.publications: dict[str, Publication] = {}
        self.subscriptions: dict[str, Subscription] = {}
        self.services: dict[str, ServiceServer] = {}
        self.params = ParamCache()
        self.log = NodeLog(self.name, package_logger(package), LoggerTree(), Console())
        self.logging = NodeLogging(self)
        self.uri = ""
        self.tcpros_port = 0
        self.loop: asyncio.AbstractEventLoop = None  # type: ignore[assignment]
        self.loop_thread_id = -1
        self.busy_poll: BusyPoll | None = None
        self._wants_busy_poll = busy_poll
        self.shutdown_reason: str | None = None
        self.shutdown_hooks: list[Callable[[str], Any]] = []
        self._master: XmlRpcClient | None = None
        self._ids = itertools.count(1)
        self._xmlrpc: XmlRpcServer | None = None
        self._tcpros: asyncio.AbstractServer | None = None
        self._done: asyncio.Event | None = None
        self._clients: dict[str, XmlRpcClient] = {}
        #: The judge of the master (None with ``watch_master=False``: a node that manages its master itself).
        self.master_watch = MasterWatch(self, period=master_check_period) if watch_master else None

    # -- lifecycle --------------------------------------------------------------
    async def start(self, *, announce: bool = True, publish_rosout: bool = True) -> "AsyncNode":
        """Open the slave API and TCPROS servers; set ``_param:=`` parameters.

        With ``announce`` (the default) the node also registers its logging
        with the master at once (see :meth:`announce`); pass False to do that
        later, e.g. after waiting for the master.
        """
        self.logging.attach()
        self.loop = asyncio.get_running_loop()
        self.loop.call_later(TUNE_DELAY, tune_allocator)  # after the start (ctypes), before big messages stream
        self.loop_thread_id = threading.get_ident()
        self.busy_poll = busy_poll_for(self.loop) if self._wants_busy_poll else None
        self._done = asyncio.Event()
        self._master = XmlRpcClient(self.master_uri)
        bind, host = self.addressing.bind_host, self.addressing.advertise_host
        self._tcpros = await self.loop.create_server(lambda: InboundConnection(self), bind, 0)
        self.tcpros_port = self._tcpros.sockets[0].getsockname()[1]
        self._xmlrpc = XmlRpcServer(SlaveApi(self), bind, 0, advertise_host=host)
        await self._xmlrpc.start()
        self.uri = self._xmlrpc.uri
        _LOCAL_NODES[self.uri] = self
        if self.master_watch is not None:
            self.master_watch.start()
        for key, value in self.args.params.items():
            await self.set_param("~" + key, value)
        if announce:
            try:
                await self.announce(publish_rosout=publish_rosout)
            except BaseException:
                await self.shutdown("could not register with the master")
                raise
        start_up_done()
        return self

    async def announce(self, *, publish_rosout: bool = True, logger_services: bool = True) -> None:
        """Publish log records on /rosout, serve the logger-level services, open the log file.

        Without *logger_services* the services wait for ``self.logging.serve_loggers()``.
        """
        await self.logging.announce(publish_rosout=publish_rosout, services=logger_services)

    async def wait_for_master(self, timeout: float | None = None, on_wait: Callable[[], None] | None = None) -> None:
        """Wait until the master answers; ``on_wait`` is called once if it does not at first."""
        deadline = None if timeout is None else self.loop.time() + timeout
        warned = False
        while True:
            try:
                await self.master_call("getPid")
                return
            except MasterError:
                if self.is_shutdown:
                    raise MasterUnreachableError(self.master_uri, "node shut down while waiting for it") from None
                if deadline is not None and self.loop.time() >= deadline:
                    raise
                if not warned and on_wait is not None:
                    on_wait()
                    warned = True
                await asyncio.sleep(0.2)

    @property
    def is_shutdown(self) -> bool:
        """True once shutdown began."""
        return self.shutdown_reason is not None

    def request_shutdown(self, reason: str) -> None:
        """Begin shutdown on a slave ``shutdown`` call, logging why, as roscpp does."""
        if self.shutdown_reason is None:
            self.log.warn("Shutdown request received. Reason given for shutdown: [%s]", reason)
            self.loop.create_task(self.shutdown(reason))

    async def wait_shutdown(self) -> str:
        """Wait until the node has shut down; return the reason."""
        assert self._done is not None
        await self._done.wait()
        return self.shutdown_reason or ""

    async def shutdown(self, reason: str = "shutdown") -> None:
        """Unregister everything, close all connections and servers."""
        if self.shutdown_reason is not None:
            if self._done is not None:
                await self._done.wait()
            return
        self.shutdown_reason = reason
        if self.master_watch is not None:
            await self.master_watch.stop()
        for hook in list(self.shutdown_hooks):
            try:
                hook(reason)
            except Exception:
                log.exception("error in shutdown hook")
        unregister = []
        for pub in self.publications.values():
            unregister.append(self._quiet_call("unregisterPublisher", pub.topic, self.uri))
        for sub in self.subscriptions.values():
            unregister.append(self._quiet_call("unregisterSubscriber", sub.topic, self.uri))
        for srv in self.services.values():
            unregister.append(self._quiet_call("unregisterService", srv.name, self.service_uri))
        for key in self.params.keys():
            unregister.append(self._quiet_call("unsubscribeParam", self.uri, key))
        if unregister:
            await asyncio.wait([asyncio.ensure_future(c) for c in unregister], timeout=2.0)
        for pub in self.publications.values():
            pub.close()
        for sub in self.subscriptions.values():
            sub.close()
        self.publications.clear()
        self.subscriptions.clear()
        self.services.clear()
        _LOCAL_NODES.pop(self.uri, None)
        if self._tcpros is not None:
            self._tcpros.close()
        if self._xmlrpc is not None:
            await self._xmlrpc.close()
        for client in [self._master, *self._clients.values()]:
            if client is not None:
                await client.close()
        self.logging.close()
        assert self._done is not None
        self._done.set()

    # -- a new master --------------------------------------------------------------
    @property
    def registrations_renewed(self) -> int:
        """How many times the node registered everything again with a new master."""
        return self.master_watch.renewals if self.master_watch is not None else 0

    async def check_master(self) -> bool:
        """Check who the master is now; register everything again if it is not the one the node knew.

        Returns True when the node registered again.  The node does this about every second by itself
        (:class:`~rostui.core.node.master_watch.MasterWatch`); call it to do it now.
        """
        assert self.master_watch is not None, "the node was made with watch_master=False"
        return await self.master_watch.check()

    def has_registrations(self) -> bool:
        """Whether the node has anything registered with the master (a topic, a service, a parameter)."""
        return bool(self.publications or self.subscriptions or self.services or self.params.keys())

    async def register_again(self) -> None:
        """Register with the master every publication, subscription, service and parameter subscription again.

        For a master that does not know the node (it restarted).  Each
        subscription connects to the publishers the master lists and keeps
        its live connections (their publishers register again by themselves,
        if they are rostui nodes); subscribed parameters take the master's
        values.
        """
        for topic, pub in list(self.publications.items()):
            if self.publications.get(topic) is pub and not self.is_shutdown:
                await self.master_call("registerPublisher", topic, pub.topic_type.type, self.uri)
        for topic, sub in list(self.subscriptions.items()):
            if self.subscriptions.get(topic) is sub and not self.is_shutdown:
                uris = await self.master_call("registerSubscriber", topic, sub.type_name, self.uri)
                sub.rejoin(list(uris))
        for name, srv in list(self.services.items()):
            if self.services.get(name) is srv and not self.is_shutdown:
                await self.master_call("registerService", name, self.service_uri, self.uri)
        for key in self.params.keys():
            if not self.is_shutdown:
                self.params.update(key, await self.master_call("subscribeParam", self.uri, key))

    async def _quiet_call(self, method: str, *args: Any) -> None:
        try:
            await asyncio.wait_for(self.master_call(method, *args), 2.0)
        except Exception as exc:
            log.debug("%s during shutdown failed: %s", method, exc)

    # -- names --------------------------------------------------------------------
    def resolve(self, name: str) -> str:
        """Resolve a name in this node's namespace, applying remappings."""
        return names.resolve_name(name, self.namespace, self.name, self.remappings)

    def next_connection_id(self) -> int:
        """A fresh id for getBusInfo / getBusStats."""
        return next(self._ids)

    @property
    def service_uri(self) -> str:
        """``rosrpc://host:port`` of this node's service endpoint."""
        return f"rosrpc://{self.addressing.advertise_host}:{self.tcpros_port}"

    # -- master -------------------------------------------------------------------
    @property
    def registers(self) -> bool:
        """False once shutdown has begun: what is asked for after that is not told to the master, whose
        unregistrations have gone already (rospy registers nothing once shut down, too)."""
        return self.shutdown_reason is None

    async def master_call(self, method: str, *args: Any) -> Any:
        """Call a Master API method with our caller id; unwrap the ROS result."""
        assert self._master is not None, "node not started"
        try:
            return ros_result(await self._master.call(method, self.name, *args))
        except XmlRpcConnectionError as exc:
            raise MasterUnreachableError(self.master_uri, str(exc)) from exc
        except RosApiError as exc:
            raise MasterRefusedError(f"master refused {method}: {exc}") from exc

    def _client(self, uri: str) -> XmlRpcClient:
        client = self._clients.get(uri)
        if client is None:
            client = self._clients[uri] = XmlRpcClient(uri, timeout=5.0)
        return client

    async def request_topic(self, uri: str, topic: str) -> tuple[str, int]:
        """Ask a publisher's slave API for a TCPROS endpoint."""
        client = self._client(uri)
        try:
            result = ros_result(await client.call("requestTopic", self.name, topic, [["TCPROS"]]))
        except Exception:
            self._clients.pop(uri, None)
            await client.close()
            raise
        if not result or result[0] != "TCPROS":
            raise ConnectionError(f"publisher {uri} offered no TCPROS endpoint for {topic}")
        return str(result[1]), int(result[2])

    def local_publication(self, uri: str, topic: str) -> Publication | None:
        """A publication of a node in this process, for direct delivery."""
        node = _LOCAL_NODES.get(uri)
        if node is None or node.loop is not self.loop:
            return None
        return node.publications.get(topic)

    async def lookup_service(self, name: str) -> str:
        """The rosrpc URI of a service, or ServiceException if none is registered."""
        try:
            return str(await self.master_call("lookupService", name))
        except MasterUnreachableError as exc:
            raise ServiceException(str(exc)) from exc
        except MasterRefusedError as exc:
            raise ServiceException(f"service [{name}] unavailable") from exc

    # -- TCPROS routing ------------------------------------------------------------
    def route_inbound(self, header: dict[str, str], conn: InboundConnection) -> InboundHandler | str:
        """Hand an accepted connection to the publication or service it names."""
        if "topic" in header:
            pub = self.publications.get(header["topic"])
            if pub is None:
                return f"received request for unknown topic [{header['topic']}]"
            return pub.accept(header, conn)
        if "service" in header:
            srv = self.services.get(header["service"])
            if srv is None:
                return f"received request for unknown service [{header['service']}]"
            return srv.accept(header, conn)
        return "header did not have required element: topic or service"

    # -- topics -----------------------------------------------------------------------
    async def advertise(self, topic: str, msg_class: Any, *, queue_size: int | None = None, latch: bool = False,
                        tcp_nodelay: bool = False, topic_type: TopicType | None = None) -> Publisher:
        """Publish on a topic; ``topic_type`` overrides the type (for AnyMsg relays)."""
        name = self.resolve(topic)
        ttype = topic_type or TopicType.of(msg_class)
        pub = self.publications.get(name)
        if pub is None:
            pub = Publication(self, name, ttype, queue_size=queue_size, latch=latch, tcp_nodelay=tcp_nodelay)
            self.publications[name] = pub
            try:
                if self.registers:
                    await self.master_call("registerPublisher", name, ttype.type, self.uri)
            except MasterError:
                self.publications.pop(name, None)
                raise
        elif pub.topic_type.md5sum != ttype.md5sum:
            raise ValueError(f"topic [{name}] is already published as {pub.topic_type.type}, not {ttype.type}")
        pub.handles += 1
        return Publisher(self, pub, msg_class)

    async def release_publication(self, pub: Publication) -> None:
        """Drop one handle; unregister when none are left."""
        pub.handles -= 1
        if pub.handles <= 0 and self.publications.get(pub.topic) is pub:
            del self.publications[pub.topic]
            pub.close()
            await self._quiet_call("unregisterPublisher", pub.topic, self.uri)

    async def subscribe(self, topic: str, msg_class: Any, callback: Callable[..., Any] | None = None, *,
                        callback_args: Any = None, queue_size: int | None = None,
                        tcp_nodelay: bool = False, check: HeaderCheck | None = None) -> Subscriber:
        """Subscribe to a topic; ``callback(msg)`` runs on the engine loop.

        With ``check`` (:mod:`rostui.core.node.header_check`) the callback hears only the publishers whose
        connection header it accepts; a publisher no callback of the topic accepts is refused.
        """
        name = self.resolve(topic)
        sub = self.subscriptions.get(name)
        created = sub is None
        if sub is None:
            sub = Subscription(self, name, msg_class, queue_size=queue_size, tcp_nodelay=tcp_nodelay)
            self.subscriptions[name] = sub
        elif sub.msg_class._md5sum != msg_class._md5sum:
            raise ValueError(f"topic [{name}] is already subscribed as {sub.type_name}, not {msg_class._type}")
        if callback is not None:
            sub.add_callback(callback, callback_args, check)
        sub.handles += 1
        if created and self.registers:
            try:
                uris = await self.master_call("registerSubscriber", name, msg_class._type, self.uri)
            except MasterError:
                self.subscriptions.pop(name, None)
                raise
            sub.update_publishers(list(uris))
        return Subscriber(self, sub, callback, callback_args)

    async def add_subscription(self, sub: Subscription, callback: Callable[..., Any] | None = None,
                               callback_args: Any = None) -> Subscriber:
        """Register a subscription built by the caller, e.g. of a Subscription subclass.

        ``sub`` must have been built for this node with its topic name
        already resolved (:meth:`resolve`), and the topic must not be
        subscribed in this node yet (ValueError otherwise).  ``callback``,
        when given, is added to ``sub`` as :meth:`subscribe` adds it.  The
        master is told, ``sub`` connects to the publishers, and the handle
        returned unregisters it like one from :meth:`subscribe`.
        """
        name = sub.topic
        if sub.node is not self:
            raise ValueError(f"the subscription to [{name}] belongs to another node")
        if name in self.subscriptions:
            raise ValueError(f"topic [{name}] is already subscribed in this node")
        if callback is not None:
            sub.add_callback(callback, callback_args)
        sub.handles += 1
        self.subscriptions[name] = sub
        if not self.registers:
            return Subscriber(self, sub, callback, callback_args)
        try:
            uris = await self.master_call("registerSubscriber", name, sub.type_name, self.uri)
        except Exception:
            self.subscriptions.pop(name, None)
            raise
        sub.update_publishers(list(uris))
        return Subscriber(self, sub, callback, callback_args)

    async def release_subscription(self, sub: Subscription) -> None:
        """Drop one handle; unregister when none are left."""
        sub.handles -= 1
        if sub.handles <= 0 and self.subscriptions.get(sub.topic) is sub:
            del self.subscriptions[sub.topic]
            sub.close()
            await self._quiet_call("unregisterSubscriber", sub.topic, self.uri)

    # -- services ----------------------------------------------------------------------
    async def advertise_service(self, name: str, srv_class: Any, handler: Callable[[Any], Any], *,
                                threaded: bool = False) -> ServiceServer:
        """Serve a service; ``threaded`` runs the handler in a worker thread."""
        resolved = self.resolve(name)
        if resolved in self.services:
            raise ValueError(f"service [{resolved}] is already registered in this node")
        server = ServiceServer(self, resolved, srv_class, handler, threaded=threaded)
        self.services[resolved] = server
        try:
            if self.registers:
                await self.master_call("registerService", resolved, self.service_uri, self.uri)
        except BaseException:  # refused, unreachable or cancelled (a caller's timeout): not half-kept, so a retry can
            self.services.pop(resolved, None)
            raise
        return server

    async def unadvertise_service(self, server: ServiceServer) -> None:
        """Stop serving a service."""
        if self.services.get(server.name) is server:
            del self.services[server.name]
            await self._quiet_call("unregisterService", server.name, self.service_uri)

    def service_proxy(self, name: str, srv_class: Any, *, persistent: bool = False,
                      headers: dict[str, str] | None = None) -> ServiceProxy:
        """A client for a service (resolved in this node's namespace)."""
        return ServiceProxy(self, self.resolve(name), srv_class, persistent=persistent, headers=headers)

    async def wait_for_service(self, name: str, timeout: float | None = None) -> None:
        """Wait until a service is registered and accepts connections."""
        resolved = self.resolve(name)
        deadline = None if timeout is None else self.loop.time() + timeout
        while True:
            try:
                uri = await self.lookup_service(resolved)
                parsed = urlparse(uri)
                _, writer = await asyncio.wait_for(
                    asyncio.open_connection(connect_host(parsed.hostname or ""), parsed.port), 1.0)
                writer.write(encode_header(probe_header(self.name, resolved)))
                writer.close()
                return
            except (ServiceException, OSError, asyncio.TimeoutError) as exc:
                if self.is_shutdown:
                    raise MasterUnreachableError(self.master_uri, f"node shut down while waiting for service {resolved}") \
                        from None
                if deadline is not None and self.loop.time() >= deadline:
                    raise TimeoutError(f"timeout exceeded while waiting for service {resolved}") from exc
            await asyncio.sleep(0.1)

    # -- parameters ----------------------------------------------------------------------
    async def get_param(self, name: str, default: Any = ...) -> Any:
        """A parameter's value; KeyError when unset and no default is given."""
        key = self.resolve(name)
        try:
            return await self.master_call("getParam", key)
        except MasterRefusedError:
            if default is ...:
                raise KeyError(key) from None
            return default

    async def get_param_cached(self, name: str, default: Any = ...) -> Any:
        """Like get_param, but subscribes once and answers from the cache after."""
        key = self.resolve(name)
        if not self.params.subscribed(key):
            value = await self.master_call("subscribeParam", self.uri, key)
            self.params.set(key, value)
        value = self.params.get(key)
        if value == {} and not await self.has_param(key):
            if default is ...:
                raise KeyError(key)
            return default
        return value

    async def set_param(self, name: str, value: Any) -> None:
        """Set a parameter (a dict sets a namespace)."""
        await self.master_call("setParam", self.resolve(name), value)

    async def has_param(self, name: str) -> bool:
        """True when the parameter exists."""
        return bool(await self.master_call("hasParam", self.resolve(name)))

    async def delete_param(self, name: str) -> None:
        """Delete a parameter; KeyError when it does not exist."""
        key = self.resolve(name)
        try:
            await self.master_call("deleteParam", key)
        except MasterRefusedError:
            raise KeyError(key) from None

    async def search_param(self, name: str) -> str | None:
        """The closest parameter name up the namespace tree, or None."""
        try:
            found = await self.master_call("searchParam", name)
        except MasterRefusedError:
            return None
        return found or None

    async def get_param_names(self) -> list[str]:
        """Every parameter name on the server."""
        return list(await self.master_call("getParamNames"))

