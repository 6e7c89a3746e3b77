"""The bag inspector's picture: the registered view (rostui/apps/view/registry.py) of the message under the cursor.

When the selected message's type has a view (an image...), the view is
mounted at the top of the inspector, above the message's text, and shown
that message; another topic or type replaces it, a type without a view
removes it.  A view draws its type by name, so a message recorded with
another version of that type (the bag's own definition: another md5sum) is
not given to it: one line says so and the message is shown as text only.

A message of rostui's version of its type is read as `rostui view` reads it
(:mod:`rostui.models.sensors.lazy_msg`: numeric arrays as views of the
bag's bytes, arrays of messages read when asked), so a scan of ten million
ranges is neither turned into ten million floats for its picture nor for
its text (:func:`inspected_text`: each array cut to its first items).  A
message that cannot be read so (another version, a type rostui does not
know) is decoded with the bag's definition only up to :data:`MAX_DECODED`.
"""

from __future__ import annotations

from textual.containers import VerticalScroll
from textual.markup import escape
from textual.widget import Widget
from textual.widgets import Static

from rostui.apps.view.registry import TopicView, view_class, viewable
from rostui.core.bag.model import BagError, Connection
from rostui.core.msg import Message, MessageError, foreign_version, md5sum
from rostui.core.msg.spec import shown
from rostui.models.sensors.lazy_msg import LazyDecodeError, LazyMessage, read_message

__all__ = ["InspectorView", "MAX_DECODED", "decode_bag_message", "inspected_message", "inspected_text"]

#: Fewest lines the picture gets in the inspector.
MIN_LINES = 6

#: Largest message (bytes) decoded with a class built from the bag's definition, whose arrays become Python
#: lists (a float32 takes 32 bytes there): larger ones of another version of a type, or of a type rostui does
#: not know, are not decoded (one line says so).
MAX_DECODED = 16 * 1024 * 1024


def decode_bag_message(conn: Connection, data: bytes) -> object:
    """The message, decoded with the type recorded in the bag once checked; :class:`BagError` when it cannot be."""
    from rostui.core.bag.decode import decode_message

    return decode_message(conn, data)


def inspected_message(conn: Connection, data: bytes) -> object:
    """The message as the inspector reads it: lazily when its type is rostui's and recorded with rostui's
    md5sum, else decoded with the bag's definition (:func:`decode_bag_message`); :class:`BagError` when neither
    can read it."""
    try:
        ours = md5sum(conn.type)
    except MessageError:
        ours = None
    if ours is None or conn.md5sum != ours:
        if len(data) > MAX_DECODED:
            raise BagError(f"a {shown(conn.type)} message of {len(data)} B on {shown(conn.topic)} is not "
                           f"rostui's version of its type: not decoded here (more than {MAX_DECODED} B)")
        return decode_bag_message(conn, data)
    try:
        return read_message(conn.type, data)
    except LazyDecodeError as exc:
        raise BagError(f"cannot decode a {shown(conn.type)} message on {shown(conn.topic)}: {exc}") from None


def inspected_text(conn: Connection, data: bytes, *, noarr: bool, cut_above: int) -> str:
    """The message's text: as ``rostopic echo`` prints it (``--noarr`` with ``noarr``) up to ``cut_above``
    bytes; a larger message of rostui's version of its type with each array cut to its first items and its
    length (:func:`~rostui.models.sensors.lazy_text.lazy_text`), any other with its arrays summarised; a line
    saying so for a message with no fields (a blank inspector would look like a fault).
    :class:`BagError` when it cannot be read."""
    from rostui.core.bag.index import message_yaml
    from rostui.core.msg.convert import message_to_yaml
    from rostui.models.sensors.lazy_text import lazy_text

    if len(data) > cut_above:
        msg = inspected_message(conn, data)
        if isinstance(msg, LazyMessage):
            return lazy_text(msg)
        assert isinstance(msg, Message)  # decode_bag_message's
        return message_to_yaml(msg, noarr=True)
    return message_yaml(conn, data, noarr=noarr) or f"(no fields: {conn.type} is an empty message)"


class InspectorView:
    """Keeps the view of the inspected message's type in ``inspector`` (before ``before``), and the line saying
    why a message of a viewable type's name is shown as text only (:attr:`note`)."""

    def __init__(self, inspector: VerticalScroll, before: Widget) -> None:
        self.inspector = inspector
        self.before = before
        self.view: TopicView | None = None
        self.note = Static(classes="inspector-note")
        self.note.display = False
        self._key: tuple[str, str] | None = None

    def show(self, topic: str | None, conn: Connection | None, data: bytes, t_ns: int) -> bool:
        """Show the message in its view; False (and no view) when its type has none or it is another version of
        that type than rostui's (then :attr:`note` says so)."""
        if topic is None or conn is None or not viewable(conn.type):
            self.clear()
            return False
        try:
            msg = inspected_message(conn, data)
        except BagError:
            self.clear()
            raise
        other = None if isinstance(msg, LazyMessage) else foreign_version(msg)  # lazily read: rostui's version
        if other is not None:
            self.clear()
            self._say(f"{other}: shown as text")
            return False
        self._say("")
        if self._key != (topic, conn.type) or self.view is None:
            self.clear()
            self.view = view_class(conn.type).for_bag(topic, classes="inspector-view")
            self.view.styles.height = max(MIN_LINES, self.inspector.size.height - 3)
            self.inspector.mount(self.view, before=self.before)
            self._key = (topic, conn.type)
        view = self.view
        view.call_after_refresh(view.show_message, msg, t_ns / 1e9)
        return True

    def clear(self) -> None:
        """Remove the view and the note."""
        if self.view is not None:
            self.view.remove()
        self.view = None
        self._key = None
        self._say("")

    def _say(self, text: str) -> None:
        """The note line above the message's text (hidden when empty)."""
        if text and not self.note.is_attached:
            self.inspector.mount(self.note, before=self.before)
        self.note.update(escape(text))
        self.note.display = bool(text)
