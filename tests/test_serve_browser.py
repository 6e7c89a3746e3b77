"""`rostui serve` in a real headless browser (Debian's chromium through chromium-driver).

The test starts a master, serves turtlesim (with a ROS argument, to see that the
served command keeps its words) on a free port, opens the page, reads the app off
xterm.js, drives the turtle with the Up arrow and sees it move on the page and on
the master.  Closing the page's tab quits that app (its node leaves the master); a second
page's app quits when the server gets Ctrl-C, which then exits 0 with nothing left.
Every other app opens in a page too, `?` opens and closes its help, and `q` ends it with all it started.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path
from typing import Iterator

import psutil
import pytest

from rostui.apps.widgets.help import HELP_TITLE

from bag_view_helpers import write_counts
from browser_helpers import DEADLINE, XtermPage, headless_chromium
from cli_helpers import rostui
from conftest import REPO, free_port, rostui_cmd, stop_process, wait_for_port, wait_until
from launch_tui_helpers import BUILTIN_SHARE, make_package, write_launch

SCREEN_POSE = re.compile(r"turtle1 x (-?\d+\.\d+) y (-?\d+\.\d+)")
ECHO_X = re.compile(r"^x: (-?[\d.e+-]+)$", re.M)
NODE = "/browser_sim"


def serve(words: list[str], env: dict[str, str], log: Path) -> tuple[subprocess.Popen, int]:
    """`rostui serve --port PORT WORDS...` on a free port, listening when this returns; output to ``log``."""
    port = free_port()
    with log.open("w") as out:
        proc = subprocess.Popen(rostui_cmd("serve", "--port", str(port), *words), env=env, cwd=REPO,
                                stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT)
    try:
        wait_for_port(port, timeout=DEADLINE, proc=proc)
    except BaseException:
        stop_process(proc)
        raise
    return proc, port


@pytest.fixture
def served(rostui_core: subprocess.Popen, ros_env: dict[str, str],
           tmp_path: Path) -> Iterator[tuple[subprocess.Popen, int, Path]]:
    """`rostui serve turtlesim __name:=browser_sim` on a free port: the process, its port and its output file."""
    log = tmp_path / "serve.log"
    proc, port = serve(["turtlesim", f"__name:={NODE[1:]}"], ros_env, log)
    try:
        yield proc, port, log
    finally:
        stop_process(proc, timeout=60)


def master_x(env: dict[str, str]) -> float:
    """turtle1's x as the master's /turtle1/pose publisher says (one message through `rostui topic echo`)."""
    r = rostui(["topic", "echo", "-n", "1", "/turtle1/pose"], env)
    assert r.returncode == 0, r.stderr
    match = ECHO_X.search(r.stdout)
    assert match is not None, r.stdout
    return float(match[1])


def screen_x(page: XtermPage) -> float | None:
    """turtle1's x on the page's status line, if it shows."""
    match = SCREEN_POSE.search(page.screen())
    return None if match is None else float(match[1])


def nodes(env: dict[str, str]) -> list[str]:
    """The master's nodes (`rostui node list`)."""
    r = rostui(["node", "list"], env)
    assert r.returncode == 0, r.stderr
    return r.stdout.split()


def app_processes(server: subprocess.Popen) -> list[psutil.Process]:
    """The processes the server runs (one app a page)."""
    return [p for p in psutil.Process(server.pid).children(recursive=True) if p.status() != psutil.STATUS_ZOMBIE]


def gone(processes: list[psutil.Process]) -> bool:
    """True when none of ``processes`` runs any more."""
    return not any(p.is_running() and p.status() != psutil.STATUS_ZOMBIE for p in processes)


