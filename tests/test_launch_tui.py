"""`rostui launch --tui`, driven with Textual's pilot: the real supervisor runs real node processes.

Each test writes a launch file using the ``tuitest`` package (launch_tui_helpers),
opens the monitor headless, and checks what the table and the log pane show
while nodes run, die, respawn, and are started, stopped and restarted from the
app; after q no process of the launch may be left.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

import psutil

from rostui.launch.process import NodeState

from conftest import until
from launch_tui_helpers import (  # noqa: F401  (tui_env is a fixture)
    cell, log_text, monitor, on_loop, pids_of_launch, still_alive, tui_env, write_launch,
)

SIZE = (120, 36)


async def quit_and_check_gone(pilot, pids: set[int]) -> None:  # type: ignore[no-untyped-def]
    """q: the app leaves once every node has stopped; none of ``pids`` is left."""
    app = pilot.app
    await pilot.press("q")
    await until(lambda: app.supervisor.finished.is_set(), "the launch to shut down", timeout=60)
    await until(lambda: not app.is_running, "the app to leave", timeout=30)
    assert not still_alive(pids), "processes of the launch are left behind"


@on_loop
async def test_table_and_output_of_each_node(tui_env: dict[str, str], tmp_path: Path) -> None:
    """Every node in the table (running, pid, usage, flags); the log pane shows the selected node's output."""
    launch = write_launch(tmp_path / "three.launch", """
  <node pkg="tuitest" type="chatty" name="talker" args="3"/>
  <node pkg="tuitest" type="quiet" name="worker" ns="robot" respawn="true" respawn_delay="2"/>
  <node pkg="tuitest" type="quiet" name="boss" required="true" output="screen"/>""")
    app = monitor(launch)
    async with app.run_test(size=SIZE) as pilot:
        await until(lambda: len(app.rows) == 3 and all(r.state == "running" for r in app.rows.values()),
                    "three running nodes")
        await until(lambda: all(cell(app, n, "cpu") != "-" for n in ("/talker", "/robot/worker", "/boss")),
                    "CPU and memory measured")
        talker = app.supervisor.process_named("/talker")
        assert cell(app, "/talker", "pid") == str(talker.pid)
        assert cell(app, "/talker", "mem").endswith(" MB")
        assert cell(app, "/robot/worker", "flags") == "respawn 2 s"
        assert cell(app, "/boss", "flags") == "required"
        assert cell(app, "/talker", "restarts") == "0"
        await until(lambda: "a warning from chatty" in log_text(app), "the talker's stderr in the log pane")
        text = log_text(app)
        assert "line 1 of 3" in text and "line 3 of 3" in text
        assert f"process[talker-1]: started with pid [{talker.pid}]" in text
        log_file = Path(talker.plan.stdout_log or "")
        assert log_file.read_text().splitlines() == ["line 1 of 3", "line 2 of 3", "line 3 of 3"]
        await pilot.press("down", "down")
        await until(lambda: "quiet is up" in log_text(app), "the boss's output after moving down")
        assert "line 1 of 3" not in log_text(app)
        assert "output of /boss" in str(app.query_one("#log-title").render())
        assert app.supervisor.process_named("/boss").plan.stdout_log is None  # output="screen": no log file
        await pilot.press("l")
        await until(lambda: "logging to" in log_text(app), "the launcher's own output after l")
        assert "started master (in this process)" in log_text(app)
        await quit_and_check_gone(pilot, pids_of_launch(app))
    assert app.return_code == 0


@on_loop
async def test_killed_respawn_node_dies_and_comes_back(tui_env: dict[str, str], tmp_path: Path) -> None:
    """os.kill from outside: the table shows the death (exit code, respawning) and then a new pid, 1 restart."""
    launch = write_launch(tmp_path / "respawn.launch",
                          '<node pkg="tuitest" type="quiet" name="phoenix" respawn="true" respawn_delay="3"/>')
    app = monitor(launch)
    async with app.run_test(size=SIZE) as pilot:
        await until(lambda: app.rows and cell(app, "/phoenix", "state") == "running", "the node running")
        first = int(cell(app, "/phoenix", "pid"))
        os.kill(first, signal.SIGKILL)
        await until(lambda: cell(app, "/phoenix", "state").startswith("respawning in"), "the respawn countdown")
        assert "died: exit code -9, SIGKILL" in cell(app, "/phoenix", "state")
        assert cell(app, "/phoenix", "pid") == "-"
        await until(lambda: cell(app, "/phoenix", "state") == "running", "the node back", timeout=60)
        assert cell(app, "/phoenix", "restarts") == "1"
        second = int(cell(app, "/phoenix", "pid"))
        assert second != first and psutil.pid_exists(second)
        text = log_text(app)
        assert f"[phoenix-1] process has died [pid {first}, exit code -9" in text
        assert f"process[phoenix-1]: restarted with pid [{second}]" in text
        await quit_and_check_gone(pilot, pids_of_launch(app) | {first})


