"""FormApp: rqt_publisher and rqt_service_caller in the terminal (``rostui publish``, ``rostui call``).

A message type (or a service's request) is laid out as a table of its fields, each an expression: a number,
a list, ``sin(t)``, ``i``, ``now``. Enter edits a field; ←/→ move a number's slider. ctrl+s publishes one
message or calls the service and shows the response; ctrl+r publishes at the typed rate until
pressed again, following the sliders as they move. ctrl+w saves the form as YAML and ctrl+o loads one
(``--form FILE`` opens it). Nothing is registered with the master or sent before ctrl+s or ctrl+r, and the
master line says where things go.
"""

from __future__ import annotations

import asyncio
from functools import partial
from pathlib import Path
from typing import Any, ClassVar

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Horizontal, Vertical
from textual.widgets import DataTable, Input, Label, Log, Static
from textual.worker import Worker

from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.line_input import LineInput
from rostui.apps.widgets.notice import Notice
from rostui.core.masteruri import master_uri_from_env
from rostui.core.msg import Message
from rostui.core.one_line import exception_line
from rostui.models.message_form.expression import ExpressionError, evaluate
from rostui.models.message_form.form_file import (
    FormFileError, FormSpec, apply_spec, read_form, spec_of, write_form,
)
from rostui.models.message_form.rows import MessageForm
from rostui.models.message_form.sender import SendFailed, ServiceCaller, TopicSender
from rostui.models.monitor.publish import PublishError, Repeater, check_topic, parse_rate, publish_class

from .panels import FieldTable, LineScreen, detail_text

__all__ = ["FormApp", "run_app"]

PUBLISH_KEYS = key_line("Enter edit  ←→ slider  ctrl+s send  ctrl+r at rate  ctrl+w save  ctrl+o load")
CALL_KEYS = key_line("Enter edit  ←→ slider  ctrl+s call  ctrl+w save  ctrl+o load")


