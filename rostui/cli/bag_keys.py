"""``rostui bag play``'s keys: space pauses and resumes, ``s`` steps, read from the terminal on stdin."""

from __future__ import annotations

import asyncio
import os
import sys
from typing import Any

from rostui.tools.bag.player import Player


class TerminalKeys:
    """Space and ``s`` from a terminal on stdin, in cbreak mode (restored on close); nothing without a terminal."""

    def __init__(self) -> None:
        self.player: Player | None = None
        self.saved: Any = None
        self.fd = -1

    def open(self, loop: asyncio.AbstractEventLoop, player: Player) -> None:
        """Start reading keys for ``player`` when stdin is a terminal."""
        if not sys.stdin.isatty():
            return
        import termios
        import tty

        self.player = player
        self.fd = sys.stdin.fileno()
        self.saved = termios.tcgetattr(self.fd)
        tty.setcbreak(self.fd)
        loop.add_reader(self.fd, self._on_key)

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
        self.saved = None
