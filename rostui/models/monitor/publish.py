"""Publishing from the monitor: a YAML template for a type, a message from edited YAML, repeating at a rate.

The template is what ``rostopic pub`` tab completion offers (a default
instance as ``rosmsg-proto`` prints it); the edited text is read as one
YAML document and filled into the message with ``rostopic pub``'s rules
(``now``/``auto`` stamps included).  Every problem is one line; YAML errors
say line and column.
"""

from __future__ import annotations

import asyncio
from dataclasses import dataclass
from typing import Any, Awaitable, Callable

__all__ = ["PublishError", "publish_class", "message_template", "message_from_text", "parse_rate", "check_topic", "Repeater"]


class PublishError(Exception):
    """What is wrong with a publish request, in one line."""


def publish_class(type_name: str) -> Any:
    """The message class of ``type_name``; :class:`PublishError` for an unknown type."""
    from rostui.tools.topic.common import TopicToolError
    from rostui.tools.topic.pub_args import message_class

    try:
        return message_class(type_name.strip())
    except TopicToolError as exc:
        raise PublishError(str(exc)) from None


def message_template(type_name: str) -> tuple[Any, str]:
    """``(class, YAML template)`` of ``type_name``; :class:`PublishError` for an unknown type."""
    from rostui.core.msg.convert import default_yaml_template

    cls = publish_class(type_name)
    return cls, default_yaml_template(cls)


def message_from_text(cls: Any, text: str) -> Any:
    """A ``cls`` message from the YAML ``text`` (empty text: the default message)."""
    import yaml

    from rostui.core.rostime import Time
    from rostui.tools.topic.common import TopicToolError
    from rostui.tools.topic.pub_args import build_message, yaml_error

    try:
        document = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise PublishError(f"YAML error: {yaml_error(exc, 'message')}") from None
    if document is None:
        return cls()
    try:
        return build_message(cls, [document], Time.now())
    except TopicToolError as exc:
        raise PublishError(str(exc)) from None


def parse_rate(text: str) -> float | None:
    """The rate typed in the editor: None for empty (publish once), else a positive number of Hz."""
    text = text.strip()
    if not text:
        return None
    try:
        rate = float(text)
    except ValueError:
        raise PublishError(f"rate must be a number of Hz, not {text!r}") from None
    if not rate > 0 or rate != rate or rate == float("inf"):
        raise PublishError(f"rate must be a positive number of Hz, not {text!r}")
    return rate


@dataclass
class Repeater:
    """Publishes a message ``rate`` times a second through ``send`` until :meth:`stop` (a task on the loop)."""

    topic: str
    rate: float
    send: Callable[[], Awaitable[None]]
    sent: int = 0
    error: str = ""
    _task: asyncio.Task | None = None

    def start(self) -> None:
        """Begin publishing."""
        self._task = asyncio.get_running_loop().create_task(self._run())

    @property
    def running(self) -> bool:
        """True while publishing."""
        return self._task is not None and not self._task.done()

    async def _run(self) -> None:
        loop = asyncio.get_running_loop()
        period = 1.0 / self.rate
        due = loop.time()
        while True:
            try:
                await self.send()
            except Exception as exc:  # the node went away with the master: say so and stop
                self.error = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
                return
            self.sent += 1
            due += period
            delay = due - loop.time()
            if delay < -period:  # fell far behind: do not burst to catch up
                due = loop.time()
                delay = 0.0
            await asyncio.sleep(max(delay, 0.0))

    def stop(self) -> None:
        """Stop publishing."""
        if self._task is not None:
            self._task.cancel()


def check_topic(name: str) -> str:
    """``name`` resolved as ``rostopic pub`` resolves it; :class:`PublishError` for an empty or illegal name."""
    from rostui.core.names import InvalidNameError, validate_name
    from rostui.tools.topic.common import resolve_topic

    name = name.strip()
    if not name:
        raise PublishError("topic name is empty")
    try:
        validate_name(name, "topic")
    except InvalidNameError as exc:
        raise PublishError(str(exc)) from None
    return resolve_topic(name)
