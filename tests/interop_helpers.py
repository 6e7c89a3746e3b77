"""Helpers for the interop tests: peer processes whose output can be awaited.

Every process a test starts goes through the ``spawn`` fixture, which stops
them all (SIGINT, then SIGKILL) when the test ends, pass or fail.  Output is
read on a background thread, so a chatty peer never blocks on a full pipe and
a test can wait for the line a user would see.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import threading
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Callable, Iterator, Sequence

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_command, need_peer, shared_build, stop_process, wait_until  # noqa: F401  (re-exported)
from debian_peers import describe

PEERS = Path(__file__).resolve().parent / "peers"
EXAMPLES = REPO / "examples"
ROSCPP_SOURCE = REPO / "bench" / "roscpp_peer.cpp"

#: How long to wait for something that should happen; only a guard against hangs.
PATIENCE = 30.0


class Peer:
    """A running process with its combined stdout/stderr collected line by line."""

    def __init__(self, argv: Sequence[str], env: dict[str, str], label: str, cwd: Path = REPO) -> None:
        self.argv = list(argv)
        self.label = label
        self.lines: list[str] = []
        self._cond = threading.Condition()
        self.proc = subprocess.Popen(
            self.argv, env=env, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT, text=True, errors="replace", start_new_session=True,
        )
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            with self._cond:
                self.lines.append(line.rstrip("\n"))
                self._cond.notify_all()
        with self._cond:
            self._cond.notify_all()

    @property
    def output(self) -> str:
        """Everything the process printed so far."""
        with self._cond:
            return "\n".join(self.lines)

    def describe(self) -> str:
        """The command and its output, for assertion messages."""
        return f"--- {self.label}: {' '.join(self.argv)} (rc={self.proc.poll()})\n{self.output}"

    def wait_for(self, pattern: str, timeout: float = PATIENCE) -> re.Match[str]:
        """Wait until a line matches ``pattern`` (a regex searched in each line)."""
        regex = re.compile(pattern)
        deadline = time.monotonic() + timeout
        seen = 0
        with self._cond:
            while True:
                for line in self.lines[seen:]:
                    match = regex.search(line)
                    if match:
                        return match
                seen = len(self.lines)
                finished = self.proc.poll() is not None and not self._reader.is_alive()
                left = deadline - time.monotonic()
                if finished or left <= 0:
                    why = "exited" if finished else f"did not print it within {timeout}s"
                    raise AssertionError(f"{self.label} {why}; expected a line matching {pattern!r}\n"
                                         f"{self.describe()}")
                self._cond.wait(min(left, 0.2))

    def count(self, pattern: str) -> int:
        """How many lines so far match ``pattern``."""
        regex = re.compile(pattern)
        with self._cond:
            return sum(1 for line in self.lines if regex.search(line))

    def wait_exit(self, timeout: float = PATIENCE) -> int:
        """Wait for the process to end on its own; return its exit status."""
        try:
            rc = self.proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            raise AssertionError(f"{self.label} did not exit within {timeout}s\n{self.describe()}") from None
        self._reader.join(5)
        return rc

    def stop(self) -> None:
        """SIGINT, then SIGKILL."""
        stop_process(self.proc, timeout=10)
        self._reader.join(5)


Spawn = Callable[..., Peer]


@contextmanager
def peers(default_env: dict[str, str]) -> Iterator[Spawn]:
    """``spawn(argv, label=..., env=...)`` starts a Peer (in *default_env* unless told); all stop when this ends."""
    started: list[Peer] = []

    def start(argv: Sequence[str], label: str | None = None, env: dict[str, str] | None = None) -> Peer:
        peer = Peer(argv, env or default_env, label or Path(argv[1] if len(argv) > 1 else argv[0]).name)
        started.append(peer)
        return peer

    try:
        yield start
    finally:
        for peer in reversed(started):
            peer.stop()


@pytest.fixture
def spawn(ros_env: dict[str, str]) -> Iterator[Spawn]:
    """``spawn(argv, label=..., env=...)`` starts a Peer that is stopped when the test ends."""
    with peers(ros_env) as start:
        yield start


def rospy_peer(script: str, *args: str) -> list[str]:
    """argv of a rospy peer script in tests/peers, run by the system Python."""
    return [SYSTEM_PYTHON, str(PEERS / script), *args]


def rostui_peer(*args: str) -> list[str]:
    """argv of tests/peers/rostui_peer.py, run by the project's Python."""
    return [sys.executable, str(PEERS / "rostui_peer.py"), *args]


