"""The reader's desk for the book tests: several terminals in one tmux session, and one-shot commands.

The book runs long-lived programs (roscore, turtlesim, teleop, rostopic echo,
rqt_console, rosbag record) each in its own terminal.  ``Desk`` gives a test
such terminals: windows of one detached tmux session on a private tmux server,
each a plain shell in the chapter's ROS environment, where the test types the
same ``rostui ...`` lines a reader types.  Commands that print and exit
(``rostui node list``) run through :func:`cli` instead, so their output can be
compared whole.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
import time
import uuid
from pathlib import Path
from typing import Callable, Iterator

import psutil
import pytest

from cli_helpers import rostui
from conftest import need_command, wait_until

DEADLINE = 60.0
"""Seconds a wait for the screen may take (generous: the book tests share the machine with others)."""

PLAIN_SHELL = "env PS1='$ ' /bin/sh"
EXIT_MARK = "EXIT_STATUS="
READER_TERMINAL = (80, 24)
"""Columns and lines of every terminal on the desk: the size a terminal opens at, which the book's reader keeps."""
LOG_LINE = re.compile(r"^\[ ?(DEBUG|INFO|WARN|ERROR|FATAL)\] \[(\d+\.\d+)\]: (.*)$", re.MULTILINE)


def cli(args: str, env: dict[str, str], timeout: float = 30.0) -> subprocess.CompletedProcess[str]:
    """Run one ``rostui ARGS`` line (shell-split) to completion, as typed in a spare terminal."""
    return rostui(shlex.split(args), env, timeout=timeout)


def ok(args: str, env: dict[str, str], timeout: float = 30.0) -> str:
    """``rostui ARGS`` that must succeed; its stdout."""
    result = cli(args, env, timeout)
    assert result.returncode == 0, f"rostui {args} exited {result.returncode}: {result.stderr}"
    return result.stdout


def lines(text: str) -> list[str]:
    """The non-empty lines of ``text``, stripped."""
    return [line.strip() for line in text.splitlines() if line.strip()]


def poll(predicate: Callable[[], bool], what: str, timeout: float = DEADLINE) -> None:
    """Wait for ``predicate`` (the book tests' generous deadline)."""
    wait_until(predicate, what, timeout=timeout)


def dot_edges(dot: str) -> set[tuple[str, str, str]]:
    """The edges of ``rostui graph --dot`` output as (from, to, topic), one per topic of a node-to-node edge's label
    (empty for edges to and from topic boxes), with the n:/t: prefixes dropped."""
    edges = set()
    for match in re.finditer(r'^\s*"[nt]:([^"]+)" -> "[nt]:([^"]+)"(?: \[label="([^"]*)"\])?;$', dot, re.MULTILINE):
        for topic in (match[3] or "").split("\\n"):
            edges.add((match[1], match[2], topic))
    return edges


def dot_nodes(dot: str) -> set[str]:
    """The node names (ellipses) in ``rostui graph --dot`` output."""
    return set(re.findall(r'^\s*"n:([^"]+)" \[', dot, re.MULTILINE))


def dot_topics(dot: str) -> set[str]:
    """The topic names (boxes) in ``rostui graph --dot`` output."""
    return set(re.findall(r'^\s*"t:([^"]+)" \[', dot, re.MULTILINE))


