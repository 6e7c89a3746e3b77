"""``rostui bag play``'s keys: space pauses and resumes, ``s`` steps, read from the terminal on stdin."""

from __future__ import annotations

import asyncio
import os
import sys
from typing import Any

from rostui.tools.bag.player import Player


class TerminalKeys:
    """Space and ``s`` from a terminal on stdin, in cbreak mode (restored on close); nothing without a terminal.

    uvloop's ``add_reader`` (libuv's poll handle) makes the descriptor non-blocking, and the terminal's open file
    is shared with stdout and with the shell: it is made blocking again at once (a full terminal would otherwise
    fail the status line's writes with EAGAIN) and left as it was found (the shell said "turning off NDELAY
    mode" after every play).
    """

    def __init__(self) -> None:
        self.player: Player | None = None
        self.saved: Any = None
        self.fd = -1
        self.was_blocking = True

    def open(self, loop: asyncio.AbstractEventLoop, player: Player) -> None:
        """Start reading keys for ``player`` when stdin is a terminal."""
        if not sys.stdin.isatty():
            return
        import termios
        import tty

        self.player = player
        self.fd = sys.stdin.fileno()
        self.saved = termios.tcgetattr(self.fd)
        self.was_blocking = os.get_blocking(self.fd)
        tty.setcbreak(self.fd)
        loop.add_reader(self.fd, self._on_key)
        os.set_blocking(self.fd, True)  # readiness is polled; the read below takes only what is there

    def _on_key(self) -> None:
        key = os.read(self.fd, 16)
        if self.player is None:
            return
        if b" " in key:
            self.player.toggle_pause()
        elif b"s" in key:
            self.player.step_once()

    def close(self, loop: asyncio.AbstractEventLoop) -> None:
        """Give the terminal back as it was."""
        if self.saved is None:
            return
        import termios

        loop.remove_reader(self.fd)
        termios.tcsetattr(self.fd, termios.TCSADRAIN, self.saved)
        os.set_blocking(self.fd, self.was_blocking)
        self.saved = None
