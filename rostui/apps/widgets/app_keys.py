"""KeysApp: the keys every rostui app shares: ``?``/F1 help, Ctrl-C quits, ctrl+p command palette.

Textual binds ctrl+c to a notice ("Do you want to quit? Press ctrl+q") and
ctrl+q to quit; here both run the app's own ``quit`` action, so Ctrl-C leaves
at once with the same clean shutdown as ``q`` (nodes unregistered, files
finished, exit status 0).  These keys are priority bindings: they work over
any screen (the publish editor, the palette, the help itself) and whatever
widget has the focus, except that ``?`` still types a ``?`` into a text field.
While a modal screen is up, the app's other priority keys (graph's Escape
and Tab, turtlesim's Tab) stay out of its way.

A key that opens a line editor (``/`` to search) is a priority binding named in
:attr:`KeysApp.TYPE_AHEAD_ACTIONS`: Textual hands a key to the widget focused when
the key is read, and a plain binding moves the focus only once the key has come
back up from that widget, so what was typed right after ``/`` in the same burst
(type-ahead over SSH, a paste, tmux's send-keys) went to the table behind and ran
its keys.  Such an action never acts while a text field has the keyboard: there
the key is typed.

Quitting, Textual removes the screens' widgets first and then lets the app
handle what is still queued for it: a table's row highlight, a timer's tick.
An app handler then finds its widgets gone (NoMatches); so once shutdown has
begun, KeysApp hands the app's own handlers no more widget messages or ticks.
"""

from __future__ import annotations

from typing import ClassVar

from textual import events
from textual.app import App
from textual.binding import Binding, BindingType
from textual.dom import DOMNode
from textual.message import Message
from textual.notifications import SeverityLevel
from textual.screen import ModalScreen, Screen
from textual.widgets import Input

from rostui.apps.widgets.help import HelpScreen
from rostui.apps.widgets.keys import KeySection, key_sections
from rostui.apps.widgets.palette import KeysProvider

__all__ = ["KeysApp"]

#: App actions that stay live over modal screens.
SHARED_ACTIONS = frozenset({"help", "quit", "command_palette"})


class KeysApp(App[int]):
    """Base of every rostui app: help panel, Ctrl-C as ``q``, and a palette of the app's own actions.

    :attr:`KEY_NOTES` lists keys an app reads without a binding (keys, description).
    """

    ENABLE_COMMAND_PALETTE = True
    COMMANDS = {KeysProvider}
    COMMAND_PALETTE_BINDING = "ctrl+p"

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("question_mark", "help", "help", priority=True),
        Binding("f1", "help", "help", show=False, priority=True),
        Binding("ctrl+c", "quit", "quit", show=False, priority=True),
        Binding("ctrl+q", "quit", "quit", show=False, priority=True),
    ]

    KEY_NOTES: ClassVar[tuple[tuple[str, str], ...]] = ()

    TYPE_AHEAD_ACTIONS: ClassVar[frozenset[str]] = frozenset()
    """Actions that open a line editor, bound with ``priority=True``; refused while a text field has the keyboard."""

    _listing_keys = False

    def key_notes(self) -> tuple[tuple[str, str], ...]:
        """Keys this app reads without a binding, as (keys, description); :attr:`KEY_NOTES` by default."""
        return self.KEY_NOTES

    def keys_for(self, screen: Screen[object]) -> list[KeySection]:
        """The keys ``screen`` answers to now (over a modal screen, the shared app keys too)."""
        extra: list[tuple[DOMNode, Binding]] = []
        if screen.is_modal:
            extra = [(self, binding) for _key, binding in self._bindings
                     if binding.priority and binding.action in SHARED_ACTIONS]
        self._listing_keys = True  # list what the screen's keys do, whatever screen is on top now
        try:
            return key_sections(screen, self.key_notes(), extra)
        finally:
            self._listing_keys = False

    def action_help(self) -> None:
        """?/F1: open the help panel over the current screen (again: close it)."""
        if isinstance(self.screen, HelpScreen):
            self.screen.dismiss(None)
            return
        self.push_screen(HelpScreen(self.keys_for(self.screen)))

    def notify(self, message: str, *, title: str = "", severity: SeverityLevel = "information",
               timeout: float | None = None, markup: bool = False) -> None:
        """Textual's toast, plain text unless ``markup`` is asked for: notices quote names, paths, reasons and
        exceptions, and one with brackets in it ("[/teleop_turtle]") is not markup (Textual raised MarkupError
        and the app ended)."""
        super().notify(message, title=title, severity=severity, timeout=timeout, markup=markup)

    async def _on_message(self, message: Message) -> None:
        if not self._running and comes_after_the_widgets(message):
            return
        await super()._on_message(message)

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """Over a modal screen only the shared keys act here; the modal screen has the rest."""
        stack = self.screen_stack
        if not self._listing_keys and stack and isinstance(stack[-1], ModalScreen) and action not in SHARED_ACTIONS:
            return False
        return not self.typing_in_a_field(action)

    def typing_in_a_field(self, action: str) -> bool:
        """Whether ``action`` opens a line editor (:attr:`TYPE_AHEAD_ACTIONS`) while a text field has the keyboard:
        then its key is typed there instead."""
        return action in self.TYPE_AHEAD_ACTIONS and not self._listing_keys and isinstance(self.focused, Input)


def comes_after_the_widgets(message: Message) -> bool:
    """Whether ``message``, handled once shutdown has begun, would reach app code about widgets already gone:
    a widget's message (a row highlighted, an input changed) or a timer's tick.  Textual's own messages and
    the other events (Unmount among them) still go through."""
    if isinstance(message, events.Timer):
        return True
    return not isinstance(message, events.Event) and not type(message).__module__.startswith("textual.messages")