class FormApp(ReleasesOnExit, KeysApp):
    """The form of ``kind`` ``publish`` (a topic ``name`` of ``type_name``, at ``rate``) or ``call`` (a service
    ``name``); ``form_path`` is the file ctrl+w saves to, read first when it exists."""

    CSS_PATH = Path(__file__).with_name("app.tcss")

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("ctrl+s", "send", "publish once / call", priority=True),
        Binding("ctrl+r", "repeat", "publish at the rate, or stop", priority=True),
        Binding("ctrl+w", "save", "save the form as YAML"),  # not over a field's own ctrl+w (delete a word)
        Binding("ctrl+o", "load", "load a form from YAML"),
    ]
    KEY_NOTES: ClassVar[tuple[tuple[str, str], ...]] = (
        ("Enter", "on a field: edit its expression (numbers, lists, sin(t), i, t, now, 'text')"),
        ("←/→", "move a number's slider a hundredth of its range (shift: a tenth)"),
        ("Tab", "between the topic, type, rate and the fields (where q types a q)"),
    )

    def __init__(self, kind: str = "publish", *, name: str = "", type_name: str = "", rate: float | None = None,
                 form_path: Path | None = None, master_uri: str | None = None) -> None:
        super().__init__()
        self.kind = kind
        self.initial = (name, type_name, rate)
        self.form_path = form_path
        self.master_uri = master_uri or master_uri_from_env()
        self.form: MessageForm | None = None
        self.srv_class: Any = None
        self.sender = TopicSender(self.master_uri)
        self.caller = ServiceCaller(self.master_uri)
        self.repeater: Repeater | None = None
        self.ready = asyncio.Event()
        self.starting: Worker[None] | None = None
        self.sending: Worker[None] | None = None
        self.loading: Worker[bool] | None = None
        self.title = f"rostui {kind}"

    # -- layout ------------------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """Where to send and what, the fields, the log, the notices and the keys."""
        name, type_name, rate = self.initial
        with Horizontal(id="target"):
            yield Label("topic" if self.kind == "publish" else "service", classes="field-label")
            yield LineInput(name, placeholder="/topic" if self.kind == "publish" else "/service", id="name",
                            compact=True)
            if self.kind == "publish":
                yield Label("type", classes="field-label")
                yield LineInput(type_name, placeholder="pkg/Type", id="type", compact=True)
                yield Label("rate Hz", classes="field-label")
                yield LineInput("" if rate is None else f"{rate:g}", placeholder="once", id="rate", compact=True)
        with Vertical(id="fields-panel", classes="panel"):
            yield FieldTable(id="fields")
            yield Static("", id="detail", markup=False)
        with Vertical(id="log-panel", classes="panel"):
            yield Log(id="log", max_lines=2000)
        yield Notice(id="status")
        yield Notice(id="master")
        yield Static(PUBLISH_KEYS if self.kind == "publish" else CALL_KEYS, id="keys")

    def on_mount(self) -> None:
        """Titles; the form file, the type or the service; the focus where typing is needed first."""
        self.query_one("#fields-panel").border_title = "Fields"
        self.query_one("#log-panel").border_title = "Sent" if self.kind == "publish" else "Response"
        self.say_master()
        self.set_interval(0.5, self._watch_repeater, name="repeat-watch")
        quit_on_signals(self)
        self.starting = self.run_worker(partial(self._start), name="start", exit_on_error=False)

    async def _start(self) -> None:
        try:
            if self.form_path is not None and self.form_path.exists():
                await self.load_form(self.form_path)
            elif self.kind == "publish" and self.type_input.value.strip():
                self.new_form(self.type_input.value.strip())
            elif self.name_input.value.strip():
                await self._name_entered()
            else:
                self.status("type a topic and Enter" if self.kind == "publish" else "type a service and Enter")
        finally:
            self.ready.set()
        focus_now(self.query_one(FieldTable) if self.form is not None else self.name_input)

    @property
    def name_input(self) -> Input:
        """The topic or service field."""
        return self.query_one("#name", Input)

    @property
    def type_input(self) -> Input:
        """The type field (publish only)."""
        return self.query_one("#type", Input)

    @property
    def table(self) -> FieldTable:
        """The fields."""
        return self.query_one(FieldTable)

    def status(self, text: str, kind: str = "info") -> None:
        """The status line."""
        self.query_one("#status", Notice).say(text, kind)

    def master_label(self) -> str:
        """How the master is named on screen (its URI)."""
        return self.master_uri

    def say_master(self) -> None:
        """Where sends go, and that nothing is sent before it is asked for."""
        if self.repeater is not None and self.repeater.running:
            doing = f"publishing {self.repeater.topic} at {self.repeater.rate:g} Hz (ctrl+r stops)"
        elif self.kind == "publish":
            doing = "nothing is published until ctrl+s or ctrl+r"
        else:
            doing = "nothing is called until ctrl+s"
        self.query_one("#master", Notice).say(f"master {self.master_label()} · {doing}")

    # -- the form ----------------------------------------------------------------------------------
    def show_form(self, form: MessageForm, what: str) -> None:
        """Make ``form`` the one edited (a rate publishing the last one stops)."""
        if self.repeater is not None and self.repeater.running and form is not self.form:
            self.repeater.stop()
            self.repeater = None
            self.say_master()
        self.form = form
        self.table.show_rows(form.rows)
        self.query_one("#fields-panel").border_title = f"Fields · {what}"
        self._show_detail()

    def new_form(self, type_name: str) -> bool:
        """A fresh form of the message ``type_name`` (False, and why, for a type not known here)."""
        try:
            cls = publish_class(type_name)
        except PublishError as exc:
            self.status(str(exc), "error")
            return False
        self.show_form(MessageForm.of(cls), type_name)
        self.status(f"a {type_name}: Enter edits a field, ctrl+s sends it")
        return True

    async def service_form(self, service: str) -> bool:
        """A fresh form of ``service``'s request, its type asked of the service."""
        self.status(f"asking {service} for its type…")
        try:
            self.srv_class = await self.caller.service_class(service)
        except SendFailed as exc:
            self.srv_class, self.form = None, None
            self.table.show_rows([])
            self.query_one("#fields-panel").border_title = "Fields"
            self.status(str(exc), "error")
            return False
        self.show_form(MessageForm.of(self.srv_class._request_class), self.srv_class._type)
        self.status(f"{service} [{self.srv_class._type}]: Enter edits a field, ctrl+s calls it")
        return True

    async def load_form(self, path: Path) -> bool:
        """Read the form at ``path`` into the app (False, and the file:line of the problem, if it cannot be)."""
        try:
            spec = read_form(path)
            if spec.kind != self.kind:
                raise FormFileError(f"{path}: a `{spec.kind}` form: open it with `rostui {spec.kind} --form`")
            if not await self._form_of_spec(spec):
                return False
            assert self.form is not None
            apply_spec(self.form, spec)
        except FormFileError as exc:
            self.status(str(exc), "error")
            return False
        self.show_form(self.form, self.form.type_name)
        self.status(f"loaded {path}")
        return True

    async def _form_of_spec(self, spec: FormSpec) -> bool:
        self.name_input.value = spec.name
        if self.kind == "call":
            return await self.service_form(spec.name)
        self.type_input.value = spec.type_name
        self.query_one("#rate", Input).value = "" if spec.rate is None else f"{spec.rate:g}"
        return self.new_form(spec.type_name)

    def _show_detail(self) -> None:
        self.query_one("#detail", Static).update(detail_text(self.table.highlighted))

    @on(DataTable.RowHighlighted, "#fields")
    def _highlighted(self) -> None:
        self._show_detail()

    @on(FieldTable.Nudged)
    def _nudged(self) -> None:
        self._show_detail()

    @on(DataTable.RowSelected, "#fields")
    def _edit(self) -> None:
        row = self.table.highlighted
        if row is None:
            return

        def check(text: str) -> str | None:
            if row.type == "string" or not text.strip():
                return None if text.strip() or row.type == "string" else "an expression is needed"
            try:
                evaluate(text, {"i": 0, "t": 0.0, "now": 0})
            except ExpressionError as exc:
                return str(exc)
            return None

        def done(text: str | None) -> None:
            if text is not None:
                row.expression = text.strip() if row.type != "string" else text
                self.table.refresh_row_of(row)
                self._show_detail()
                self.status(f"{row.path} = {row.expression}")

        about = f"{row.path} ({row.type}): an expression; i is the message's number, t seconds since the first"
        self.push_screen(LineScreen(row.path, about, row.expression, check), done)

    @on(Input.Submitted, "#name")
    async def _name_entered(self) -> None:
        name = self.name_input.value.strip()
        if self.kind == "call":
            if name and await self.service_form(name):
                focus_now(self.table)
            return
        if not self.type_input.value.strip():
            known = await self._topic_type(name)
            if known:
                self.type_input.value = known
                if self.new_form(known):
                    focus_now(self.table)
                return
        focus_now(self.type_input)

    async def _topic_type(self, topic: str) -> str | None:
        try:
            await self.caller.start()
            types = await self.caller.node.master_call("getTopicTypes")
        except Exception as exc:  # the master's failure is said, whatever it was
            self.status(f"the master does not answer: {exc}", "error")
            return None
        try:
            resolved = check_topic(topic)
        except PublishError:
            return None
        return next((str(kind) for name, kind in types if name == resolved), None)

    @on(Input.Submitted, "#type")
    def _type_entered(self) -> None:
        if self.new_form(self.type_input.value.strip()):
            focus_now(self.table)

    # -- sending -----------------------------------------------------------------------------------
    def action_send(self) -> None:
        """ctrl+s: publish one message, or call the service."""
        if self.form is None:
            self.status("no form yet: type a " + ("topic and type" if self.kind == "publish" else "service"), "error")
            return
        if self.repeater is not None and self.repeater.running:
            self.status(f"publishing {self.repeater.topic} at a rate: ctrl+r stops it first", "error")
            return
        self.sending = self.run_worker(partial(self._send_once), group="send", exit_on_error=False)

    async def _send_once(self) -> None:
        assert self.form is not None
        log = self.query_one("#log", Log)
        try:
            if self.kind == "call":
                service = self.name_input.value.strip()
                if self.srv_class is None:
                    raise SendFailed("no service yet: type one and Enter")
                self.status(f"calling {service}…")
                response = await self.caller.call(service, self.srv_class, self.form)
                log.clear()
                log.write_line(f"call #{self.caller.calls} of {service}:")
                log.write_lines(f"  {line}" for line in _yaml(response).splitlines())
                self.status(f"{service} answered", "ok")
                return
            topic = self._topic()
            msg = await self.sender.send(topic, self.form)
            log.write_line(f"#{self.sender.sent} on {topic}: " + _one_line_yaml(msg))
            self.status(f"published one {self.form.type_name} on {topic} (latched)", "ok")
        except (SendFailed, PublishError) as exc:
            self.status(str(exc), "error")
        except Exception as exc:  # a value the wire refuses (a float32 of 1e39): said, and the app goes on
            self.status(f"not sent: {type(exc).__name__}: {exception_line(exc)}", "error")

    def _topic(self) -> str:
        topic = check_topic(self.name_input.value)
        if self.form is not None and self.type_input.value.strip() != self.form.type_name:
            raise PublishError(f"the type says {self.type_input.value.strip()!r} but the form is a "
                               f"{self.form.type_name}: Enter on the type makes a new form")
        return topic

    def action_repeat(self) -> None:
        """ctrl+r: publish at the typed rate, or stop."""
        if self.kind != "publish":
            self.status("a service is called once per ctrl+s", "error")
            return
        if self.repeater is not None and self.repeater.running:
            self.repeater.stop()
            self.status(f"stopped after {self.repeater.sent} messages", "ok")
            self.repeater = None
            self.say_master()
            return
        if self.form is None:
            self.status("no form yet: type a topic and a type", "error")
            return
        try:
            topic = self._topic()
            rate = parse_rate(self.query_one("#rate", Input).value)
        except PublishError as exc:
            self.status(str(exc), "error")
            return
        if rate is None:
            self.status("type a rate in Hz first (ctrl+s sends one message)", "error")
            return
        self.sender.restart_count()

        async def send() -> None:
            if self.form is not None:  # the form on screen: edits and sliders go into the next message
                await self.sender.send(topic, self.form)

        self.repeater = Repeater(topic, rate, send)
        self.repeater.start()
        self.status(f"publishing {topic} at {rate:g} Hz: sliders and edits apply to the next message")
        self.say_master()

    def _watch_repeater(self) -> None:
        repeater = self.repeater
        if repeater is None:
            return
        if repeater.running:
            self.query_one("#fields-panel").border_subtitle = f"{repeater.sent} sent at {repeater.rate:g} Hz"
        elif repeater.error:
            self.status(f"stopped: {repeater.error}", "error")
            self.repeater = None
            self.say_master()

    # -- files -------------------------------------------------------------------------------------
    def _default_path(self) -> str:
        if self.form_path is not None:
            return str(self.form_path)
        name = self.name_input.value.strip().strip("/").replace("/", "_") or self.kind
        return f"{name}.form.yaml"

    def action_save(self) -> None:
        """ctrl+w: save the form as YAML (asks for the file's path)."""
        if self.form is None:
            self.status("no form to save yet", "error")
            return

        def done(text: str | None) -> None:
            if text is None:
                return
            assert self.form is not None
            rate = None
            if self.kind == "publish":
                try:
                    rate = parse_rate(self.query_one("#rate", Input).value)
                except PublishError:
                    rate = None
            spec = spec_of(self.form, self.kind, self.name_input.value.strip(), self.form.type_name if
                           self.kind == "publish" else self.srv_class._type, rate)
            path = Path(text.strip()).expanduser()
            try:
                write_form(spec, path)
            except OSError as exc:
                self.status(f"{path}: {exc.strerror or exc}", "error")
                return
            self.form_path = path
            self.status(f"saved {path}", "ok")

        self.push_screen(LineScreen("save the form", "the file to write (YAML)", self._default_path(),
                                    lambda text: None if text.strip() else "a file name is needed"), done)

    def action_load(self) -> None:
        """ctrl+o: load a form saved as YAML (asks for the file's path)."""
        def done(text: str | None) -> None:
            if text is not None:
                self.loading = self.run_worker(
                    partial(self.load_form, Path(text.strip()).expanduser()), group="load", exit_on_error=False)

        self.push_screen(LineScreen("load a form", "the file to read (YAML, as ctrl+w writes it)",
                                    self._default_path(),
                                    lambda text: None if Path(text.strip()).expanduser().is_file()
                                    else f"no file {text.strip()!r}"), done)

    async def release(self) -> None:
        """Stop publishing; close the nodes."""
        if self.repeater is not None:
            self.repeater.stop()
        for closing in (self.sender.close(), self.caller.close()):
            try:
                await asyncio.wait_for(closing, 5.0)
            except Exception:  # the process is ending; nothing left to tell the user
                pass


def _yaml(msg: Message) -> str:
    from rostui.core.msg.convert import message_to_yaml

    return message_to_yaml(msg) or "{}"


def _one_line_yaml(msg: Message) -> str:
    from rostui.core.msg.convert import message_to_yaml

    text = message_to_yaml(msg)
    return " ".join(line.strip() for line in text.splitlines()) if text else "{}"


def run_app(kind: str, *, name: str = "", type_name: str = "", rate: float | None = None,
            form_path: Path | None = None) -> int:
    """Run :class:`FormApp` in this terminal; returns the exit status (1 without a TTY)."""
    instead = "rostui topic pub" if kind == "publish" else "rostui service call"
    if terminal_missing(f"rostui {kind}", f"use `{instead}` without one"):
        return 1
    app = FormApp(kind, name=name, type_name=type_name, rate=rate, form_path=form_path)
    app.run()
    return app.return_code or 0
