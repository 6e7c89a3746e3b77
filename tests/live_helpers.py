"""Helpers for tests that run ROS programs as real processes and watch them from the test.

``Watcher`` is an in-process node on its own engine thread that records topics,
publishes, calls services and reads parameters; ``Program`` is a program
started with ``rostui run PKG EXE`` whose output goes to a file, so that a
chatty program never blocks on a full pipe.
"""

from __future__ import annotations

import re
import subprocess
import threading
import xmlrpc.client
from pathlib import Path
from typing import Any, Callable, Sequence

from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node import AsyncNode
from rostui.core.node.engine import Engine

from conftest import REPO, rostui_cmd, stop_process, wait_until  # noqa: F401  (re-exported)

DEADLINE = 30.0
"""Seconds a test waits for a condition before it fails (generous: CI machines are slow)."""


def wait_for_service(env: dict[str, str], service: str, timeout: float = DEADLINE) -> None:
    """Wait until the master at ``env``'s ROS_MASTER_URI knows a provider of ``service``."""
    master = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"])
    wait_until(lambda: master.lookupService("/test", service)[0] == 1, f"{service} registered", timeout)




class Recording:
    """Messages received on one topic, in arrival order (thread-safe)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._messages: list[Any] = []
        self.subscriber: Any = None

    def add(self, msg: Any) -> None:
        """Store one message (the subscriber callback)."""
        with self._lock:
            self._messages.append(msg)

    @property
    def messages(self) -> list[Any]:
        """A copy of what arrived so far."""
        with self._lock:
            return list(self._messages)

    def wait_for_count(self, count: int, what: str = "", timeout: float = DEADLINE) -> list[Any]:
        """Wait until at least ``count`` messages arrived; return them."""
        wait_until(lambda: len(self.messages) >= count, what or f"{count} messages", timeout)
        return self.messages

    def wait_for(self, predicate: Callable[[Any], bool], what: str, timeout: float = DEADLINE) -> Any:
        """Wait for a message satisfying ``predicate``; return the first one."""
        found: list[Any] = []

        def check() -> bool:
            found[:] = [m for m in self.messages if predicate(m)][:1]
            return bool(found)
        wait_until(check, what, timeout)
        return found[0]

    def wait_connected(self, timeout: float = DEADLINE) -> None:
        """Wait until at least one publisher is connected."""
        wait_until(lambda: self.subscriber.get_num_connections() > 0, "a publisher to connect", timeout)


class Watcher:
    """A node inside the test process that observes and pokes a live ROS graph."""

    def __init__(self, name: str = "test_watcher") -> None:
        self.engine = Engine()
        self.node: AsyncNode = self.engine.run(AsyncNode(name).start(), timeout=DEADLINE)

    def record(self, topic: str, type_name: str) -> Recording:
        """Subscribe to ``topic`` and keep every message."""
        recording = Recording()
        recording.subscriber = self.engine.run(
            self.node.subscribe(topic, get_message_class(type_name), recording.add), timeout=DEADLINE)
        return recording

    def publisher(self, topic: str, type_name: str) -> Any:
        """A publisher handle (its ``publish`` may be called from any thread)."""
        return self.engine.run(self.node.advertise(topic, get_message_class(type_name), queue_size=10),
                               timeout=DEADLINE)

    def call(self, service: str, type_name: str, **fields: Any) -> Any:
        """Call a service once it is available; returns the response."""
        srv = get_service_class(type_name)
        self.engine.run(self.node.wait_for_service(service, DEADLINE), timeout=DEADLINE + 5)
        return self.engine.run(self.node.service_proxy(service, srv).call(**fields), timeout=DEADLINE)

    def get_param(self, name: str, default: Any = None) -> Any:
        """A parameter's value, or ``default``."""
        return self.engine.run(self.node.get_param(name, default), timeout=DEADLINE)

    def lookup_node(self, name: str) -> bool:
        """True when the master knows a node of that name."""
        try:
            self.engine.run(self.node.master_call("lookupNode", name), timeout=DEADLINE)
        except Exception:
            return False
        return True

    def connected_subscribers(self, node: str, topic: str) -> set[str]:
        """The subscribers ``node``'s publisher on ``topic`` is connected to (its slave API's getBusInfo)."""
        try:
            uri = self.engine.run(self.node.master_call("lookupNode", node), timeout=DEADLINE)
            code, _, info = xmlrpc.client.ServerProxy(uri).getBusInfo("/test_watcher")
        except Exception:
            return set()
        return {row[1] for row in info if row[2] == "o" and row[4] == topic} if code == 1 else set()

    def close(self) -> None:
        """Unregister the node and stop its engine."""
        try:
            self.engine.run(self.node.shutdown("test done"), timeout=10)
        finally:
            self.engine.stop()


