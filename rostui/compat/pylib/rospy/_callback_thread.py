"""A subscriber's callbacks on a thread of their own, as rospy runs them.

rospy calls a subscriber's callback from that subscription's receiving thread,
so a callback may block: sleep, call a service, make a Publisher and publish
for seconds (ROS Robotics By Example's turtlesim_joy.py drives a 6-second
circle from its joystick callback). rostui's engine calls callbacks on its own
loop thread, where such calls cannot run; this hands each message over to one
thread per Subscriber instead. Messages wait in order; with a *queue_size*
only the newest *queue_size* wait, as rospy drops the oldest.
"""

from __future__ import annotations

import collections
import threading
import traceback
from typing import Any, Callable

__all__ = ["CallbackThread"]


class CallbackThread:
    """Calls *callback* with each argument tuple handed to it, in order, on a daemon thread of its own."""

    def __init__(self, callback: Callable[..., Any], queue_size: int | None, topic: str,
                 report: Callable[[str], None]) -> None:
        self._callback = callback
        self._topic = topic
        self._report = report
        self._waiting: collections.deque[tuple[Any, ...]] = collections.deque(
            maxlen=queue_size if queue_size and queue_size > 0 else None)
        self._wake = threading.Condition()
        self._stopped = False
        self._thread: threading.Thread | None = None

    def __call__(self, *args: Any) -> None:
        """Queue one call (made on the engine thread: never blocks)."""
        with self._wake:
            if self._stopped:
                return
            self._waiting.append(args)
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name=f"rospy-callback {self._topic}", daemon=True)
                self._thread.start()
            self._wake.notify()

    def stop(self) -> None:
        """Drop what waits and end the thread after the call under way, if any."""
        with self._wake:
            self._stopped = True
            self._waiting.clear()
            self._wake.notify()

    def _run(self) -> None:
        while True:
            with self._wake:
                while not self._waiting and not self._stopped:
                    self._wake.wait()
                if self._stopped:
                    return
                args = self._waiting.popleft()
            try:
                self._callback(*args)
            except Exception:  # rospy logs it and goes on with the next message
                self._report(f"bad callback: {self._callback}\n{traceback.format_exc()}")
