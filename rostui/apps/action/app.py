"""ActionApp: axclient and rqt_action in the terminal: the action servers on the master, a goal sent to one.

Left, the action servers (asked again every second). Right, the selected action's goal as YAML, filled with its
type's defaults, to edit; ctrl+s sends it, and the log under it shows the goal's status changes, each feedback and
the result; ctrl+x cancels the goal running. Nothing is sent unless ctrl+s asks for it; the status line says which
action a goal goes to.
"""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any, ClassVar

from textual import events
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Horizontal, Vertical
from textual.widgets import Log, OptionList, Static, TextArea

from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.name_list import NameList
from rostui.apps.widgets.notice import Notice
from rostui.core.master_errors import MasterUnreachableError
from rostui.core.masteruri import master_uri_from_env
from rostui.models.actions import ActionsSource, GoalFailed, goal_template
from rostui.tools.action import STATUS_NAMES

__all__ = ["ActionApp", "run_app"]

KEYS = key_line("ctrl+s send goal  ctrl+x cancel  Tab actions/goal")
#: The key line while the goal editor has focus, where q and ? are typed into the goal.
EDITING_KEYS = "Tab back to the actions (q and ? type here)  ctrl+s send goal  ctrl+x cancel"


class ActionApp(ReleasesOnExit, KeysApp):
    """The action servers on the master; *action* is the one selected first (``rostui action`` ACTION)."""

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui action"

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("ctrl+s", "send", "send the goal to the selected action", priority=True),
        Binding("ctrl+x", "cancel", "cancel the goal running", priority=True),
    ]
    KEY_NOTES: ClassVar[tuple[tuple[str, str], ...]] = (
        ("↑/↓", "choose an action (its goal template fills the editor)"),
        ("Tab", "between the actions and the goal editor (where q types a q)"),
    )

    def __init__(self, *, master_uri: str | None = None, action: str | None = None, period: float = 1.0) -> None:
        super().__init__()
        self.master_uri = master_uri or master_uri_from_env()
        self.wanted = action
        self.period = period
        self.source = ActionsSource(self.master_uri)
        self.selected: str | None = None
        self.running = False
        self.master_lost = False
        self.polls = 0
        self.started = asyncio.Event()

    def compose(self) -> ComposeResult:
        """Actions beside the goal editor and its log, the notices, the master line and the keys."""
        with Horizontal(id="panels"):
            with Vertical(id="actions-panel", classes="panel"):
                yield NameList(id="actions")
                yield Notice(id="actions-notice")
            with Vertical(id="goal-panel", classes="panel"):
                yield TextArea("", id="goal", language=None, tab_behavior="focus")
                yield Log(id="progress", max_lines=2000)
                yield Notice(id="goal-notice")
        yield Notice(id="master")
        yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Titles and first notices; start asking the master."""
        self.query_one("#actions-panel").border_title = "Actions"
        self.query_one("#goal-panel").border_title = "Goal"
        self.notice("actions").say("asking the master…")
        self.notice("goal").say("select an action")
        self.say_master()
        self.query_one(NameList).focus()
        self.run_worker(self._poll(), name="poll", exit_on_error=False)
        quit_on_signals(self)

    def on_descendant_focus(self, event: events.DescendantFocus) -> None:
        """The key line for where the keys go now: in the goal editor, q and ? are text."""
        self.query_one("#keys", Static).update(EDITING_KEYS if event.widget.id == "goal" else KEYS)

    def notice(self, name: str) -> Notice:
        """The notice under ``actions`` or ``goal``, or the ``master`` line."""
        return self.query_one("#master" if name == "master" else f"#{name}-notice", Notice)

    def master_label(self) -> str:
        """How the master is named on screen (its URI)."""
        return self.master_uri

    def say_master(self) -> None:
        """The master line: where goals go, or that the master does not answer."""
        if self.master_lost:
            self.notice("master").say(f"master {self.master_label()} does not answer: asking again", "error")
            return
        goes = f" · ctrl+s sends a goal to {self.selected}" if self.selected else " · nothing is sent until ctrl+s"
        self.notice("master").say(f"master {self.master_label()}{goes}")

    async def _poll(self) -> None:
        await self.source.start()
        self.started.set()
        while True:
            try:
                await self.source.refresh()
                self.master_lost = False
            except MasterUnreachableError:
                self.master_lost = True
            self.polls += 1
            self._show_actions()
            await asyncio.sleep(self.period)

    def _show_actions(self) -> None:
        names = [action.name for action in self.source.actions]
        self.query_one(NameList).show_names(names, self.selected)
        if self.master_lost:
            self.notice("actions").say("no master", "error")
        else:
            self.notice("actions").say(f"{len(names)} action server{'' if len(names) == 1 else 's'}" if names
                                       else "no action server")
        if self.selected is None and names:
            self.select(self.wanted if self.wanted in names else names[0])
        elif self.wanted and self.selected is None and self.source.read:
            self.notice("goal").say(f"{self.wanted} is not on the master (yet)")
        self.say_master()

    def select(self, name: str) -> None:
        """Make ``name`` the selected action: its goal template in the editor."""
        action = self.source.action(name)
        if action is None or name == self.selected:
            return
        self.selected, self.wanted = name, None
        self.query_one(NameList).highlight_name(name)
        self.query_one("#goal-panel").border_title = f"Goal · {name} [{action.type or '?'}]"
        try:
            self.query_one("#goal", TextArea).load_text(goal_template(action.type) + "\n" if action.type else "")
            self.notice("goal").say("edit the goal, ctrl+s sends it" if action.type else
                                    f"the master names no type for {name}", "info" if action.type else "error")
        except GoalFailed as exc:
            self.query_one("#goal", TextArea).load_text("")
            self.notice("goal").say(str(exc), "error")
        self.say_master()

    def on_option_list_option_highlighted(self, event: OptionList.OptionHighlighted) -> None:
        """Highlighting an action selects it."""
        if event.option.id:
            self.select(event.option.id)

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        """Enter on an action: go to its goal (at once: keys typed right after Enter edit the goal)."""
        if event.option.id:
            self.select(event.option.id)
        self.set_focus(self.query_one("#goal", TextArea))
        if self.selected and self.notice("goal").kind != "error":
            self.notice("goal").say("editing the goal: ctrl+s sends it, Tab goes back to the actions")

    # -- goals -----------------------------------------------------------------------------------
    def action_send(self) -> None:
        """ctrl+s: send the goal in the editor to the selected action."""
        action = self.source.action(self.selected) if self.selected else None
        if action is None:
            self.notice("goal").say("select an action first", "error")
            return
        if self.running:
            self.notice("goal").say("a goal is running: ctrl+x cancels it first", "error")
            return
        self.running = True
        self.notice("goal").say(f"sending the goal to {action.name}…")
        self.run_worker(self._send(action, self.query_one("#goal", TextArea).text), group="goal",
                        exit_on_error=False)

    async def _send(self, action: Any, text: str) -> None:
        log = self.query_one("#progress", Log)
        try:
            outcome = await self.source.send(action, text, on_feedback=self._feedback, on_status=self._status)
        except GoalFailed as exc:
            self.notice("goal").say(str(exc), "error")
            return
        finally:
            self.running = False
        log.write_line("result:")
        log.write_lines(f"  {line}" for line in _yaml(outcome.result).splitlines())
        said = f"goal {outcome.status_name}" + (f": {outcome.text}" if outcome.text else "")
        self.notice("goal").say(said, "ok" if outcome.status == 3 else "error")

    def _status(self, state: int, text: str) -> None:
        session = self.source.session
        if state == 1 and session is not None:
            self.query_one("#progress", Log).write_line(f"goal {session.goal_id}")
        self.query_one("#progress", Log).write_line(f"status: {STATUS_NAMES.get(state, state)}"
                                                    + (f" ({text})" if text else ""))
        self.notice("goal").say(f"goal {STATUS_NAMES.get(state, state)}")

    def _feedback(self, msg: Any) -> None:
        log = self.query_one("#progress", Log)
        log.write_line("feedback:")
        log.write_lines(f"  {line}" for line in _yaml(msg).splitlines())

    def action_cancel(self) -> None:
        """ctrl+x: ask the server to stop the goal running."""
        if self.source.cancel():
            self.notice("goal").say("cancel sent: waiting for the server's answer")
        else:
            self.notice("goal").say("no goal is running", "error")

    async def release(self) -> None:
        """Close the goal session and the node."""
        try:
            await asyncio.wait_for(self.source.close(), 5.0)
        except Exception:  # the process is ending; nothing left to tell the user
            pass


def _yaml(msg: Any) -> str:
    from rostui.core.msg.convert import message_to_yaml

    return message_to_yaml(msg) or "{}"


def run_app(action: str | None = None) -> int:
    """Run :class:`ActionApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui action", "use `rostui action send` without one"):
        return 1
    app = ActionApp(action=action)
    app.run()
    return app.return_code or 0
