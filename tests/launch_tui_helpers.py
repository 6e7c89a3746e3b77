"""Shared pieces of the `rostui launch --tui` tests: a small package of node scripts, launch files, the monitor.

``tuitest`` is a ROS package written into the test's temporary folder, with
shell-script nodes whose behaviour the tests rely on: ``chatty`` prints
numbered lines then waits, ``quiet`` only waits, ``dies`` exits at once with
the status it is given, ``stubborn`` ignores SIGINT and has a child.
"""

from __future__ import annotations

import asyncio
import functools
import os
import re
from pathlib import Path
from typing import Any, Callable, Coroutine

import psutil
import pytest

from rostui.apps.launchmon.app import LaunchMonitorApp
from rostui.apps.launchmon.rows import NodeRow
from rostui.launch.files import LaunchRequest
from rostui.launch.supervisor import SupervisorOptions, keep_quiet, load_supervisor

from conftest import REPO

BUILTIN_SHARE = REPO / "rostui" / "share"

SCRIPTS = {
    "chatty": '#!/bin/sh\n# Prints "line 1".."line N" ($1) on stdout and one line on stderr, then waits.\n'
              'i=1\nwhile [ "$i" -le "$1" ]; do echo "line $i of $1"; i=$((i + 1)); done\n'
              'sleep 0.3\necho "a warning from chatty" >&2\nexec sleep 1000\n',
    "quiet": '#!/bin/sh\n# Says it is up, then waits to be stopped.\necho "quiet is up"\nexec sleep 1000\n',
    "dies": '#!/bin/sh\n# Complains and exits at once with status $1.\necho "giving up with $1" >&2\nexit "$1"\n',
    "stubborn": "#!/bin/sh\n# Ignores SIGINT; its child sleeps too (both must be gone after the shutdown).\n"
                "trap '' INT\nsleep 1000 &\nwhile true; do wait; done\n",
}

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>tuitest</name>
  <version>0.0.1</version>
  <description>Nodes for the launch monitor tests.</description>
  <maintainer email="rostui@example.com">rostui</maintainer>
  <license>BSD</license>
</package>
"""


def make_package(root: Path) -> Path:
    """Write the ``tuitest`` package below ``root``; returns ``root`` (for ROS_PACKAGE_PATH)."""
    package = root / "tuitest"
    (package / "scripts").mkdir(parents=True, exist_ok=True)
    (package / "package.xml").write_text(PACKAGE_XML)
    for name, text in SCRIPTS.items():
        script = package / "scripts" / name
        script.write_text(text)
        script.chmod(0o755)
    return root


def write_launch(path: Path, body: str) -> Path:
    """A launch file whose ``<launch>`` holds ``body``."""
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    return path


@pytest.fixture
def tui_env(ros_env: dict[str, str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    """ros_env plus a package path with rostui's built-ins and ``tuitest`` (also applied to this process)."""
    path = f"{BUILTIN_SHARE}:{make_package(tmp_path / 'pkgs')}"
    monkeypatch.setenv("ROS_PACKAGE_PATH", path)
    return {**ros_env, "ROS_PACKAGE_PATH": path}


def monitor(launch_file: Path, *, sigint_timeout: float = 15.0, sigterm_timeout: float = 2.0,
            **hooks: object) -> LaunchMonitorApp:
    """The monitor app on ``launch_file`` with the options `rostui launch --tui` uses."""
    options = SupervisorOptions(capture=True, handle_signals=False, stay_when_all_ended=True,
                                sigint_timeout=sigint_timeout, sigterm_timeout=sigterm_timeout)
    supervisor = load_supervisor(LaunchRequest([str(launch_file)]), options, reporter=keep_quiet)
    return LaunchMonitorApp(supervisor, title=launch_file.name, period=0.1, **hooks)  # type: ignore[arg-type]


def cell(app: LaunchMonitorApp, node: str, column: str) -> str:
    """The text the table shows for ``node`` (global name) in ``column``."""
    label = app.supervisor.process_named(node).label
    return app.table.get_cell(label, column).plain


def pids_of_launch(app: LaunchMonitorApp) -> set[int]:
    """Every pid of every node's process tree right now."""
    pids: set[int] = set()
    for process in app.supervisor.processes:
        pids.update(p.pid for p in process.alive_tree())
    return pids


def still_alive(pids: set[int]) -> list[int]:
    """The pids of ``pids`` that still run (zombies count as gone)."""
    alive = []
    for pid in pids:
        try:
            if psutil.Process(pid).status() != psutil.STATUS_ZOMBIE:
                alive.append(pid)
        except psutil.Error:
            continue
    return alive


def log_text(app: LaunchMonitorApp) -> str:
    """Every line the log pane holds."""
    return "\n".join(strip.text for strip in app.log_view.lines)


def table_settled(app: LaunchMonitorApp) -> bool:
    """Whether the node table's self-sizing columns are as wide as their widest cell now.

    The DataTable fits a column to changed cells only when its message queue next runs dry: on a busy
    machine a screenshot taken right after a state change can show a column still as wide as an earlier,
    longer state ("starting"). Snapshots wait for this before they are taken."""
    from rich.cells import cell_len
    from textual.widgets.data_table import ColumnKey

    from rostui.apps.launchmon.rows import COLUMNS

    for key, heading, width in COLUMNS:
        if width is None:
            widest = max([cell_len(heading)] + [cell_len(getattr(row, key)) for row in app.rows.values()])
            if app.table.columns[ColumnKey(key)].content_width != widest:
                return False
    return True


def fixed_row(row: NodeRow) -> NodeRow:
    """A row with the columns that differ from run to run (pid, CPU, memory) replaced by fixed text."""
    from dataclasses import replace

    running = row.pid != "-"
    return replace(row, pid="4242" if running else "-", cpu="0.5" if running else "-",
                   mem="12.3 MB" if running else "-")


def fixed_text(tmp_path: Path, env: dict[str, str]) -> Callable[[str], str]:
    """A text hook replacing the master's port, temporary paths, run ids and pids by fixed text."""
    port = env["ROSTUI_TEST_MASTER_PORT"]
    run_id = re.compile(r"[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}")
    pid = re.compile(r"(pid \[?)\d+")

    def hook(text: str) -> str:
        text = text.replace(str(tmp_path), "/tmp/T").replace(f":{port}/", ":11311/")
        text = run_id.sub("RUN-ID", text)
        return pid.sub(r"\g<1>4242", text)

    return hook


def cleanup_pids() -> set[int]:
    """The pids of this test process's descendants (to check that a monitor left none behind)."""
    return {p.pid for p in psutil.Process(os.getpid()).children(recursive=True)}


def on_loop(test: Callable[..., Coroutine[Any, Any, None]]) -> Callable[..., None]:
    """Run an async test function on a fresh event loop (pytest here has no async plugin)."""
    @functools.wraps(test)
    def run(*args: Any, **kwargs: Any) -> None:
        asyncio.run(test(*args, **kwargs))

    return run
