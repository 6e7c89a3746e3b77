"""What the `rostui serve` tests share: a server on a free port with the token it printed, its app processes,
and a websocket client that speaks textual-serve's protocol (the page's side of it) without a browser.

A :class:`Tab` is what one browser tab does: it opens ``/ws`` with the token, reads the app's screen bytes,
sends keys and sizes, and closes.  It runs on its own event loop thread so a synchronous test can drive
several at once.
"""

from __future__ import annotations

import asyncio
import json
import re
import subprocess
import threading
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Coroutine, Iterator, TypeVar

import psutil
import pytest

from conftest import REPO, free_port, rostui_cmd, stop_process, wait_for_port, wait_until

DEADLINE = 30.0
"""Seconds a wait on the server or an app may take (generous: CI machines are slow)."""

#: The address serve prints, with the token the browser must present.
TOKEN_URL = re.compile(r"(http://[^\s/]+)/\?token=([A-Za-z0-9_-]+)")

T = TypeVar("T")


@dataclass
class Served:
    """A running `rostui serve`: its process, port, token (from its printed URL) and output file."""

    proc: subprocess.Popen
    port: int
    token: str
    log: Path

    @property
    def url(self) -> str:
        """The address serve printed (token included)."""
        return f"http://localhost:{self.port}/?token={self.token}"

    def output(self) -> str:
        """Everything serve wrote so far."""
        return self.log.read_text()

    def apps(self) -> list[psutil.Process]:
        """The processes the server runs (one app a tab, and what each app started), zombies left out."""
        return live(psutil.Process(self.proc.pid).children(recursive=True))

    def stop(self) -> None:
        """Ctrl-C; SIGKILL if it is still there a minute later."""
        stop_process(self.proc, timeout=60)


def live(processes: list[psutil.Process]) -> list[psutil.Process]:
    """Those of ``processes`` that still run (zombies count as gone)."""
    alive = []
    for p in processes:
        try:
            if p.is_running() and p.status() != psutil.STATUS_ZOMBIE:
                alive.append(p)
        except psutil.NoSuchProcess:
            pass
    return alive


def start_serve(words: list[str], env: dict[str, str], log: Path, *options: str) -> Served:
    """`rostui serve --port PORT OPTIONS WORDS...` on a free port, listening when this returns."""
    port = free_port()
    with log.open("w") as out:
        proc = subprocess.Popen(rostui_cmd("serve", "--port", str(port), *options, *words), env=env, cwd=REPO,
                                stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT)
    try:
        wait_for_port(port, timeout=DEADLINE, proc=proc)
        wait_until(lambda: TOKEN_URL.search(log.read_text()) is not None, "serve to print its address",
                   timeout=DEADLINE)
    except BaseException:
        stop_process(proc)
        raise
    match = TOKEN_URL.search(log.read_text())
    assert match is not None
    return Served(proc, port, match[2], log)


@contextmanager
def serving(words: list[str], env: dict[str, str], log: Path, *options: str) -> Iterator[Served]:
    """:func:`start_serve` for the ``with`` block; Ctrl-C on it after."""
    served = start_serve(words, env, log, *options)
    try:
        yield served
    finally:
        served.stop()


class Loop:
    """An asyncio loop on a thread of its own: tests submit coroutines and wait for their results."""

    def __init__(self) -> None:
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, daemon=True)
        self.thread.start()

    def run(self, coro: Coroutine[Any, Any, T], timeout: float = DEADLINE) -> T:
        """Run ``coro`` on the loop; its result."""
        return asyncio.run_coroutine_threadsafe(coro, self.loop).result(timeout)

    def close(self) -> None:
        """Stop the loop and its thread."""
        self.loop.call_soon_threadsafe(self.loop.stop)
        self.thread.join(5)


@pytest.fixture
def loop() -> Iterator[Loop]:
    """An event loop thread for the tabs."""
    tabs_loop = Loop()
    try:
        yield tabs_loop
    finally:
        tabs_loop.close()


