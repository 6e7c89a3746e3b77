"""PublishEditor: choose a topic and type, edit the YAML of a message, send it once or at a rate.

The editor only edits; its :class:`PublishHost` (the monitor app) publishes
(``send_once``, ``toggle_repeat``) and reports back through :meth:`PublishEditor.say`.
"""

from __future__ import annotations

from typing import ClassVar, Protocol

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Horizontal, Vertical
from textual.markup import escape
from textual.screen import ModalScreen
from textual.widgets import Input, Label, Static, TextArea

from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.line_input import LineInput
from rostui.core.msg import Message
from rostui.models.monitor.publish import PublishError, message_template

__all__ = ["PublishEditor", "PublishHost", "EDITOR_KEYS"]

#: Key help at the bottom of the editor.
EDITOR_KEYS = "ctrl+s send once · ctrl+r start/stop at rate · Enter on type: new template · Esc close"


class PublishHost(Protocol):
    """What publishes for the editor: the monitor app."""

    def topic_type(self, topic: str) -> str | None:
        """The type the master knows for ``topic``."""
        ...

    def send_once(self, editor: "PublishEditor") -> None:
        """Publish the editor's message once."""
        ...

    def toggle_repeat(self, editor: "PublishEditor") -> None:
        """Start or stop publishing the editor's message at its rate."""
        ...


class PublishEditor(ModalScreen[None]):
    """The publish form for ``topic`` of ``type_name`` (either may be empty); ``host`` publishes."""

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("escape", "close", "close", priority=True),
        Binding("ctrl+s", "send", "send once", priority=True),
        Binding("ctrl+r", "repeat", "start/stop at rate", priority=True),
    ]

    def __init__(self, host: PublishHost, topic: str, type_name: str) -> None:
        super().__init__()
        self.host = host
        self.initial_topic = topic
        self.initial_type = type_name
        self.msg_class: type[Message] | None = None

    def compose(self) -> ComposeResult:
        """Topic and type, the YAML, the rate, a status line and the keys."""
        with Vertical(id="editor"):
            with Horizontal(classes="field-row"):
                yield Label("topic", classes="field-label")
                yield LineInput(self.initial_topic, placeholder="/topic", id="pub-topic")
            with Horizontal(classes="field-row"):
                yield Label("type", classes="field-label")
                yield LineInput(self.initial_type, placeholder="pkg/Type", id="pub-type")
            yield TextArea("", id="pub-yaml", show_line_numbers=True, tab_behavior="indent")
            with Horizontal(classes="field-row"):
                yield Label("rate Hz", classes="field-label")
                yield LineInput("", placeholder="empty: once (latched)", id="pub-rate")
            yield Static(id="pub-status")
            yield Static(EDITOR_KEYS, id="pub-keys")

    def on_mount(self) -> None:
        """Fill the template for the initial type; focus where typing is needed first."""
        self.query_one("#editor").border_title = "publish"
        if self.initial_type:
            self.load_template()
        focus_now(self.query_one("#pub-yaml" if self.initial_topic and self.initial_type else "#pub-topic"))

    @property
    def topic(self) -> str:
        """The topic as typed."""
        return self.query_one("#pub-topic", Input).value

    @property
    def type_name(self) -> str:
        """The type as typed."""
        return self.query_one("#pub-type", Input).value.strip()

    @property
    def yaml_text(self) -> str:
        """The message as typed."""
        return self.query_one("#pub-yaml", TextArea).text

    @property
    def rate_text(self) -> str:
        """The rate as typed."""
        return self.query_one("#pub-rate", Input).value

    def load_template(self) -> bool:
        """Put the default message of the typed type in the YAML box; False (and say why) for an unknown type."""
        try:
            self.msg_class, text = message_template(self.type_name)
        except PublishError as exc:
            self.msg_class = None
            self.say(str(exc), error=True)
            return False
        self.query_one("#pub-yaml", TextArea).load_text(text + "\n")
        self.say(f"template for {self.type_name}")
        return True

    def say(self, text: str, *, error: bool = False) -> None:
        """One line in the editor's status."""
        status = self.query_one("#pub-status", Static)
        status.update(escape(text))
        status.set_class(error, "error")

    @on(Input.Submitted, "#pub-type")
    def _type_entered(self) -> None:
        if self.load_template():
            self.query_one("#pub-yaml", TextArea).focus()

    @on(Input.Submitted, "#pub-topic")
    def _topic_entered(self) -> None:
        known = self.host.topic_type(self.topic.strip())
        if known and not self.type_name:
            self.query_one("#pub-type", Input).value = known
            self.load_template()
        self.query_one("#pub-type", Input).focus()

    def action_send(self) -> None:
        """ctrl+s: publish the message once."""
        self.host.send_once(self)

    def action_repeat(self) -> None:
        """ctrl+r: publish at the typed rate, or stop doing so."""
        self.host.toggle_repeat(self)

    def action_close(self) -> None:
        """Esc: back to the table (repeating publishers keep going)."""
        self.dismiss(None)
