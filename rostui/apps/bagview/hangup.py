"""Ending the bag view when its terminal goes away, even when Textual cannot finish.

``quit_on_signals`` quits as ``q`` does on SIGTERM and SIGHUP: the app stops
its node and finishes its files, then Textual restores the terminal through
its writer thread. On a terminal that has hung up that thread can die on the
first failed write (EIO) with its queue full; ``App.exit`` then waits for
ever to hand it the stop marker (seen about once in five `tmux kill-server`
runs with a bag playing). The app's own cleanup has run by then, so a
watchdog that ends the process a little later loses nothing.
"""

from __future__ import annotations

import asyncio
import os
import signal
import threading

from textual.app import App

from rostui.apps.widgets.lifecycle import quit_on_signals

#: Seconds after a hangup by which the process ends, whatever Textual is doing.
HANGUP_GRACE = 10.0

#: Exit status when the watchdog ends the process (128 + SIGHUP, as a shell reports it).
HANGUP_STATUS = 128 + signal.SIGHUP


def quit_on_signals_and_hangup(app: App, grace: float = HANGUP_GRACE) -> None:
    """``quit_on_signals(app)``; on SIGHUP also start a watchdog that ends the process after ``grace`` seconds."""
    quit_on_signals(app)
    loop = asyncio.get_running_loop()

    def hangup() -> None:
        watchdog = threading.Timer(grace, os._exit, args=(HANGUP_STATUS,))
        watchdog.daemon = True
        watchdog.start()
        app.call_later(app.action_quit)

    try:
        loop.add_signal_handler(signal.SIGHUP, hangup)
    except (NotImplementedError, RuntimeError, ValueError):
        pass
