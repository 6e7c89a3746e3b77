"""SVG snapshots of `rostui launch --tui` (stored in snapshots/test_launch_tui_snapshots/).

A real launch runs real node processes (the ``tuitest`` scripts of
launch_tui_helpers) under the real supervisor; the screenshot is taken once
the state to show has been reached.  What differs from run to run is fixed by
the app's hooks: the pid, CPU and memory columns (launch_tui_helpers.fixed_row)
and, in the status line and the log pane, the master's port, temporary paths,
run ids and pids (fixed_text).  Everything else on screen is what the launch
really shows.  Regenerate with ``pytest tests/test_launch_tui_snapshots.py
--snapshot-update`` and look at the SVGs before committing them.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from textual.pilot import Pilot

from rostui.apps.launchmon.app import LaunchMonitorApp

from conftest import until
from launch_tui_helpers import (  # noqa: F401  (tui_env is a fixture)
    cell, fixed_row, fixed_text, log_text, monitor, table_settled, tui_env, write_launch,
)
from textual_snapshots import snapshot  # noqa: F401  (stores SVGs in snapshots/)


@pytest.fixture(autouse=True)
def fixed_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """Truecolor."""
    monkeypatch.setenv("COLORTERM", "truecolor")
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)


def fixed_monitor(launch: Path, tmp_path: Path, env: dict[str, str]) -> LaunchMonitorApp:
    """The monitor on ``launch`` with the varying columns and texts fixed."""
    return monitor(launch, row_hook=fixed_row, text_hook=fixed_text(tmp_path, env))


def test_running_launch(snap_compare, tui_env: dict[str, str], tmp_path: Path) -> None:
    """Three running nodes (one respawn, one required), the first node's output in the log pane."""
    launch = write_launch(tmp_path / "three.launch", """
  <node pkg="tuitest" type="chatty" name="talker" args="3"/>
  <node pkg="tuitest" type="quiet" name="worker" ns="robot" respawn="true" respawn_delay="2"/>
  <node pkg="tuitest" type="quiet" name="boss" required="true" output="screen"/>""")

    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, LaunchMonitorApp)
        await until(lambda: len(app.rows) == 3 and all(r.state == "running" for r in app.rows.values()),
                    "three running nodes")
        await until(lambda: "a warning from chatty" in log_text(app), "the talker's output")
        await until(lambda: table_settled(app), "the node table's columns fitted to their cells")
        await pilot.pause(0.3)

    assert snap_compare(fixed_monitor(launch, tmp_path, tui_env), run_before=run_before, terminal_size=(110, 24))


def test_followed_output(snap_compare, tui_env: dict[str, str], tmp_path: Path) -> None:
    """A node that printed 200 lines, selected: the log pane follows its end."""
    launch = write_launch(tmp_path / "busy.launch", """
  <node pkg="tuitest" type="quiet" name="idle"/>
  <node pkg="tuitest" type="chatty" name="chatterbox" args="200"/>""")

    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, LaunchMonitorApp)
        await until(lambda: len(app.rows) == 2 and all(r.state == "running" for r in app.rows.values()),
                    "both nodes running")
        await pilot.press("down")
        await until(lambda: "a warning from chatty" in log_text(app), "the chatterbox's last line")
        await until(lambda: table_settled(app), "the node table's columns fitted to their cells")
        await pilot.pause(0.3)

    assert snap_compare(fixed_monitor(launch, tmp_path, tui_env), run_before=run_before, terminal_size=(100, 22))


def test_died_node(snap_compare, tui_env: dict[str, str], tmp_path: Path) -> None:
    """A node that exited with status 3 (red, 'died (exit code 3)'), selected, beside one that cannot start."""
    launch = write_launch(tmp_path / "broken.launch", """
  <node pkg="tuitest" type="quiet" name="survivor"/>
  <node pkg="tuitest" type="dies" name="quitter" args="3"/>
  <node pkg="tuitest" type="quiet" name="framed" launch-prefix="no-such-terminal -e"/>""")

    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, LaunchMonitorApp)
        await until(lambda: len(app.rows) == 3 and cell(app, "/quitter", "state") == "died (exit code 3)"
                    and cell(app, "/survivor", "state") == "running", "the quitter's death")
        await pilot.press("down")
        await until(lambda: "process has died" in log_text(app), "the quitter's output")
        await until(lambda: table_settled(app), "the node table's columns fitted to their cells")
        await pilot.pause(0.3)

    assert snap_compare(fixed_monitor(launch, tmp_path, tui_env), run_before=run_before, terminal_size=(110, 20))


def test_running_launch_at_80x24(snap_compare, tui_env: dict[str, str], tmp_path: Path) -> None:
    """One running node in an 80x24 terminal: the key line starts with `? help  q quit`."""
    launch = write_launch(tmp_path / "one.launch", '  <node pkg="tuitest" type="chatty" name="talker" args="3"/>')

    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, LaunchMonitorApp)
        await until(lambda: len(app.rows) == 1 and all(r.state == "running" for r in app.rows.values()),
                    "the running node")
        await until(lambda: "a warning from chatty" in log_text(app), "the talker's output")
        await until(lambda: table_settled(app), "the node table's columns fitted to their cells")
        await pilot.pause(0.3)

    assert snap_compare(fixed_monitor(launch, tmp_path, tui_env), run_before=run_before, terminal_size=(80, 24))
