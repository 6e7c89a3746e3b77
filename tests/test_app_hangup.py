"""A rostui app ends when its terminal goes away (SIGHUP) or it is told to (SIGTERM), however busy its loop is.

Each app runs in a real terminal (a tmux pane); closing the pane is the hangup a closed SSH link or terminal
window gives.  The apps' signal handlers must not wait for the event loop: a loop stuck in a long computation
(a decoder on a huge message) would never run them.  A small app built on the apps' base class whose loop never
comes back stands for any such app; bag view decoding a large message over and over is the real one.
"""

from __future__ import annotations

import os
import shlex
import signal
import sys
import textwrap
from pathlib import Path
from typing import Iterator

import psutil
import pytest

from rostui.apps.widgets.lifecycle import LOOP_GRACE
from rostui.core.bag.files import open_writer
from rostui.core.bag.model import Connection
from rostui.core.msg import get_message_class

from conftest import REPO, wait_until
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "APP_EXIT="

#: An app on the apps' base class whose event loop, once it has drawn, never comes back.
STUCK_APP = textwrap.dedent('''
    import sys
    from pathlib import Path

    from textual.widgets import Static

    from rostui.apps.widgets.app_keys import KeysApp
    from rostui.apps.widgets.lifecycle import quit_on_signals


    class Stuck(KeysApp):
        def compose(self):
            yield Static("about to be stuck")

        def on_mount(self):
            quit_on_signals(self)
            self.set_timer(0.3, self.stick)

        def stick(self):
            Path(sys.argv[1]).write_text(str(__import__("os").getpid()))
            while True:  # a computation on the event loop that does not end
                sum(range(1000))


    Stuck().run()
''')


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 100x30 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("hangup", 100, 30) as pane:
        yield pane


def shell_line(env: dict[str, str], argv: list[str], cwd: Path) -> str:
    """The shell line that runs ``argv`` with the test's environment, then prints its exit status."""
    values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    values["TERM"] = "xterm-256color"
    values["PYTHONPATH"] = str(REPO)
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    return f"cd {shlex.quote(str(cwd))} && env -u COLUMNS -u LINES {assignments} {shlex.join(argv)}; echo {EXIT_MARK}$?"


def ended(pid: int) -> bool:
    """True once ``pid`` is gone (or a zombie)."""
    try:
        return psutil.Process(pid).status() == psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return True


def kill_if_left(pid: int) -> None:
    """SIGKILL ``pid`` if the test left it running."""
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def start_stuck_app(pane: Pane, env: dict[str, str], tmp_path: Path) -> int:
    """Run :data:`STUCK_APP` in ``pane``; its pid once its loop is stuck."""
    script, marker = tmp_path / "stuck_app.py", tmp_path / "stuck.pid"
    script.write_text(STUCK_APP)
    pane.type(shell_line(env, [sys.executable, str(script), str(marker)], tmp_path))
    wait_until(lambda: marker.exists() and marker.read_text().isdigit(), "the app's loop to be stuck")
    return int(marker.read_text())


def test_a_hangup_ends_an_app_whose_loop_never_comes_back(pane: Pane, ros_env: dict[str, str],
                                                          tmp_path: Path) -> None:
    pid = start_stuck_app(pane, ros_env, tmp_path)
    try:
        pane.close()  # the terminal goes away: SIGHUP
        wait_until(lambda: ended(pid), "the app to end after its terminal went away", timeout=LOOP_GRACE + 10)
    finally:
        kill_if_left(pid)


def test_sigterm_ends_an_app_whose_loop_never_comes_back(pane: Pane, ros_env: dict[str, str],
                                                          tmp_path: Path) -> None:
    pid = start_stuck_app(pane, ros_env, tmp_path)
    try:
        os.kill(pid, signal.SIGTERM)
        pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}{128 + signal.SIGTERM}"),
                        "the app to end with status 143 (a stuck loop cannot clean up)")
    finally:
        kill_if_left(pid)


def write_busy_bag(path: Path, messages: int = 4, names: int = 1_000_000) -> Path:
    """``/joints`` (sensor_msgs/JointState), each message ``names`` empty joint names: slow to decode, small."""
    JointState = get_message_class("sensor_msgs/JointState")
    data = JointState(name=[""] * names).serialize()
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/joints", "sensor_msgs/JointState", JointState._md5sum,
                                     JointState._full_text, "/j"))
    for i in range(messages):
        writer.write(0, 1_700_000_000_000_000_000 + i * 50_000_000, data)
    writer.close()
    return path


def test_a_hangup_ends_bag_view_while_it_decodes(pane: Pane, ros_env: dict[str, str], tmp_path: Path) -> None:
    """bag view plays, in a loop, messages that take its loop a while each to decode; the terminal goes away."""
    bag = write_busy_bag(tmp_path / "busy_joints.mcap")
    pane.type(shell_line(ros_env, [sys.executable, "-m", "rostui", "bag", "view", "--no-publish", "--play", "--loop",
                                   bag.name], tmp_path))
    pane.wait_until(lambda: pane.shows("/joints", "PLAYING"), "bag view playing /joints")
    app = next(p for p in psutil.process_iter(["cmdline"]) if str(bag.name) in " ".join(p.info["cmdline"] or [])
               and "bag" in (p.info["cmdline"] or []))
    start = app.cpu_times().user
    wait_until(lambda: app.cpu_times().user > start + 1.0, "bag view to spend CPU decoding")
    try:
        pane.close()
        # it ends once it has released what it holds, not HANGUP_GRACE later (Textual cannot restore a dead screen)
        wait_until(lambda: ended(app.pid), "bag view to end after its terminal went away", timeout=LOOP_GRACE + 5)
    finally:
        kill_if_left(app.pid)


def test_sigterm_quits_graph_as_q_does(pane: Pane, rostui_core: object, ros_env: dict[str, str],
                                       tmp_path: Path) -> None:
    """`kill` on the graph app: it leaves as q does (exit status 0, the shell's screen given back)."""
    pane.type(shell_line(ros_env, [sys.executable, "-m", "rostui", "graph", "--show-debug"], tmp_path))
    pane.wait_until(lambda: pane.shows("/rosout"), "the graph")
    app = next(p for p in psutil.process_iter(["cmdline"])
               if (p.info["cmdline"] or [])[-3:] == ["rostui", "graph", "--show-debug"])
    try:
        app.terminate()
        pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}0"), "graph to quit with status 0")
        assert "/rosout" not in pane.screen(), "the app's screen was left behind"
    finally:
        kill_if_left(app.pid)
