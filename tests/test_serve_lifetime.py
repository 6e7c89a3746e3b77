"""How long the apps of `rostui serve` live: no longer than their tab, and never longer than the server.

The tabs here are websocket clients speaking the page's protocol (tests/serve_helpers.py); the browser's
own view of the same is in tests/test_serve_browser.py.  The app served is `console FILE` (no master needed).
"""

from __future__ import annotations

import os
import signal
from pathlib import Path
from typing import Iterator

import pytest

from rostui.apps.widgets.lifecycle import HANGUP_GRACE

from conftest import wait_until
from console_helpers import write_sample_log
from serve_helpers import Loop, Served, Tab, live, loop, serving  # noqa: F401  (loop is a fixture)

#: The acceptance of issue 30: a tab closed after its first screen leaves no app process within 5 s.
TAB_GONE_WITHIN = 5.0

SHOWS = "divisible by"

#: Seconds serve may take to stop with a deaf app: its grace to quit, SIGTERM's, and time to spare (it waited 35 s).
SERVE_STOPS_WITHIN = 20.0


@pytest.fixture
def served(ros_env: dict[str, str], tmp_path: Path) -> Iterator[Served]:
    """`rostui serve console FILE`."""
    log = write_sample_log(tmp_path / "rosout.log")
    with serving(["console", str(log)], ros_env, tmp_path / "serve.log") as served:
        yield served


def open_tabs(served: Served, loop: Loop, count: int) -> list[Tab]:
    """``count`` tabs, each showing its app's first screen."""
    tabs = [Tab(loop, served.port, token=served.token) for _ in range(count)]
    for tab in tabs:
        assert tab.open(), tab.status
    for tab in tabs:
        tab.wait_for(SHOWS)
    return tabs


def test_tabs_closed_right_after_their_first_screen_leave_no_app(served: Served, loop: Loop) -> None:
    """A page that resizes and closes just after its first bytes (the app still starting): its app ends."""
    for _ in range(3):
        tab = Tab(loop, served.port, token=served.token)
        assert tab.open(), tab.status
        wait_until(lambda: tab.frames > 0, "the app's first bytes")
        tab.resize(137, 45)
        tab.close()
    wait_until(lambda: not served.apps(), lambda: f"no app left: {[p.cmdline() for p in served.apps()]}",
               timeout=TAB_GONE_WITHIN)
    assert served.proc.poll() is None
    tab = open_tabs(served, loop, 1)[0]  # the server still serves
    tab.help_round()
    tab.close()
    assert "Traceback" not in served.output()


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP], ids=lambda s: s.name)
def test_every_stop_signal_ends_serve_and_every_app(served: Served, loop: Loop, stop: signal.Signals) -> None:
    """Ctrl-C, SIGTERM and a hangup (its terminal closed) each end serve and all it started, with two tabs open:
    one app answers, the other is deaf to everything but SIGKILL (stopped)."""
    tabs = open_tabs(served, loop, 2)
    started = served.apps()
    assert len(started) == 2, [p.cmdline() for p in started]
    groups = {p.pid: os.getpgid(p.pid) for p in started}
    assert all(group == pid for pid, group in groups.items()), f"each app leads a process group: {groups}"
    started[1].suspend()
    served.proc.send_signal(stop)
    assert served.proc.wait(timeout=SERVE_STOPS_WITHIN) == 0, served.output()
    wait_until(lambda: not live(started), "every app to end with the server", timeout=10)
    for tab in tabs:
        wait_until(tab.closed, "each page to be told its session ended")
    output = served.output()
    assert "Traceback" not in output, output


def test_apps_end_when_serve_is_killed(served: Served, loop: Loop) -> None:
    """serve killed outright (SIGKILL: no clean-up of its own): its apps hang up as if their terminal closed."""
    open_tabs(served, loop, 2)
    started = served.apps()
    assert len(started) == 2
    served.proc.kill()
    served.proc.wait(timeout=10)
    wait_until(lambda: not live(started), lambda: f"the apps to end: {[p.cmdline() for p in live(started)]}",
               timeout=HANGUP_GRACE + 10)
