"""How a rostui app ends when its terminal goes away or it is told to stop."""

from __future__ import annotations

import asyncio
import signal

from textual.app import App


def quit_on_signals(app: App) -> None:
    """Quit ``app`` cleanly (as q would) on SIGTERM and SIGHUP; call from ``on_mount``.

    Where the event loop cannot take signal handlers (not the main thread, or
    a platform without them) the default behaviour stays.
    """
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGTERM, signal.SIGHUP):
        try:
            loop.add_signal_handler(sig, lambda: app.call_later(app.action_quit))
        except (NotImplementedError, RuntimeError, ValueError):
            pass