class Terminal:
    """One window of the desk: a shell the test types into and reads back."""

    def __init__(self, desk: "Desk", name: str) -> None:
        self.desk = desk
        self.name = name
        self.target = f"{desk.session}:{name}"
        self.runs = 0

    def type(self, line: str) -> None:
        """Type ``line`` and Enter."""
        self.desk.tmux("send-keys", "-t", self.target, "-l", line)
        self.desk.tmux("send-keys", "-t", self.target, "Enter")

    def run(self, line: str) -> None:
        """Type ``line`` followed by a marker that prints its exit status when it ends."""
        self.runs += 1
        self.type(f"{line}; echo {EXIT_MARK}{self.runs}=$?")

    def keys(self, *keys: str) -> None:
        """Send tmux key names (``Up``, ``C-c``, ``q``)."""
        self.desk.tmux("send-keys", "-t", self.target, *keys)

    def screen(self, history: int = 0) -> str:
        """The visible screen, with ``history`` lines of scrollback above it."""
        args = ["capture-pane", "-p", "-J", "-t", self.target]
        if history:
            args += ["-S", f"-{history}"]
        return self.desk.tmux(*args)

    def colours(self) -> str:
        """The visible screen with its colour escape sequences (``capture-pane -e``)."""
        return self.desk.tmux("capture-pane", "-p", "-e", "-t", self.target)

    def wait_for(self, pattern: str, history: int = 2000, timeout: float = DEADLINE) -> re.Match[str]:
        """Wait until the regular expression matches the screen (and scrollback); return the match."""
        found: list[re.Match[str]] = []

        def check() -> bool:
            match = re.search(pattern, self.screen(history), re.MULTILINE)
            if match:
                found.append(match)
            return match is not None
        try:
            wait_until(check, f"{pattern!r} in terminal {self.name}", timeout=timeout)
        except AssertionError as error:
            raise AssertionError(f"{error}; the screen:\n{self.screen(history)}") from None
        return found[0]

    def exit_status(self, timeout: float = DEADLINE) -> int:
        """Wait for the command started with :meth:`run` to end; its exit status."""
        return int(self.wait_for(rf"{EXIT_MARK}{self.runs}=(\d+)$", timeout=timeout)[1])

    def interrupt(self, timeout: float = DEADLINE) -> int:
        """Ctrl-C the command started with :meth:`run`; its exit status."""
        self.keys("C-c")
        return self.exit_status(timeout)