@pytest.mark.timeout(300)
def test_turtlesim_in_a_browser_drives_the_turtle_and_stops_cleanly(
        served: tuple[subprocess.Popen, int, Path], ros_env: dict[str, str], tmp_path: Path) -> None:
    server, port, log = served
    url = f"http://localhost:{port}/"
    announced = log.read_text()
    assert f"at {url[:-1]} " in announced, announced
    assert f"ssh -L {port}:localhost:{port} " in announced, announced

    with headless_chromium() as driver:
        page = XtermPage(driver)
        page.open(url)
        page.wait_for("turtle1 x ")
        page.wait_for(f"master {ros_env['ROS_MASTER_URI']}")  # the served app has this shell's ROS_MASTER_URI
        wait_until(lambda: NODE in nodes(ros_env), f"{NODE} on the master (the served command keeps __name:=)")
        assert page.screenshot(tmp_path / "serve_turtlesim.png").read_bytes().startswith(b"\x89PNG")
        start_screen, start_master = screen_x(page), master_x(ros_env)
        assert start_screen is not None and abs(start_screen - start_master) < 0.01, page.screen()

        from selenium.webdriver.common.keys import Keys

        page.press(Keys.ARROW_UP)
        wait_until(lambda: (screen_x(page) or 0.0) > start_screen + 0.5, "the turtle to move on the page",
                   timeout=DEADLINE)
        assert master_x(ros_env) > start_master + 0.5
        page.screenshot(tmp_path / "serve_turtlesim_moved.png")
        apps = app_processes(server)
        assert len(apps) == 1, apps

        page.close_tab()  # its app quits and its node leaves the master
        wait_until(lambda: gone(apps), "the app of the closed page to exit", timeout=DEADLINE)
        wait_until(lambda: NODE not in nodes(ros_env), f"{NODE} to unregister when its page closed")
        assert server.poll() is None

        page.open(url)  # a new page, a new app
        page.wait_for("turtle1 x ")
        wait_until(lambda: NODE in nodes(ros_env), f"{NODE} on the master again")
        apps = app_processes(server)
        assert len(apps) == 1, apps
        server.send_signal(2)  # Ctrl-C with the page still open
        assert server.wait(timeout=60) == 0, log.read_text()
        assert gone(apps), [p.cmdline() for p in apps if p.is_running()]
        assert NODE not in nodes(ros_env)
        wait_until(page.closed, "the page to say its session ended", timeout=DEADLINE)
    output = log.read_text()
    assert "Traceback" not in output and "ERROR" not in output, output
    with pytest.raises(OSError):
        wait_for_port(port, timeout=0.5)


#: Each other app (bag view and launch get their file in the test), and what its first screen shows.
APPS = {
    "graph": (["graph", "--show-debug"], "/rosout"),
    "console": (["console"], "FATAL"),
    "loggers": (["loggers"], "/rosout"),
    "monitor": (["monitor"], "/rosout_agg"),
    "bag view": (["bag", "view"], "/count"),
    "launch --tui": (["launch", "--tui"], "quiet is up"),
}


@pytest.mark.timeout(240)
@pytest.mark.parametrize("app", list(APPS))
def test_every_app_opens_in_a_browser_shows_its_help_and_q_ends_it(app: str, rostui_core: subprocess.Popen,
                                                     ros_env: dict[str, str], tmp_path: Path) -> None:
    words, shows = APPS[app]
    env = {**ros_env, "ROS_PACKAGE_PATH": f"{BUILTIN_SHARE}:{make_package(tmp_path / 'pkgs')}"}
    if app == "bag view":
        words = [*words, str(write_counts(tmp_path / "counts.bag"))]
    if app == "launch --tui":
        quiet = write_launch(tmp_path / "quiet.launch", '<node pkg="tuitest" type="quiet" name="quiet"/>')
        words = [*words, str(quiet)]
    log = tmp_path / "serve.log"
    server, port = serve(words, env, log)
    try:
        with headless_chromium() as driver:
            page = XtermPage(driver)
            page.open(f"http://localhost:{port}/")
            page.wait_for(shows)
            page.wait_for("q quit")
            started = app_processes(server)  # the app, and for launch --tui its node
            assert len(started) == (2 if app == "launch --tui" else 1), [p.cmdline() for p in started]
            page.press("?")  # the help panel opens over the app, and closes again
            page.wait_for(HELP_TITLE)
            page.screenshot(tmp_path / f"serve_{app.replace(' ', '_')}_help.png")
            page.press("?")
            wait_until(lambda: not page.shows(HELP_TITLE), f"{app}'s help panel to close", timeout=DEADLINE)
            page.screenshot(tmp_path / f"serve_{app.replace(' ', '_')}.png")
            page.press("q")
            wait_until(page.closed, "the page to say its session ended after q", timeout=DEADLINE)
            wait_until(lambda: gone(started), f"{app} and what it started to exit after q", timeout=DEADLINE)
        assert server.poll() is None
        server.send_signal(2)
        assert server.wait(timeout=60) == 0
    finally:
        stop_process(server)
    output = log.read_text()
    assert "Traceback" not in output and "ERROR" not in output, output
