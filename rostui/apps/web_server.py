"""A terminal app served to web browsers: textual-serve's server, stopped the way rostui's apps expect.

This module imports textual-serve and aiohttp (the optional extra ``rostui[web]``):
only `rostui serve` imports it, after checking that the extra is there.

textual-serve starts one app process for each browser tab and, when the tab
closes, asks it to quit (Textual's web driver turns that into an ordinary
exit, so the app unregisters its nodes and a launch stops its processes).
When the server itself stops, its open tabs are closed the same way, and the
server waits for their apps before it goes, so nothing it started outlives it.
"""

from __future__ import annotations

import asyncio
import logging
import shlex
from typing import Any, Sequence

import psutil
from aiohttp import web
from textual_serve.server import Server

#: Seconds the open apps get to quit when the server stops (a launch's nodes get 15 s after SIGINT).
QUIT_GRACE = 30.0

#: Seconds between SIGTERM and SIGKILL for an app that did not quit within :data:`QUIT_GRACE`.
KILL_GRACE = 5.0


class AppServer(Server):
    """Serves ``argv`` (a rostui app's command line) to every browser tab that opens ``public_url``."""

    def __init__(self, argv: Sequence[str], *, host: str, port: int, public_url: str, title: str,
                 announce: Sequence[str]) -> None:
        # textual-serve runs the command through /bin/sh; `exec` makes the app the server's own child.
        super().__init__("exec " + shlex.join(argv), host=host, port=port, title=title, public_url=public_url)
        self.announce = list(announce)
        self.sessions: set[asyncio.Task[Any]] = set()

    def initialize_logging(self) -> None:
        """textual-serve's log handler, without a line for each HTTP request."""
        super().initialize_logging()
        logging.getLogger("aiohttp.access").setLevel(logging.WARNING)

    async def on_startup(self, app: web.Application) -> None:
        """Say where the app is served (in place of textual-serve's banner)."""
        for line in self.announce:
            print(line, flush=True)

    async def handle_websocket(self, request: web.Request) -> web.WebSocketResponse:
        """One browser tab's session, remembered until it ends so that shutdown can close it."""
        session = asyncio.current_task()
        assert session is not None
        self.sessions.add(session)
        try:
            response: web.WebSocketResponse = await super().handle_websocket(request)
            return response
        finally:
            self.sessions.discard(session)

    async def on_shutdown(self, app: web.Application) -> None:
        """Close every open session as a closed tab would (its app quits), then wait for the apps to end."""
        loop = asyncio.get_running_loop()
        deadline = loop.time() + QUIT_GRACE
        sessions = list(self.sessions)
        for session in sessions:
            session.cancel()
        if sessions:
            await asyncio.wait(sessions, timeout=QUIT_GRACE)
        await end_children(max(0.0, deadline - loop.time()), KILL_GRACE)


async def end_children(grace: float, kill_grace: float) -> None:
    """Wait up to ``grace`` seconds until this process has no children left (each reaped by asyncio's
    child watcher, while the loop still runs); SIGTERM those still there, SIGKILL them after ``kill_grace``."""
    me = psutil.Process()
    children = await _children_after(me, grace)
    for child in children:
        _signal(child, terminate=True)
    children = await _children_after(me, kill_grace)
    for child in children:
        _signal(child, terminate=False)
    await _children_after(me, kill_grace)


async def _children_after(me: psutil.Process, timeout: float) -> list[psutil.Process]:
    """This process's children once none is left, or those still there after ``timeout`` seconds."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + timeout
    while (children := me.children()) and loop.time() < deadline:
        await asyncio.sleep(0.05)
    return children


def _signal(child: psutil.Process, *, terminate: bool) -> None:
    """SIGTERM (or SIGKILL) one child, if it is still there."""
    try:
        child.terminate() if terminate else child.kill()
    except psutil.NoSuchProcess:
        pass