class Desk:
    """A private tmux server with one session whose windows are the reader's terminals."""

    def __init__(self, env: dict[str, str], tmp: Path, size: tuple[int, int] = READER_TERMINAL) -> None:
        need_command("tmux")
        width, height = size
        self.env = self._terminal_env(env, tmp)
        self.socket = f"rostui-book-{os.getpid()}-{uuid.uuid4().hex[:8]}"
        self.session = "book"
        self.cwd = tmp
        self.terminals: list[Terminal] = []
        subprocess.run(["tmux", "-u", "-L", self.socket, "-f", "/dev/null", "new-session", "-d", "-s", self.session,
                        "-n", "spare", "-x", str(width), "-y", str(height), PLAIN_SHELL], env=self.env, cwd=tmp,
                       check=True, timeout=30)
        self.tmux("set-option", "-t", self.session, "status", "off")

    @staticmethod
    def _terminal_env(env: dict[str, str], tmp: Path) -> dict[str, str]:
        """``env`` with ``rostui`` on PATH (this Python's rostui), a 256-colour terminal and no fixed size."""
        bin_dir = tmp / "bin"
        bin_dir.mkdir(exist_ok=True)
        wrapper = bin_dir / "rostui"
        wrapper.write_text(f"#!/bin/sh\nexec {shlex.quote(sys.executable)} -m rostui \"$@\"\n")
        wrapper.chmod(0o755)
        values = dict(env)
        values["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
        values["TERM"] = "xterm-256color"
        values["COLORTERM"] = "truecolor"
        for key in ("COLUMNS", "LINES", "TMUX", "TMUX_PANE", "NO_COLOR"):
            values.pop(key, None)
        return values

    def tmux(self, *args: str) -> str:
        """Run a tmux command against this desk's server; its stdout."""
        result = subprocess.run(["tmux", "-u", "-L", self.socket, *args], capture_output=True, text=True, timeout=30,
                                env=self.env)
        assert result.returncode == 0, f"tmux {' '.join(args)}: {result.stderr}"
        return result.stdout

    def terminal(self, name: str) -> Terminal:
        """Open a new terminal (window) called ``name`` with a shell at its ``$`` prompt."""
        self.tmux("new-window", "-d", "-t", self.session, "-n", name, "-c", str(self.cwd),
                  f"env PATH={shlex.quote(self.env['PATH'])} {PLAIN_SHELL}")
        terminal = Terminal(self, name)
        terminal.wait_for(r"^\$", history=0)
        self.terminals.append(terminal)
        return terminal

    def close(self) -> None:
        """End every terminal's program as a reader would (q for the apps, then Ctrl-C), then kill the tmux server.

        Anything the terminals started that still runs afterwards is killed, so no test leaves a process behind.
        """
        started = self._programs()
        for key, patience in (("q", 3.0), ("C-c", 10.0)):  # q ends the apps and teleops while the master runs
            for terminal in reversed(self.terminals):
                if not self._idle(terminal):
                    terminal.keys(key)
            deadline = time.monotonic() + patience
            while time.monotonic() < deadline and not all(self._idle(t) for t in self.terminals):
                time.sleep(0.2)
        subprocess.run(["tmux", "-L", self.socket, "kill-server"], capture_output=True, timeout=30)
        _, alive = psutil.wait_procs(started, timeout=10)
        for process in alive:
            try:
                process.kill()
            except psutil.Error:
                pass

    def _programs(self) -> list[psutil.Process]:
        """Every process running below the terminals' shells."""
        try:
            pids = self.tmux("list-panes", "-s", "-t", self.session, "-F", "#{pane_pid}").split()
        except AssertionError:
            return []
        found: list[psutil.Process] = []
        for pid in pids:
            try:
                found += psutil.Process(int(pid)).children(recursive=True)
            except psutil.Error:
                pass
        return found

    def _idle(self, terminal: Terminal) -> bool:
        """True when the terminal's shell has no program running in the foreground."""
        try:
            command = self.tmux("display-message", "-p", "-t", terminal.target, "#{pane_current_command}")
        except AssertionError:
            return True
        return command.strip() in ("sh", "dash", "bash")


def log_lines(text: str, level: str) -> list[str]:
    """The messages of console log lines at ``level`` in ``text``."""
    return [m[3] for m in LOG_LINE.finditer(text) if m[1] == level]


POSE = re.compile(r"(\w+) x (-?\d+\.\d+) y (-?\d+\.\d+) \S (-?\d+\.\d+)")
"""The selected turtle's pose on the turtlesim app's status line."""


def status_pose(terminal: Terminal) -> tuple[float, float, float] | None:
    """The pose on a turtlesim app's status line, if it is on screen."""
    match = POSE.search(terminal.screen())
    return None if match is None else (float(match[2]), float(match[3]), float(match[4]))


def settled_pose(terminal: Terminal) -> tuple[float, float, float]:
    """The turtle's pose once it has stood still for 1.5 s (turtlesim stops a turtle 1 s after its last command)."""
    seen: list[tuple[float, tuple[float, float, float] | None]] = []

    def settled() -> bool:
        now = time.monotonic()
        seen.append((now, status_pose(terminal)))
        recent = {pose for when, pose in seen if when >= now - 1.5}
        return now - seen[0][0] >= 1.5 and len(recent) == 1 and None not in recent
    poll(settled, "the turtle to stand still")
    pose = seen[-1][1]
    assert pose is not None
    return pose


def start_core(desk: Desk) -> Terminal:
    """The book's first terminal: ``rostui core`` on the chapter's port, waited for until it serves."""
    core = desk.terminal("core")
    core.run(f"rostui core -p {desk.env['ROSTUI_TEST_MASTER_PORT']}")
    core.wait_for(r"^started core service \[/rosout\]$")
    return core


def start_turtlesim_view(desk: Desk, name: str = "turtlesim", args: str = "") -> Terminal:
    """``rostui run turtlesim turtlesim_node ARGS`` in its own terminal; waits until turtle1 is drawn."""
    sim = desk.terminal(name)
    sim.run(f"rostui run turtlesim turtlesim_node {args}".strip())
    poll(lambda: status_pose(sim) == (5.54, 5.54, 0.0), f"turtlesim's status line in terminal {name}")
    return sim


def start_teleop(desk: Desk, name: str = "teleop", args: str = "") -> Terminal:
    """``rostui run turtlesim turtle_teleop_key ARGS`` in its own terminal; waits for its key help."""
    teleop = desk.terminal(name)
    teleop.run(f"rostui run turtlesim turtle_teleop_key {args}".strip())
    teleop.wait_for(r"Use arrow keys to move the turtle")
    return teleop


def drive(teleop: Terminal, sim: Terminal, key: str = "Up", what: str = "the turtle to move") -> None:
    """Press ``key`` in the teleop terminal until the pose on ``sim``'s status line changes."""
    before = status_pose(sim)

    def moved() -> bool:
        teleop.keys(key)
        time.sleep(0.2)
        return status_pose(sim) not in (None, before)
    poll(moved, what)


@pytest.fixture
def desk(ros_env: dict[str, str], tmp_path: Path) -> Iterator[Desk]:
    """The reader's terminals for one chapter, in the chapter's own ROS environment (ros_env)."""
    terminals = Desk(ros_env, tmp_path)
    try:
        yield terminals
    finally:
        terminals.close()