class Tab:
    """One session of the page's protocol: ``["stdin", text]``, ``["resize", {...}]`` up; screen bytes down."""

    def __init__(self, loop: Loop, port: int, *, token: str | None, width: object = 80, height: object = 24,
                 origin: str | None = None, host: str | None = None) -> None:
        self.loop = loop
        self.port = port
        self.token = token
        self.size = (width, height)
        self.headers = {k: v for k, v in (("Origin", origin), ("Host", host)) if v is not None}
        self.received = bytearray()
        self.dropped = 0
        self.frames = 0
        self.close_code: int | None = None
        self.close_reason = ""
        self.status: int | None = None
        self.session: Any = None
        self.ws: Any = None
        self.reader: asyncio.Task[None] | None = None

    def open(self) -> bool:
        """Open the websocket; False (with :attr:`status`) when the server refused the handshake."""
        return self.loop.run(self._open())

    async def _open(self) -> bool:
        import aiohttp

        self.session = aiohttp.ClientSession()
        query = {"width": str(self.size[0]), "height": str(self.size[1])}
        if self.token is not None:
            query["token"] = self.token
        try:
            self.ws = await self.session.ws_connect(f"http://127.0.0.1:{self.port}/ws", params=query,
                                                    headers=self.headers, max_msg_size=0)
        except aiohttp.WSServerHandshakeError as exc:
            self.status = exc.status
            await self.session.close()
            return False
        self.status = 101
        self.reader = asyncio.ensure_future(self._read())
        return True

    async def _read(self) -> None:
        import aiohttp

        kind = aiohttp.WSMsgType
        while True:
            message = await self.ws.receive()
            if message.type == kind.BINARY:
                self.received += message.data
                self.frames += 1
                if len(self.received) > 1 << 20:  # keep the tail only: what the screen shows now
                    self.dropped += len(self.received) - (1 << 16)
                    del self.received[:-(1 << 16)]
            elif message.type == kind.CLOSE:
                self.close_code, self.close_reason = message.data, message.extra or ""
                break
            elif message.type in (kind.CLOSING, kind.CLOSED, kind.ERROR):
                self.close_code = self.ws.close_code
                break

    def send(self, *envelope: object) -> None:
        """Send one message of the page's protocol (JSON text)."""
        self.send_text(json.dumps(list(envelope)))

    def send_text(self, text: str) -> None:
        """Send one text frame as it is."""
        self.loop.run(self.ws.send_str(text))

    def keys(self, text: str) -> None:
        """Type ``text`` into the app."""
        self.send("stdin", text)

    def resize(self, width: object, height: object) -> None:
        """Tell the app the page's terminal has a new size."""
        self.send("resize", {"width": width, "height": height})

    def mark(self) -> int:
        """A position in the app's output: :meth:`shows` and :meth:`wait_for` can look only past it."""
        return self.dropped + len(self.received)

    def since(self, mark: int) -> bytes:
        """What the app sent after ``mark`` (as much of it as is kept)."""
        return bytes(self.received)[max(0, mark - self.dropped):]

    def shows(self, text: str, mark: int = 0) -> bool:
        """True when ``text`` is in what the app sent (after ``mark``)."""
        return text.encode() in self.since(mark)

    def wait_for(self, text: str, mark: int = 0, timeout: float = DEADLINE) -> None:
        """Wait until ``text`` arrives in the app's output (after ``mark``)."""
        wait_until(lambda: self.shows(text, mark), f"{text!r} from the app", timeout=timeout)

    def help_round(self) -> None:
        """A user's round trip: ``?`` opens the app's help panel, ``?`` closes it again."""
        from rostui.apps.widgets.help import HELP_TITLE

        mark = self.mark()
        self.keys("?")
        self.wait_for(HELP_TITLE.split(" · ")[1], mark)
        mark = self.mark()
        self.keys("?")
        wait_until(lambda: len(self.since(mark)) > 0, "the app to redraw without its help panel", timeout=DEADLINE)

    def closed(self) -> bool:
        """True once the server closed the websocket."""
        return self.reader is not None and self.reader.done()

    def close(self) -> None:
        """Close the tab (the websocket, then the client)."""
        if self.ws is not None:
            self.loop.run(self._close())

    async def _close(self) -> None:
        await self.ws.close()
        if self.reader is not None:
            await asyncio.wait({self.reader}, timeout=5)
        await self.session.close()
