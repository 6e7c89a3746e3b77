"""Every node on the master with its process, as rqt_top shows them, and stopping one with escalating signals.

A node's pid comes from its own slave API (``getPid``), asked once per URI; a node whose URI names this host
(loopback, or an address of one of its interfaces) is measured with psutil: CPU since the last poll, resident
memory, threads and TCP connections. A node elsewhere is listed as remote with its pid, and nothing more can be
known or done from here. Master calls are few: the master is asked for its nodes once per poll, and a node's URI
only while it is new or its pid is unknown (a node that did not answer is asked again after 10 s).

Stopping a node sends SIGINT (what Ctrl-C in its terminal sends), then SIGTERM, then SIGKILL, each after a grace
period, and only after the node has said its pid again: a pid taken by another process since is never signalled.
"""

from __future__ import annotations

import asyncio
import os
import signal
import time
from dataclasses import dataclass
from typing import Any, Callable, Iterable
from urllib.parse import urlsplit

import psutil

from rostui.core.master_errors import MasterRefusedError, MasterUnreachableError
from rostui.models.calling_node import CallingNode
from rostui.core.xmlrpc import RosApiError, XmlRpcClient, XmlRpcError, ros_result
from rostui.tools.hosts import is_local_host, local_addresses
from rostui.tools.usage import ProcessSample, UsageSampler

__all__ = ["NodeRow", "TopSource", "SORTS", "sort_rows", "format_rows", "format_bytes", "CALL_TIMEOUT",
           "STOP_GRACE", "StopRefused", "table_lines"]

#: Seconds a master or node call may take.
CALL_TIMEOUT = 2.0
#: Seconds a node gets to end after each signal before the next one.
STOP_GRACE = 5.0
#: Node URIs asked at once.
PARALLEL_CALLS = 16
#: Seconds before a node that did not answer getPid is asked again.
RETRY_AFTER = 10.0

SORTS = ("cpu", "memory", "name")


@dataclass(frozen=True)
class NodeRow:
    """One node: its name, URI and host, whether it runs ``here``, its pid, its process's usage (nodes here), and
    why something is missing (``problem``)."""

    name: str
    uri: str | None
    host: str
    here: bool
    pid: int | None
    usage: ProcessSample | None
    problem: str = ""

    @property
    def where(self) -> str:
        """``here`` or ``remote (HOST)``."""
        return "here" if self.here else f"remote ({self.host or '?'})"


class StopRefused(Exception):
    """A node that cannot be stopped from here; the message says why."""


def _host_of(uri: str | None) -> str:
    try:
        return (urlsplit(uri).hostname or "") if uri else ""
    except ValueError:
        return ""


