"""How a rostui app ends when its terminal goes away or it is told to stop.

SIGTERM and SIGHUP quit the app as ``q`` does: it stops its node and finishes its files, then Textual
restores the terminal through its writer thread.  Two things can stand in the way, and each has a
deadline after which the process ends at once (exit status 128 + the signal, as a shell reports it):

- the event loop may be stuck in a long computation (a decoder on a huge message): signal handlers
  that the loop runs would wait for it, so these are ordinary Python handlers, which run between two
  bytecodes however busy the loop is; they hand the quit to the loop, and if the loop has not taken
  it within :data:`LOOP_GRACE` seconds nothing can be cleaned up and the process ends;
- on a terminal that has hung up (an SSH link dropped, tmux killed) Textual's writer thread can die
  on the first failed write (EIO) with its queue full, and ``App.exit`` then waits for ever; so after
  a hangup an app that releases what it holds (:class:`ReleasesOnExit`) ends as soon as it has, and
  any app ends ``grace`` seconds after the signal whatever Textual is doing (nothing is left to
  restore on a vanished screen).
"""

from __future__ import annotations

import asyncio
import os
import signal
import threading
import time
from types import FrameType
from typing import Callable, Optional

from textual.app import App

#: Seconds after a hangup or SIGTERM by which the process ends, whatever Textual is doing.
HANGUP_GRACE = 10.0

#: Seconds the event loop has to take the quit; a loop stuck longer cannot clean up, and the process ends.
LOOP_GRACE = 3.0

#: Exit status when the watchdog ends the process after a hangup (128 + SIGHUP, as a shell reports it).
HANGUP_STATUS = 128 + signal.SIGHUP


class _Ending:
    """What the first SIGTERM or SIGHUP starts: the quit, handed to the loop, and the deadlines that follow it."""

    def __init__(self, app: App, loop: asyncio.AbstractEventLoop, grace: float,
                 on_hangup: Optional[Callable[[], None]]) -> None:
        self.app = app
        self.loop = loop
        self.grace = grace
        self.on_hangup = on_hangup
        self.started = False
        self.taken = threading.Event()

    def signalled(self, signum: int, _frame: Optional[FrameType]) -> None:
        """The signal handler (on the main thread, between two bytecodes): start ending, once."""
        if self.started:
            return
        if self.loop.is_closed() or not self.app.is_running:  # the app is over: the signal does what it did before
            signal.signal(signum, signal.SIG_DFL)
            os.kill(os.getpid(), signum)
            return
        self.started = True
        threading.Thread(target=self._deadlines, args=(signum, time.monotonic()), name="rostui-ending",
                         daemon=True).start()
        try:
            self.loop.call_soon_threadsafe(self._quit, signum)
        except RuntimeError:  # the loop is closed: the app is past its clean-up already
            os._exit(128 + signum)

    def _quit(self, signum: int) -> None:
        self.taken.set()
        if signum == signal.SIGHUP and self.on_hangup is not None:
            self.on_hangup()
        elif signum == signal.SIGHUP and isinstance(self.app, ReleasesOnExit):
            asyncio.ensure_future(self._release_then_end(self.app, signum))
        else:
            self.app.call_later(self.app.action_quit)

    async def _release_then_end(self, app: ReleasesOnExit, signum: int) -> None:
        """After a hangup: what the app holds is released (nodes, files), and nothing is left to draw."""
        try:
            await app.release_once()
        finally:
            os._exit(128 + signum)

    def _deadlines(self, signum: int, since: float) -> None:
        if not self.taken.wait(min(LOOP_GRACE, self.grace)):
            os._exit(128 + signum)
        time.sleep(max(0.0, self.grace - (time.monotonic() - since)))
        os._exit(128 + signum)


def quit_on_signals(app: App, grace: float = HANGUP_GRACE, on_hangup: Optional[Callable[[], None]] = None) -> None:
    """Quit ``app`` cleanly on SIGTERM and SIGHUP; the process ends within ``grace`` seconds of the signal,
    and within :data:`LOOP_GRACE` when its event loop does not take the quit.

    ``on_hangup``, when given, runs on the loop instead of the quit after SIGHUP (an app that must stop
    what it started before it leaves).  Call from ``on_mount``.  Off the main thread, or on a platform
    without these signals, the default behaviour stays.
    """
    ending = _Ending(app, asyncio.get_running_loop(), grace, on_hangup)
    for signum in (signal.SIGTERM, signal.SIGHUP):
        try:
            signal.signal(signum, ending.signalled)
        except (ValueError, OSError, AttributeError):
            pass


class ReleasesOnExit:
    """For an ``App``: ``q`` and unmounting (however the app ends) both run :meth:`release`, once.

    ``q`` then leaves with exit status 0.  :attr:`released` tells periodic work
    that the app is going.
    """

    released = False

    async def release(self) -> None:
        """Stop what the app runs: unregister its nodes, finish its files.  Subclasses override it."""

    async def release_once(self) -> None:
        """Run :meth:`release` unless it has run already."""
        if not self.released:
            self.released = True
            await self.release()

    async def action_quit(self) -> None:
        """q: release, then leave."""
        await self.release_once()
        assert isinstance(self, App), "ReleasesOnExit is mixed into an App"
        self.exit(0)

    async def on_unmount(self) -> None:
        """However the app ends, it releases what it holds."""
        await self.release_once()
