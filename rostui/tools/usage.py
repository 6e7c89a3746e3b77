"""CPU, memory, threads and connections of processes (a launch's nodes, `rostui top`), measured with psutil between
two samples."""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from typing import Iterable

import psutil


def children_map() -> dict[int, list[int]]:
    """Every process's children, from one pass over the process table (cheaper than asking per node)."""
    children: dict[int, list[int]] = defaultdict(list)
    for process in psutil.process_iter(["ppid"]):
        ppid = process.info.get("ppid")
        if ppid is not None:
            children[ppid].append(process.pid)
    return children


def tree_of(pid: int, children: dict[int, list[int]]) -> list[int]:
    """``pid`` and all its descendants according to ``children``."""
    tree = [pid]
    index = 0
    while index < len(tree):
        tree.extend(children.get(tree[index], ()))
        index += 1
    return tree


@dataclass(frozen=True)
class Usage:
    """What a node's processes use: CPU in percent of one core since the last sample, resident memory in bytes."""

    cpu_percent: float
    rss_bytes: int


@dataclass(frozen=True)
class ProcessSample:
    """One process now: CPU in percent of one core since the previous sample, resident memory in bytes, threads,
    open TCP connections and command line; None where the system does not tell this user."""

    cpu_percent: float
    rss_bytes: int
    threads: int
    connections: int | None
    command: str | None


def _tcp_connections(handle: psutil.Process) -> int:
    method = getattr(handle, "net_connections", None) or handle.connections  # psutil < 6 has only the old name
    return len(method(kind="tcp"))


class UsageSampler:
    """Measures groups of pids; keeps one psutil handle per pid so CPU is the share since the previous sample.

    The first sample of a pid reads 0 % CPU (there is nothing to compare with yet).
    """

    def __init__(self) -> None:
        """No pid seen yet."""
        self._handles: dict[int, psutil.Process] = {}

    def measure(self, pids: Iterable[int]) -> Usage | None:
        """The summed usage of ``pids`` (None when none of them is alive; zombies count as dead)."""
        cpu = 0.0
        rss = 0
        alive = False
        for pid in pids:
            handle = self._handle(pid)
            if handle is None:
                continue
            try:
                with handle.oneshot():
                    if handle.status() == psutil.STATUS_ZOMBIE:
                        continue
                    cpu += handle.cpu_percent(None)
                    rss += handle.memory_info().rss
            except psutil.Error:
                self._handles.pop(pid, None)
                continue
            alive = True
        return Usage(cpu, rss) if alive else None

    def sample(self, pid: int) -> ProcessSample | None:
        """What process ``pid`` uses now (None when it is gone or a zombie)."""
        handle = self._handle(pid)
        if handle is None:
            return None
        try:
            with handle.oneshot():
                if handle.status() == psutil.STATUS_ZOMBIE:
                    return None
                cpu, rss, threads = handle.cpu_percent(None), handle.memory_info().rss, handle.num_threads()
                try:
                    command: str | None = " ".join(handle.cmdline())
                except psutil.AccessDenied:
                    command = None
            try:
                connections: int | None = _tcp_connections(handle)
            except psutil.AccessDenied:
                connections = None
        except psutil.Error:
            self._handles.pop(pid, None)
            return None
        return ProcessSample(cpu, rss, threads, connections, command)

    def forget_dead(self) -> None:
        """Drop the handles of processes that have ended."""
        for pid, handle in list(self._handles.items()):
            if not handle.is_running():
                del self._handles[pid]

    def _handle(self, pid: int) -> psutil.Process | None:
        handle = self._handles.get(pid)
        if handle is not None and handle.is_running():
            return handle
        try:
            handle = psutil.Process(pid)
            handle.cpu_percent(None)
        except psutil.Error:
            self._handles.pop(pid, None)
            return None
        self._handles[pid] = handle
        return handle