@on_loop
async def test_restart_stop_and_start_from_the_app(tui_env: dict[str, str], tmp_path: Path) -> None:
    """r gives the node a new pid; k stops it (gone, not respawned); s starts it again."""
    launch = write_launch(tmp_path / "control.launch", """
  <node pkg="tuitest" type="quiet" name="first"/>
  <node pkg="tuitest" type="quiet" name="second" respawn="true" required="false"/>""")
    app = monitor(launch, sigint_timeout=5)
    async with app.run_test(size=SIZE) as pilot:
        await until(lambda: len(app.rows) == 2 and all(r.state == "running" for r in app.rows.values()),
                    "both nodes running")
        await pilot.press("down")
        old = int(cell(app, "/second", "pid"))
        await pilot.press("r")
        await until(lambda: cell(app, "/second", "pid") not in ("-", str(old)), "a new pid after r")
        assert cell(app, "/second", "state") == "running"
        assert cell(app, "/second", "restarts") == "1"
        await until(lambda: "restart /second: done" in str(app.query_one("#status").render()), "the notice")
        await pilot.press("s")
        assert "/second is already running" in str(app.query_one("#status").render())
        await until(lambda: not still_alive({old}), "the old process gone")
        new = int(cell(app, "/second", "pid"))
        await pilot.press("k")
        await until(lambda: cell(app, "/second", "state") == "stopped", "the node stopped after k")
        assert cell(app, "/second", "pid") == "-"
        await until(lambda: not still_alive({new}), "its process gone")
        await pilot.pause(2.0)  # a respawn node stopped on request stays stopped
        assert cell(app, "/second", "state") == "stopped"
        assert app.supervisor.process_named("/second").state is NodeState.STOPPED
        await pilot.press("s")
        await until(lambda: cell(app, "/second", "state") == "running", "the node running after s")
        assert int(cell(app, "/second", "pid")) not in (old, new)
        assert cell(app, "/first", "restarts") == "0"
        assert "stopped on request" in log_text(app)
        await quit_and_check_gone(pilot, pids_of_launch(app))


@on_loop
async def test_died_node_and_node_that_cannot_start(tui_env: dict[str, str], tmp_path: Path) -> None:
    """A node exiting with 3 shows 'died (exit code 3)'; a missing launch-prefix program shows 'cannot start'."""
    launch = write_launch(tmp_path / "broken.launch", """
  <node pkg="tuitest" type="quiet" name="survivor"/>
  <node pkg="tuitest" type="dies" name="quitter" args="3"/>
  <node pkg="tuitest" type="quiet" name="framed" launch-prefix="no-such-terminal -e"/>""")
    app = monitor(launch)
    async with app.run_test(size=SIZE) as pilot:
        await until(lambda: len(app.rows) == 3 and cell(app, "/quitter", "state") == "died (exit code 3)",
                    "the quitter's death")
        assert cell(app, "/framed", "state") == "cannot start"
        assert cell(app, "/survivor", "state") == "running"
        await pilot.press("down")
        await until(lambda: "giving up with 3" in log_text(app), "the quitter's stderr")
        assert "[quitter-2] process has died" in log_text(app)
        await pilot.press("down")
        await until(lambda: "'no-such-terminal' is not installed" in log_text(app), "why framed cannot start")
        await pilot.press("up", "s")  # the died node can be started again from the app
        await until(lambda: app.supervisor.process_named("/quitter").starts == 2, "a second start")
        await until(lambda: cell(app, "/quitter", "state") == "died (exit code 3)", "its second death")
        assert cell(app, "/quitter", "restarts") == "1"
        await quit_and_check_gone(pilot, pids_of_launch(app))


@on_loop
async def test_required_node_death_shuts_the_launch_down(tui_env: dict[str, str], tmp_path: Path) -> None:
    """Killing a required node stops every node, as roslaunch does; the screen says why and q leaves with 1."""
    launch = write_launch(tmp_path / "required.launch", """
  <node pkg="tuitest" type="quiet" name="boss" required="true"/>
  <node pkg="tuitest" type="quiet" name="helper"/>""")
    app = monitor(launch)
    async with app.run_test(size=SIZE) as pilot:
        await until(lambda: len(app.rows) == 2 and all(r.state == "running" for r in app.rows.values()),
                    "both nodes running")
        pids = pids_of_launch(app)
        os.kill(int(cell(app, "/boss", "pid")), signal.SIGTERM)
        await until(lambda: app.supervisor.finished.is_set(), "the launch to shut down")
        await until(lambda: cell(app, "/helper", "state") == "stopped", "the helper stopped")
        assert not still_alive(pids)
        banner = str(app.query_one("#banner").render())
        assert "required node /boss has died (exit code -15)" in banner and "q leaves" in banner
        assert app.is_running  # the screen stays to show what happened
        await pilot.press("q")
        await until(lambda: not app.is_running, "the app to leave")
    assert app.return_code == 1


