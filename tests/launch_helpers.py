"""Shared pieces of the launch tests: the corpus package, an environment real roslaunch can use, runners."""

from __future__ import annotations

import re
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import psutil

from cli_helpers import rostui
from conftest import REPO

CORPUS_ROOT = REPO / "tests" / "launch_corpus"
CORPUS = CORPUS_ROOT / "launch_corpus"
BUILTIN_SHARE = REPO / "rostui" / "share"
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


def run_roslaunch(args: list[str], env: dict[str, str], timeout: float = 60.0) -> subprocess.CompletedProcess[str]:
    """Debian's ``roslaunch ARGS`` to completion."""
    return subprocess.run(["roslaunch", *args], env=env, cwd=REPO, capture_output=True, text=True,
                          timeout=timeout, stdin=subprocess.DEVNULL)


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
