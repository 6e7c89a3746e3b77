"""Shared pieces of the launch tests: the corpus package, an environment real roslaunch can use, runners."""

from __future__ import annotations

import atexit
import json
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import psutil

from cli_helpers import rostui
from conftest import REPO, SYSTEM_PYTHON

CORPUS_ROOT = REPO / "tests" / "launch_corpus"
CORPUS = CORPUS_ROOT / "launch_corpus"
BUILTIN_SHARE = REPO / "rostui" / "share"
FORK_SERVER = REPO / "tests" / "peers" / "roslaunch_forks.py"
ANON = re.compile(r"_[A-Za-z0-9_]+?_\d+_\d+\b")


def have_roslaunch() -> bool:
    """True when Debian's roslaunch is installed."""
    return shutil.which("roslaunch") is not None


def launch_env(ros_env: dict[str, str]) -> dict[str, str]:
    """ros_env plus a package path holding rostui's built-ins and the corpus (for both launchers)."""
    env = dict(ros_env)
    env["ROS_PACKAGE_PATH"] = f"{BUILTIN_SHARE}:{CORPUS_ROOT}"
    env["CORPUS_ENV"] = "envval"
    env.pop("CORPUS_NOT_SET", None)
    return env


def run_rostui(args: list[str], env: dict[str, str], timeout: float = 60.0) -> subprocess.CompletedProcess[str]:
    """``rostui launch ARGS`` to completion."""
    return rostui(["launch", *args], env, timeout=timeout)


#: roslaunch's options that only print what a launch would do (no master, no processes, no logging).
VIEW_OPTIONS = ("--nodes", "--args", "--dump-params", "--files", "--ros-args", "--find-node")


def run_roslaunch(args: list[str], env: dict[str, str], timeout: float = 60.0) -> subprocess.CompletedProcess[str]:
    """Debian's ``roslaunch ARGS`` to completion.

    A view (``--nodes``, ``--args`` ...) runs in a fork of one process per worker that has imported
    roslaunch already (tests/peers/roslaunch_forks.py): the same script, environment, directory and
    argv, without paying two thirds of a CPU second of imports a few hundred times. Anything else runs
    as its own process.
    """
    if any(arg in VIEW_OPTIONS for arg in args):
        return _forks().run(args, env, timeout)
    return run_roslaunch_process(args, env, timeout)


def run_roslaunch_process(args: list[str], env: dict[str, str],
                          timeout: float = 60.0) -> subprocess.CompletedProcess[str]:
    """Debian's ``roslaunch ARGS`` as a process of its own, to completion."""
    return subprocess.run(["roslaunch", *args], env=env, cwd=REPO, capture_output=True, text=True,
                          timeout=timeout, stdin=subprocess.DEVNULL)


class RoslaunchForks:
    """The client of tests/peers/roslaunch_forks.py: one server per test worker, one request at a time."""

    def __init__(self) -> None:
        self.proc = subprocess.Popen([SYSTEM_PYTHON, str(FORK_SERVER)], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, bufsize=0, cwd=REPO)
        self.scratch = Path(tempfile.mkdtemp(prefix="roslaunch-forks-"))
        self._pending = b""
        atexit.register(self.close)

    def run(self, args: list[str], env: dict[str, str], timeout: float) -> subprocess.CompletedProcess[str]:
        """``roslaunch ARGS`` in a fork; its status, stdout and stderr as subprocess.run gives them."""
        assert self.proc.stdin is not None
        out, err = self.scratch / "stdout", self.scratch / "stderr"
        request = {"argv": args, "env": env, "cwd": str(REPO), "out": str(out), "err": str(err)}
        self.proc.stdin.write(json.dumps(request).encode() + b"\n")
        pid = self._answer(30.0)["pid"]
        try:
            status = self._answer(timeout)["status"]
        except subprocess.TimeoutExpired:
            os.kill(pid, signal.SIGKILL)
            self._answer(30.0)
            raise subprocess.TimeoutExpired(["roslaunch", *args], timeout) from None
        return subprocess.CompletedProcess(["roslaunch", *args], status, out.read_text(), err.read_text())

    def _answer(self, timeout: float) -> dict[str, int]:
        """The server's next answer line, read from the pipe itself (no buffer hides a line from select)."""
        assert self.proc.stdout is not None
        fd = self.proc.stdout.fileno()
        deadline = time.monotonic() + timeout
        while b"\n" not in self._pending:
            ready, _, _ = select.select([fd], [], [], max(0.0, deadline - time.monotonic()))
            if not ready:
                raise subprocess.TimeoutExpired("roslaunch", timeout)
            chunk = os.read(fd, 65536)
            if not chunk:
                raise AssertionError(f"the roslaunch fork server ended ({self.proc.poll()})")
            self._pending += chunk
        line, self._pending = self._pending.split(b"\n", 1)
        answer: dict[str, int] = json.loads(line)
        return answer

    def close(self) -> None:
        """End the server (at the worker's exit)."""
        if self.proc.stdin is not None:
            self.proc.stdin.close()
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        shutil.rmtree(self.scratch, ignore_errors=True)


_FORKS: list[RoslaunchForks] = []


def _forks() -> RoslaunchForks:
    if not _FORKS or _FORKS[0].proc.poll() is not None:
        _FORKS[:] = [RoslaunchForks()]
    return _FORKS[0]


def without_anon(text: str) -> str:
    """Text with anonymous-name suffixes replaced (they differ from run to run)."""
    return ANON.sub("_ANON", text)


def corpus_file(name: str) -> Path:
    """A launch file of the corpus package (``launch/NAME`` or ``errors/NAME``)."""
    for folder in ("launch", "errors"):
        path = CORPUS / folder / name
        if path.exists():
            return path
    raise FileNotFoundError(name)


class Launch:
    """A running ``rostui launch`` whose output is collected in files."""

    def __init__(self, args: list[str], env: dict[str, str], tmp: Path) -> None:
        self.out_path, self.err_path = tmp / "launch.out", tmp / "launch.err"
        self.proc = subprocess.Popen([sys.executable, "-m", "rostui", "launch", *args], env=env, cwd=REPO,
                                     stdout=self.out_path.open("w"), stderr=self.err_path.open("w"),
                                     stdin=subprocess.DEVNULL)

    @property
    def out(self) -> str:
        """What the launcher printed on stdout so far."""
        return self.out_path.read_text()

    @property
    def err(self) -> str:
        """What the launcher printed on stderr so far."""
        return self.err_path.read_text()

    def interrupt(self, timeout: float = 90.0) -> int:
        """Ctrl-C (SIGINT) and wait for the launcher to end."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
        return self.proc.wait(timeout=timeout)

    def descendants(self) -> list[psutil.Process]:
        """The launcher's processes (nodes and their children), [] once it is gone."""
        try:
            return psutil.Process(self.proc.pid).children(recursive=True)
        except psutil.Error:
            return []