class TopSource(CallingNode):
    """Polls the master at ``master_uri`` for its nodes and measures those on this host.

    ``addresses`` are this host's (default: its interfaces'); ``own_pid`` is never signalled.
    """

    def __init__(self, master_uri: str, *, timeout: float = CALL_TIMEOUT, addresses: set[str] | None = None,
                 own_pid: int | None = None) -> None:
        super().__init__("rostui_top", master_uri, "rostui top done", quiet=True)
        self.timeout = timeout
        self._addresses = addresses
        self._here: dict[str, bool] = {}
        self._uris: dict[str, str | None] = {}
        self._pids: dict[str, int] = {}
        self._problems: dict[str, str] = {}
        self._retry_at: dict[str, float] = {}
        self.sampler = UsageSampler()
        self.own_pid = os.getpid() if own_pid is None else own_pid

    async def _master(self, method: str, *args: Any) -> Any:
        try:
            return await asyncio.wait_for(self.node.master_call(method, *args), self.timeout)
        except asyncio.TimeoutError:
            raise MasterUnreachableError(self.master_uri, f"no answer within {self.timeout:g} s") from None
        except OSError as exc:
            raise MasterUnreachableError(self.master_uri, str(exc)) from None

    async def poll(self) -> list[NodeRow]:
        """Every node the master lists now, in name order, measured where it runs here.

        :class:`~rostui.core.master_errors.MasterUnreachableError` when the master does not answer.
        """
        publishers, subscribers, services = await self._master("getSystemState")
        names = sorted({node for kind in (publishers, subscribers, services) for _name, nodes in kind
                        for node in nodes if isinstance(node, str)})
        for gone in (set(self._uris) | set(self._problems) | set(self._retry_at)) - set(names):
            for known in (self._uris, self._problems, self._retry_at):
                known.pop(gone, None)
        now = time.monotonic()
        unknown = [name for name in names if self._retry_at.get(name, 0.0) <= now
                   and (self._uris.get(name) is None or self._pids.get(str(self._uris[name])) is None)]
        limit = asyncio.Semaphore(PARALLEL_CALLS)
        await asyncio.gather(*(self._learn(name, limit) for name in unknown))
        self.sampler.forget_dead()
        return [self._row(name) for name in names]

    async def _learn(self, name: str, limit: asyncio.Semaphore) -> None:
        """The node's URI (from the master) and pid (from the node)."""
        async with limit:
            try:
                uri = str(await self._master("lookupNode", name))
            except MasterRefusedError:  # it went between the two calls
                self._problems[name] = "no longer registered"
                return
            self._uris[name] = uri
            try:
                self._pids[uri] = await self._ask_pid(uri)
                self._problems.pop(name, None)
            except (OSError, asyncio.TimeoutError, XmlRpcError, RosApiError, ValueError, TypeError) as exc:
                self._problems[name] = f"no answer to getPid ({type(exc).__name__})"
                self._retry_at[name] = time.monotonic() + RETRY_AFTER

    async def _ask_pid(self, uri: str) -> int:
        client = XmlRpcClient(uri, timeout=self.timeout + 1.0)
        try:
            return int(ros_result(await asyncio.wait_for(client.call("getPid", self.node.name), self.timeout)))
        finally:
            await client.close()

    def _is_here(self, host: str) -> bool:
        if host not in self._here:
            addresses = self._addresses if self._addresses is not None else local_addresses()
            self._here[host] = bool(host) and is_local_host(host, addresses)
        return self._here[host]

    def _row(self, name: str) -> NodeRow:
        uri = self._uris.get(name)
        host = _host_of(uri)
        here = self._is_here(host)
        pid = self._pids.get(uri) if uri else None
        problem = self._problems.get(name, "")
        usage = None
        if here and pid is not None:
            usage = self.sampler.sample(pid)
            if usage is None:
                problem = problem or f"no process {pid} here"
                self._pids.pop(str(uri), None)  # ask again next time: it may have restarted at the same URI
        return NodeRow(name, uri, host, here, pid, usage, problem)

    async def stop(self, row: NodeRow, *, grace: float = STOP_GRACE,
                   said: Callable[[str], None] = lambda _text: None) -> str:
        """Stop ``row``'s process: SIGINT, then SIGTERM, then SIGKILL, ``grace`` seconds apart; what it took.

        :class:`StopRefused` for a node that is not here, whose pid is unknown or is this process's, or that no
        longer says the same pid. ``said(text)`` hears each step.
        """
        if not row.here or row.pid is None or row.uri is None:
            raise StopRefused(f"{row.name} does not run on this host: stop it where it runs")
        if row.pid in (self.own_pid, 0, 1):
            raise StopRefused(f"{row.name} is pid {row.pid}: not stopped from here")
        try:
            now = await self._ask_pid(row.uri)
        except (OSError, asyncio.TimeoutError, XmlRpcError, RosApiError, ValueError, TypeError):
            raise StopRefused(f"{row.name} does not answer at {row.uri}: its pid {row.pid} is not trusted") from None
        if now != row.pid:
            raise StopRefused(f"{row.name} is pid {now} now, not {row.pid}: look again")
        try:
            process = psutil.Process(row.pid)
        except psutil.NoSuchProcess:
            return f"{row.name} had already ended"
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL):
            said(f"sending {sig.name} to {row.name} (pid {row.pid})…")
            try:
                process.send_signal(sig)
            except psutil.NoSuchProcess:
                return f"{row.name} ended"
            except psutil.AccessDenied:
                raise StopRefused(f"not allowed to signal {row.name} (pid {row.pid}, another user's)") from None
            if await asyncio.to_thread(_ended, process, grace):
                return f"{row.name} ended after {sig.name}"
        return f"{row.name} (pid {row.pid}) is still there after SIGKILL"


def _ended(process: psutil.Process, seconds: float) -> bool:
    try:
        process.wait(seconds)
    except psutil.TimeoutExpired:
        return False
    return True


def sort_rows(rows: Iterable[NodeRow], by: str) -> list[NodeRow]:
    """``rows`` by ``cpu`` or ``memory`` (the most first, remote nodes last) or ``name``."""
    rows = sorted(rows, key=lambda row: row.name)
    if by == "cpu":
        return sorted(rows, key=lambda row: -(row.usage.cpu_percent if row.usage else -1.0))
    if by == "memory":
        return sorted(rows, key=lambda row: -(row.usage.rss_bytes if row.usage else -1))
    return rows


def format_bytes(count: int) -> str:
    """``812K``, ``25.3M``, ``1.2G`` (binary units, as top prints them)."""
    if count < 1024 * 1024:
        return f"{count / 1024:.0f}K"
    if count < 1024 ** 3:
        return f"{count / 1024 ** 2:.1f}M"
    return f"{count / 1024 ** 3:.1f}G"


COLUMNS = ("NODE", "PID", "CPU%", "MEM", "THREADS", "CONNS", "WHERE")


def cells(row: NodeRow) -> tuple[str, ...]:
    """The row's cells in :data:`COLUMNS` order (``-`` where nothing is known)."""
    usage = row.usage
    return (row.name, str(row.pid) if row.pid is not None else "-",
            f"{usage.cpu_percent:.1f}" if usage else "-", format_bytes(usage.rss_bytes) if usage else "-",
            str(usage.threads) if usage else "-",
            str(usage.connections) if usage and usage.connections is not None else "-",
            row.where + (f": {row.problem}" if row.problem else ""))


def table_lines(rows: list[NodeRow]) -> list[str]:
    """The header and one line per row, each column as wide as its widest cell (names left, figures right)."""
    table = [COLUMNS, *(cells(row) for row in rows)]
    widths = [max(len(line[i]) for line in table) for i in range(len(COLUMNS) - 1)]
    return ["  ".join([*(cell.ljust(width) if i == 0 else cell.rjust(width)
                         for i, (cell, width) in enumerate(zip(line, widths))), line[-1]])
            for line in table]


def format_rows(rows: list[NodeRow]) -> str:
    """The rows as a table for a terminal or a script (``rostui top --once``)."""
    return "\n".join(table_lines(rows))
