"""A real terminal for end-to-end tests: one tmux session on a private tmux server.

Tests start `rostui` commands in a detached tmux pane, send keys with
`tmux send-keys` and read the screen with `tmux capture-pane`.  Every pane has
its own server (``tmux -L SOCKET``), so tests never see each other's sessions
or the user's.
"""

from __future__ import annotations

import os
import shlex
import subprocess
import sys
import uuid
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterator, Sequence, TypeVar

from conftest import need_command, wait_until

DEADLINE = 30.0
"""Seconds a tmux command or a wait for the screen may take (generous: CI machines are slow)."""

PaneT = TypeVar("PaneT", bound="Pane")

PLAIN_SHELL = "env PS1='$ ' /bin/sh"
"""A shell whose prompt is a bare ``$``, so a test can see that the prompt is back."""


@dataclass
class Pane:
    """One tmux session on a private tmux server."""

    socket: str
    session: str

    @classmethod
    def start(cls: type[PaneT], session: str, width: int, height: int, command: Sequence[str],
              env: dict[str, str] | None = None, cwd: Path | None = None, **fields: Any) -> PaneT:
        """A detached ``width`` x ``height`` session named ``session`` running ``command``, with no status bar.

        ``env`` and ``cwd`` are those the new tmux server, and so ``command``, starts with; ``fields`` are
        the further fields of a Pane subclass.  ``COLUMNS`` and ``LINES`` are dropped from the environment
        (pilot tests in the same pytest process can leave them set): apps must size themselves to the pane.
        """
        env = {k: v for k, v in (os.environ if env is None else env).items() if k not in ("COLUMNS", "LINES")}
        pane = cls(socket=f"rostui-{session}-{os.getpid()}-{uuid.uuid4().hex[:8]}", session=session, **fields)
        subprocess.run(["tmux", "-u", "-L", pane.socket, "-f", "/dev/null", "new-session", "-d", "-s", session,
                        "-x", str(width), "-y", str(height), *command], env=env, cwd=cwd, check=True,
                       timeout=DEADLINE)
        try:
            pane.tmux("set-option", "-t", session, "status", "off")
        except BaseException:
            pane.close()
            raise
        return pane

    def tmux(self, *args: str) -> str:
        """Run a tmux command against this server; return its stdout."""
        result = subprocess.run(["tmux", "-u", "-L", self.socket, *args], capture_output=True, text=True,
                                timeout=DEADLINE)
        assert result.returncode == 0, f"tmux {' '.join(args)}: {result.stderr}"
        return result.stdout

    def screen(self) -> str:
        """The visible screen text."""
        return self.tmux("capture-pane", "-p", "-t", self.session)

    def type(self, line: str) -> None:
        """Type a command line and Enter."""
        self.tmux("send-keys", "-t", self.session, "-l", line)
        self.tmux("send-keys", "-t", self.session, "Enter")

    def clear(self) -> None:
        """Clear the screen and its history, and wait until the shell did (only its prompt shows): a line typed
        right after ``clear`` would otherwise be judged by the last command's screen."""
        self.tmux("clear-history", "-t", self.session)
        self.type("clear")
        self.wait_until(lambda: [line.strip() for line in self.screen().splitlines() if line.strip()] == ["$"],
                        "the screen to clear")

    def keys(self, *keys: str) -> None:
        """Send key names (``Up``, ``Enter``, ``C-c``, ``q``), or literal text after ``-l``."""
        self.tmux("send-keys", "-t", self.session, *keys)

    def shows(self, *texts: str) -> bool:
        """True when every text is on the screen."""
        screen = self.screen()
        return all(text in screen for text in texts)

    def wait_until(self, predicate: Callable[[], bool], what: str) -> None:
        """Poll ``predicate`` until it holds; fail with ``what`` and the screen when it never does."""
        try:
            wait_until(predicate, what, timeout=DEADLINE)
        except AssertionError as error:
            raise AssertionError(f"{error}; the screen:\n{self.screen()}") from None

    def wait_for_text(self, text: str) -> None:
        """Wait until ``text`` shows on the screen."""
        wait_until(lambda: text in self.screen(), f"{text!r} on the tmux screen", timeout=DEADLINE)

    def close(self) -> None:
        """Kill the private tmux server (and everything running in it)."""
        subprocess.run(["tmux", "-L", self.socket, "kill-server"], capture_output=True, timeout=DEADLINE)


@contextmanager
def shell_pane(session: str, width: int, height: int, kind: type[PaneT] = Pane) -> Iterator[PaneT]:
    """A detached ``width`` x ``height`` session running /bin/sh, at its plain ``$`` prompt; closed afterwards.

    ``kind`` is the Pane subclass to return, for tests that read more off the screen.

    Fails (or skips, unless interop is required) when tmux is not installed.
    """
    need_command("tmux")
    pane = kind.start(session, width, height, [PLAIN_SHELL])
    try:
        # a line typed before the shell reads is echoed by the terminal, then its output follows the prompt
        pane.wait_until(lambda: pane.screen().strip() == "$", "the shell's first prompt")
        yield pane
    finally:
        pane.close()


def rostui_line(env: dict[str, str], exit_mark: str, *args: str) -> str:
    """The shell line that runs `rostui ARGS` with the test's ROS environment, then ``exit_mark`` and its status."""
    values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    values["TERM"] = "xterm-256color"
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    return (f"env {assignments} {shlex.quote(sys.executable)} -m rostui {' '.join(map(shlex.quote, args))}; "
            f"echo {exit_mark}$?")