def example(script: str, *args: str) -> list[str]:
    """argv of an examples/ script, run by the project's Python."""
    return [sys.executable, str(EXAMPLES / script), *args]


def run_tool(argv: Sequence[str], env: dict[str, str], timeout: float = PATIENCE,
             check: bool = True) -> subprocess.CompletedProcess[str]:
    """Run a real ROS command-line tool to completion; fail loudly if it fails."""
    need_command(argv[0])
    proc = subprocess.run(list(argv), env=env, cwd=REPO, stdin=subprocess.DEVNULL, capture_output=True,
                          text=True, timeout=timeout)
    if check and proc.returncode != 0:
        raise AssertionError(f"{' '.join(argv)} exited {proc.returncode}\nstdout:\n{proc.stdout}\n"
                             f"stderr:\n{proc.stderr}")
    return proc




def graph_nodes(env: dict[str, str]) -> set[str] | str:
    """The nodes the master at ``env``'s ROS_MASTER_URI knows (what `rosnode list` lists), or why it did not say."""
    from rostui.core.xmlrpc import XmlRpcConnectionError, call_sync

    try:
        code, msg, state = call_sync(env["ROS_MASTER_URI"], "getSystemState", "/test")
    except (OSError, XmlRpcConnectionError) as exc:
        return f"no answer from the master: {exc}"
    if code != 1:
        return f"getSystemState: {msg}"
    return {node for kind in state for _, nodes in kind for node in nodes}


def wait_for_param(env: dict[str, str], name: str) -> None:
    """Wait until the master at ``env``'s ROS_MASTER_URI has the parameter ``name`` (roscore sets /run_id late)."""
    from rostui.core.xmlrpc import call_sync

    wait_until(lambda: call_sync(env["ROS_MASTER_URI"], "hasParam", "/test", name)[2] is True, f"{name} to be set")


def wait_for_publisher(env: dict[str, str], topic: str) -> None:
    """Wait until the master at ``env``'s ROS_MASTER_URI has a publisher of ``topic`` (as `topic list` shows)."""
    from rostui.core.xmlrpc import call_sync

    def published() -> bool:
        return topic in {name for name, _ in call_sync(env["ROS_MASTER_URI"], "getPublishedTopics", "/test", "")[2]}

    wait_until(published, f"a publisher of {topic}")


def wait_for_node(env: dict[str, str], node: str, peer: Peer | None = None) -> None:
    """Wait until the master knows a node (it has registered something), as `rosnode list` would show it.

    The master is asked directly: a `rosnode list` process per poll cost a third of a CPU second each time.
    On failure the message holds the last answer and, when given, the ``peer`` that should be ``node``.
    """
    last: list[set[str] | str] = []

    def listed() -> bool:
        last[:] = [graph_nodes(env)]
        return node in last[0]

    try:
        wait_until(listed, f"{node} known to the master")
    except AssertionError as exc:
        seen = f"last answer: {sorted(last[0]) if isinstance(last[0], set) else last[0]}" if last else ""
        raise AssertionError(f"{exc}\n{seen}\n{peer.describe() if peer else ''}") from None


@pytest.fixture(scope="session")
def roscpp_peer_bin(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """bench/roscpp_peer.cpp compiled against Debian's libroscpp-dev."""
    need_command("g++")
    need_peer(Path("/usr/include/ros/ros.h").exists(), describe("/usr/include/ros/ros.h"))
    if not ROSCPP_SOURCE.exists():
        pytest.fail(f"{ROSCPP_SOURCE} does not exist")

    def compile_peer(folder: Path) -> None:
        cmd = ["g++", "-O2", str(ROSCPP_SOURCE), "-o", str(folder / "roscpp_peer"), "-I/usr/include",
               "-lroscpp", "-lrosconsole", "-lroscpp_serialization", "-lrostime", "-lxmlrpcpp", "-lcpp_common",
               "-lboost_system"]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        if proc.returncode != 0:
            pytest.fail(f"compiling {ROSCPP_SOURCE.name} failed:\n{proc.stderr[-4000:]}")

    return shared_build(tmp_path_factory, "roscpp", compile_peer) / "roscpp_peer"
