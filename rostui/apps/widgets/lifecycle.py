"""How a rostui app ends when its terminal goes away or it is told to stop.

SIGTERM and SIGHUP quit the app as ``q`` does: it stops its node and
finishes its files, then Textual restores the terminal through its writer
thread.  On a terminal that has hung up (an SSH link dropped, tmux killed)
that thread can die on the first failed write (EIO) with its queue full, and
``App.exit`` then waits for ever to hand it the stop marker.  So a hangup
also starts a watchdog that ends the process a little later: the app's own
clean-up has run by then, and nothing is left to restore on a vanished screen.
"""

from __future__ import annotations

import asyncio
import os
import signal
import threading

from textual.app import App

#: Seconds after a hangup by which the process ends, whatever Textual is doing.
HANGUP_GRACE = 10.0

#: Exit status when the watchdog ends the process (128 + SIGHUP, as a shell reports it).
HANGUP_STATUS = 128 + signal.SIGHUP


def quit_on_signals(app: App, grace: float = HANGUP_GRACE) -> None:
    """Quit ``app`` cleanly on SIGTERM and SIGHUP; after SIGHUP the process ends within ``grace`` seconds.

    Call from ``on_mount``.  Where the event loop cannot take signal handlers
    (not the main thread, or a platform without them) the default behaviour stays.
    """
    loop = asyncio.get_running_loop()

    def hangup() -> None:
        watchdog = threading.Timer(grace, os._exit, args=(HANGUP_STATUS,))
        watchdog.daemon = True
        watchdog.start()
        app.call_later(app.action_quit)

    handlers = {signal.SIGTERM: lambda: app.call_later(app.action_quit), signal.SIGHUP: hangup}
    for sig, handler in handlers.items():
        try:
            loop.add_signal_handler(sig, handler)
        except (NotImplementedError, RuntimeError, ValueError):
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