@on_loop
async def test_shutdown_escalates_for_a_node_ignoring_sigint(tui_env: dict[str, str], tmp_path: Path) -> None:
    """Ctrl-C: SIGINT, then SIGTERM after the timeout; the stubborn node and its child are gone afterwards."""
    launch = write_launch(tmp_path / "stubborn.launch", """
  <node pkg="tuitest" type="stubborn" name="mule"/>
  <node pkg="tuitest" type="quiet" name="polite"/>""")
    app = monitor(launch, sigint_timeout=1.0, sigterm_timeout=1.0)
    async with app.run_test(size=SIZE) as pilot:
        mule = app.supervisor.processes
        await until(lambda: len(app.rows) == 2 and all(r.state == "running" for r in app.rows.values()),
                    "both nodes running")
        await until(lambda: len(app.supervisor.process_named("/mule").alive_tree()) == 2, "the mule's child")
        pids = pids_of_launch(app)
        await pilot.press("ctrl+c")
        await until(lambda: "shutting down" in str(app.query_one("#banner").render()), "the shutdown line")
        await until(lambda: app.supervisor.finished.is_set(), "the launch to shut down", timeout=60)
        await until(lambda: not app.is_running, "the app to leave")
        assert not still_alive(pids)
        assert mule and "did not stop on SIGINT: sent SIGTERM" in "\n".join(
            line.text for line in app.supervisor.launch_output.since(0))


@on_loop
async def test_scrolling_back_stops_following(tui_env: dict[str, str], tmp_path: Path) -> None:
    """In the log pane, Page Up stops following (the title says so); End follows the newest line again."""
    launch = write_launch(tmp_path / "long.launch", '<node pkg="tuitest" type="chatty" name="long" args="300"/>')
    app = monitor(launch)
    async with app.run_test(size=(100, 24)) as pilot:
        await until(lambda: "a warning from chatty" in log_text(app), "all of the node's output")
        log = app.log_view
        await until(lambda: app.following and log.scroll_y == log.max_scroll_y > 0, "the pane at its newest line")
        await pilot.press("tab", "pageup")
        await until(lambda: not app.following, "following stopped by Page Up")
        assert "paused" in str(app.query_one("#log-title").render())
        await until(lambda: log.scroll_y < log.max_scroll_y, "the pane scrolled back")
        await pilot.press("end")
        await until(lambda: app.following and log.scroll_y == log.max_scroll_y, "following again after End")
        assert "following" in str(app.query_one("#log-title").render())
        await quit_and_check_gone(pilot, pids_of_launch(app))


@on_loop
async def test_a_burst_of_output_shows_its_newest_lines(tui_env: dict[str, str], tmp_path: Path) -> None:
    """More lines between two refreshes than the pane takes at once: the newest are shown, the rest counted."""
    launch = write_launch(tmp_path / "burst.launch", '<node pkg="tuitest" type="quiet" name="burst"/>')
    app = monitor(launch)
    async with app.run_test(size=SIZE) as pilot:
        await until(lambda: "quiet is up" in log_text(app), "the node's first line")
        output = app.supervisor.process_named("/burst").output
        for n in range(1, 1201):  # as if the node wrote 1200 lines within one refresh
            output.append("stdout", f"burst {n}")
        await until(lambda: "burst 1200" in log_text(app), "the newest line of the burst")
        text = log_text(app)
        assert "… 700 lines skipped: more than 500 arrived between two refreshes …" in text
        assert "burst 700\n" not in text + "\n" and "burst 701" in text
        await quit_and_check_gone(pilot, pids_of_launch(app))


@on_loop
async def test_a_refresh_while_the_screen_is_torn_down_draws_nothing(tui_env: dict[str, str],
                                                                     tmp_path: Path) -> None:
    """The refresh timer is stopped after the screens on quit: a tick between the two finds no table and
    must not crash the app (a loaded CI machine met that tick)."""
    launch = write_launch(tmp_path / "one.launch", """
  <node pkg="tuitest" type="quiet" name="worker"/>""")
    app = monitor(launch)
    async with app.run_test(size=SIZE) as pilot:
        await until(lambda: len(app.rows) == 1, "the node's row")
        pids = pids_of_launch(app)
        await app.query_one("#nodes").remove()
        app.refresh_view()
        await quit_and_check_gone(pilot, pids)
    assert app.return_code == 0