class Program:
    """A program started with ``rostui run``; stdout and stderr go to files."""

    def __init__(self, env: dict[str, str], tmp: Path, package: str, executable: str, *args: str,
                 label: str | None = None) -> None:
        label = label or executable
        self.stdout_path = tmp / f"{label}.out"
        self.stderr_path = tmp / f"{label}.err"
        with self.stdout_path.open("w") as out, self.stderr_path.open("w") as err:
            self.proc = subprocess.Popen(rostui_cmd("run", package, executable, *args), env=env, cwd=REPO,
                                         stdin=subprocess.DEVNULL, stdout=out, stderr=err)

    @property
    def stdout(self) -> str:
        """Everything the program wrote to stdout so far."""
        return self.stdout_path.read_text(errors="replace")

    @property
    def stderr(self) -> str:
        """Everything the program wrote to stderr so far."""
        return self.stderr_path.read_text(errors="replace")

    @property
    def output(self) -> str:
        """stdout followed by stderr."""
        return self.stdout + self.stderr

    def wait_for_output(self, pattern: str, timeout: float = DEADLINE) -> re.Match[str]:
        """Wait until stdout or stderr matches the regular expression; return the match."""
        found: list[re.Match[str]] = []

        def check() -> bool:
            match = re.search(pattern, self.output, re.MULTILINE)
            if match:
                found.append(match)
                return True
            if self.proc.poll() is not None:
                raise AssertionError(f"program exited with {self.proc.returncode} before printing "
                                     f"{pattern!r}:\n{self.output}")
            return False
        wait_until(check, f"output matching {pattern!r}", timeout)
        return found[0]

    def wait_exit(self, timeout: float = DEADLINE) -> int:
        """Wait for the program to end on its own; its exit status."""
        return self.proc.wait(timeout=timeout)

    def stop(self) -> None:
        """Ctrl-C the program (SIGKILL if it does not stop)."""
        stop_process(self.proc)


def start_headless_sim(env: dict[str, str], tmp: Path, *args: str) -> Program:
    """``rostui run turtlesim turtlesim_node --headless`` (the caller waits for what it needs)."""
    return Program(env, tmp, "turtlesim", "turtlesim_node", "--headless", *args, label="turtlesim")


def log_lines(text: str, level: str) -> list[str]:
    """The messages of console log lines at ``level`` (``INFO``, ``WARN``...), in order."""
    tag = re.escape(f"[{level:>5}]")
    return re.findall(rf"^{tag} \[[\d.]+\]: (.*)$", text, re.MULTILINE)


def log_stamps(text: str, level: str, message: str) -> list[float]:
    """The time stamps of console log lines at ``level`` with exactly ``message``."""
    tag = re.escape(f"[{level:>5}]")
    return [float(s) for s in re.findall(rf"^{tag} \[([\d.]+)\]: {re.escape(message)}$", text, re.MULTILINE)]


def stop_all(items: Sequence[Program | Watcher]) -> None:
    """Stop programs and close watchers, ignoring ones already gone."""
    for item in reversed(items):
        if isinstance(item, Program):
            item.stop()
        else:
            item.close()
