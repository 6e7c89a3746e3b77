"""What the benchmark scripts share: free ports, a private ROS environment, CPU pinning, an app on a pty.

The scripts import it as ``_common`` (Python puts a script's own folder on
``sys.path``).
"""

from __future__ import annotations

import fcntl
import os
import pty
import shutil
import signal
import socket
import struct
import subprocess
import sys
import termios
import threading
import time
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

REPO = Path(__file__).resolve().parent.parent
BUILD = REPO / "bench" / "_build"
CPP_LIBS = ["-lroscpp", "-lrosconsole", "-lroscpp_serialization", "-lrostime", "-lxmlrpcpp", "-lcpp_common",
            "-lboost_system"]
"""What a roscpp peer links against (Debian's libroscpp-dev)."""


def build_cpp(source: Path) -> Path | None:
    """Compile a roscpp peer (``bench/NAME.cpp`` to ``bench/_build/NAME``) unless the binary is newer than
    its source; None when it cannot be built here (no g++ or no roscpp headers)."""
    binary = BUILD / source.stem
    if binary.exists() and binary.stat().st_mtime >= source.stat().st_mtime:
        return binary
    if shutil.which("g++") is None or not Path("/usr/include/ros/ros.h").exists():
        return None
    BUILD.mkdir(exist_ok=True)
    print("building", binary.relative_to(REPO), "...", flush=True)
    done = subprocess.run(["g++", "-O2", str(source), "-o", str(binary), "-I/usr/include", *CPP_LIBS],
                          capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        print(done.stderr[-2000:], file=sys.stderr)
        return None
    return binary
APP_CPU = 0
"""The CPU the measured app is pinned to; everything else runs on the others."""


def free_port() -> int:
    """A TCP port nothing listens on now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_port(port: int, timeout: float = 30.0) -> None:
    """Block until 127.0.0.1:port accepts connections; exit with one line if nothing does in time."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=0.5):
                return
        except OSError:
            time.sleep(0.05)
    raise SystemExit(f"nothing listened on port {port} within {timeout:g}s")


def other_cpus() -> set[int]:
    """The CPUs for everything but the app: all but APP_CPU, or all of them if there is only one."""
    cpus = os.sched_getaffinity(0)
    return (cpus - {APP_CPU}) or cpus


def ros_env(port: int, home: str, **extra: str) -> dict[str, str]:
    """This process's environment with a master on 127.0.0.1:``port``, ROS_HOME ``home`` and ``extra``."""
    return dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=home, ROS_IP="127.0.0.1", **extra)


@dataclass
class PtyApp(ABC):
    """A process on the slave side of a ``cols`` x ``rows`` pty, optionally pinned to ``pin``.

    A thread reads everything the process writes and hands each chunk to
    :meth:`received`, which subclasses define to keep what they measure.
    """

    argv: list[str]
    env: dict[str, str]
    cols: int
    rows: int
    pin: set[int] | None = None
    proc: subprocess.Popen | None = None
    _fd: int = -1
    _reader: threading.Thread | None = None

    def start(self) -> None:
        """Open the pty, size it, start the process on it (its own session) and the reading thread."""
        master, slave = pty.openpty()
        winsize = struct.pack("HHHH", self.rows, self.cols, self.cols * 10, self.rows * 20)  # cells of 10x20 pixels
        fcntl.ioctl(slave, termios.TIOCSWINSZ, winsize)
        pin = self.pin

        def setup() -> None:
            if pin:
                os.sched_setaffinity(0, pin)

        self.proc = subprocess.Popen(self.argv, env=self.env, cwd=REPO, stdin=slave, stdout=slave, stderr=slave,
                                     start_new_session=True, preexec_fn=setup, close_fds=True)
        os.close(slave)
        self._fd = master
        self._reader = threading.Thread(target=self._drain, daemon=True)
        self._reader.start()

    def _drain(self) -> None:
        while True:
            try:
                chunk = os.read(self._fd, 65536)
            except OSError:
                return
            if not chunk:
                return
            self.received(chunk)

    @abstractmethod
    def received(self, chunk: bytes) -> None:
        """Keep what matters of ``chunk``, just read from the terminal (called on the reading thread)."""

    def write(self, data: bytes) -> None:
        """Type ``data`` into the terminal."""
        os.write(self._fd, data)

    def quit(self) -> int:
        """Press q; wait for the exit status (kill the process's session after 15 s)."""
        assert self.proc is not None
        if self.proc.poll() is None:
            self.write(b"q")
            try:
                self.proc.wait(timeout=15)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        if self._reader is not None:
            self._reader.join(timeout=5)
        os.close(self._fd)
        return self.proc.returncode


@dataclass
class RecordingPty(PtyApp):
    """A :class:`PtyApp` that keeps every byte the process writes, and times keys against it."""

    data: bytearray = field(default_factory=bytearray)
    _lock: threading.Lock = field(default_factory=threading.Lock)

    def received(self, chunk: bytes) -> None:
        """Keep ``chunk`` after the bytes before it."""
        with self._lock:
            self.data += chunk

    @property
    def size(self) -> int:
        """Bytes received so far."""
        with self._lock:
            return len(self.data)

    def since(self, offset: int) -> bytes:
        """Bytes received after ``offset``."""
        with self._lock:
            return bytes(self.data[offset:])

    def press(self, key: bytes, done: Callable[[bytes], bool] | bytes, timeout: float = 5.0) -> float | None:
        """Type ``key``; seconds until the output after it shows ``done`` (a marker or a test), None if never."""
        test = done if callable(done) else (lambda out: done in out)
        offset = self.size
        start = time.perf_counter()
        self.write(key)
        while time.perf_counter() - start < timeout:
            if test(self.since(offset)):
                return time.perf_counter() - start
            time.sleep(0.0005)
        return None

