"""The engine thread: an asyncio loop (uvloop when installed and wanted) behind the sync API.

User scripts call blocking functions on their own thread; the engine runs the
node's I/O and subscriber callbacks on its loop thread.  A blocking call made
from the engine thread itself (a callback calling a service) runs on a private
loop in a worker thread instead of deadlocking.
"""

from __future__ import annotations

import asyncio
import atexit
import concurrent.futures
import os
import threading
from typing import Any, Awaitable, Callable, Coroutine, TypeVar

T = TypeVar("T")


ENV_LOOP = "ROSTUI_EVENT_LOOP"
"""The environment variable that picks the engine's loop: ``uvloop`` or ``asyncio``; unset, :data:`prefer_uvloop`."""

prefer_uvloop = True
"""Whether an engine runs uvloop (when installed) unless :data:`ENV_LOOP` says otherwise. uvloop loads OpenSSL
at import (5 MB): rospy scripts under ``rostui python`` turn it off to stay light."""


def new_event_loop(uvloop_wanted: bool | None = None) -> asyncio.AbstractEventLoop:
    """A new event loop: uvloop's when installed and wanted (:data:`ENV_LOOP`, else ``uvloop_wanted``, else
    :data:`prefer_uvloop`)."""
    wanted = os.environ.get(ENV_LOOP, "").strip().lower()
    if uvloop_wanted is None:
        uvloop_wanted = prefer_uvloop
    if wanted == "asyncio" or (wanted != "uvloop" and not uvloop_wanted):
        return asyncio.new_event_loop()
    try:
        import uvloop
    except ImportError:
        return asyncio.new_event_loop()
    return uvloop.new_event_loop()


class Engine:
    """Runs one asyncio loop on a daemon thread until stopped, at the latest when the interpreter exits."""

    def __init__(self) -> None:
        self.loop = new_event_loop()
        self._ready = threading.Event()
        self.thread = threading.Thread(target=self._run, name="rostui-engine", daemon=True)
        self.thread.start()
        self._ready.wait()
        # A loop thread still running while the interpreter finalizes can take the GIL back from a uvloop callback
        # after the interpreter's state is freed, and the process dies of SIGSEGV on its way out (a node Ctrl-C'd
        # while messages arrive). Made before its node, the engine is stopped after the node's exit hook
        # (atexit runs the last registered first). A callback that holds the loop past a second is left running.
        atexit.register(self.stop, 1.0)

    def _run(self) -> None:
        asyncio.set_event_loop(self.loop)
        self.loop.call_soon(self._ready.set)
        self.loop.run_forever()

    @property
    def on_engine_thread(self) -> bool:
        """True when the caller runs on the engine's loop thread (a callback)."""
        return threading.current_thread() is self.thread

    def run(self, coro: Coroutine[Any, Any, T], timeout: float | None = None) -> T:
        """Run a coroutine on the engine loop and wait for its result."""
        if self.on_engine_thread:
            coro.close()
            raise RuntimeError("blocking engine call from the engine thread; use run_detached")
        if not self.thread.is_alive():  # stopped (at exit, after its node's shutdown): nothing would run it
            coro.close()
            raise RuntimeError("the node's engine has stopped")
        future = asyncio.run_coroutine_threadsafe(coro, self.loop)
        try:
            return future.result(timeout)
        except concurrent.futures.TimeoutError:
            if future.done():
                raise  # the coroutine's own TimeoutError (the same class since Python 3.11)
            future.cancel()
            raise TimeoutError("operation timed out") from None

    def run_detached(self, make: Callable[[], Awaitable[T]]) -> T:
        """Run a self-contained coroutine on a private loop in a worker thread.

        Used for blocking calls made from the engine thread: the coroutine must
        not use objects bound to the engine loop.
        """
        values: list[T] = []
        errors: list[BaseException] = []

        def work() -> None:
            async def main() -> T:
                return await make()
            try:
                values.append(asyncio.run(main()))
            except BaseException as exc:  # re-raised in the caller's thread
                errors.append(exc)

        worker = threading.Thread(target=work, name="rostui-detached", daemon=True)
        worker.start()
        worker.join()
        if errors:
            raise errors[0]
        return values[0]

    def call_soon(self, fn: Callable[..., Any], *args: Any) -> None:
        """Schedule a plain function on the loop from any thread."""
        self.loop.call_soon_threadsafe(fn, *args)

    def stop(self, timeout: float = 5.0) -> None:
        """Stop the loop and join the thread, waiting at most *timeout* seconds for the callback it runs."""
        if self.loop.is_running():
            self.loop.call_soon_threadsafe(self.loop.stop)
        if not self.on_engine_thread:
            self.thread.join(timeout)
