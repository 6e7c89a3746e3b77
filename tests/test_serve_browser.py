"""`rostui serve` in a real headless browser (Debian's chromium through chromium-driver), one for the module.

The test starts a master, serves turtlesim (with a ROS argument, to see that the
served command keeps its words) on a free port, opens the address serve printed
(its token included), reads the app off xterm.js, drives the turtle with the Up
arrow and sees it move on the page and on the master.  Closing the page's tab quits
that app (its node leaves the master); a second page's app quits when the server
gets Ctrl-C, which then exits 0 with nothing left.  Every other app opens in a page
too, `?` opens and closes its help, and `q` ends it with all it started.  A page of
another site cannot open a session, even in a browser that holds the cookie; a tab
closed right after its first screen leaves no app.
"""

from __future__ import annotations

import re
import subprocess
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any, Iterator

import psutil
import pytest

from rostui.apps.widgets.help import HELP_TITLE

from bag_view_helpers import write_counts
from browser_helpers import DEADLINE, XtermPage, headless_chromium
from cli_helpers import rostui
from conftest import free_port, wait_for_port, wait_until
from console_helpers import write_sample_log
from launch_tui_helpers import BUILTIN_SHARE, make_package, write_launch
from serve_helpers import Served, live, serving, start_serve

SCREEN_POSE = re.compile(r"turtle1 x (-?\d+\.\d+) y (-?\d+\.\d+)")
ECHO_X = re.compile(r"^x: (-?[\d.e+-]+)$", re.M)
NODE = "/browser_sim"


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """One headless chromium for every test of the module (each test opens its own pages)."""
    with headless_chromium() as driver:
        yield driver


@pytest.fixture
def served(rostui_core: subprocess.Popen, ros_env: dict[str, str], tmp_path: Path) -> Iterator[Served]:
    """`rostui serve turtlesim __name:=browser_sim` on a free port."""
    with serving(["turtlesim", f"__name:={NODE[1:]}"], ros_env, tmp_path / "serve.log") as served:
        yield served


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


def gone(processes: list[psutil.Process]) -> bool:
    """True when none of ``processes`` runs any more."""
    return not live(processes)


@pytest.mark.timeout(300)
def test_turtlesim_in_a_browser_drives_the_turtle_and_stops_cleanly(
        served: Served, browser: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    server = served.proc
    announced = served.output()
    assert f"listening on 127.0.0.1:{served.port}; open {served.url}" in announced, announced
    assert "The token is required" in announced, announced
    assert f"ssh -L {served.port}:localhost:{served.port} " in announced, announced

    page = XtermPage(browser)
    page.open(served.url)
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
    apps = served.apps()
    assert len(apps) == 1, apps

    page.close_tab()  # its app quits and its node leaves the master
    wait_until(lambda: gone(apps), "the app of the closed page to exit", timeout=DEADLINE)
    wait_until(lambda: NODE not in nodes(ros_env), f"{NODE} to unregister when its page closed")
    assert server.poll() is None

    page.open(f"http://localhost:{served.port}/")  # a new page, a new app: the cookie holds the token now
    page.wait_for("turtle1 x ")
    wait_until(lambda: NODE in nodes(ros_env), f"{NODE} on the master again")
    apps = served.apps()
    assert len(apps) == 1, apps
    server.send_signal(2)  # Ctrl-C with the page still open
    assert server.wait(timeout=60) == 0, served.output()
    assert gone(apps), [p.cmdline() for p in apps if p.is_running()]
    assert NODE not in nodes(ros_env)
    wait_until(page.closed, "the page to say its session ended", timeout=DEADLINE)
    output = served.output()
    assert "Traceback" not in output and "ERROR" not in output, output
    with pytest.raises(OSError):
        wait_for_port(served.port, timeout=0.5)


#: Each other app (bag view and launch get their file in the test), and what its first screen shows.
APPS = {
    "graph": (["graph", "--show-debug"], "/rosout"),
    "console": (["console"], "FATAL"),
    "loggers": (["loggers"], "/rosout"),
    "monitor": (["monitor"], "/rosout_agg"),
    "bag view": (["bag", "view"], "/count"),
    "launch --tui": (["launch", "--tui"], "quiet is up"),
    "view": (["view", "/rosout"], "/rosout"),
    "reconfigure": (["reconfigure"], "no reconfigure server"),
    "diagnostics": (["diagnostics"], "no status yet"),
    "top": (["top"], "/rosout"),
    "action": (["action"], "no action server"),
    "publish": (["publish", "/serve_words", "std_msgs/String"], "Fields · std_msgs/String"),
    "call": (["call", "/rosout/get_loggers"], "Fields · roscpp/GetLoggers"),
}


@pytest.mark.timeout(240)
@pytest.mark.parametrize("app", list(APPS))
def test_every_app_opens_in_a_browser_shows_its_help_and_q_ends_it(app: str, rostui_core: subprocess.Popen,
                                                                   browser: Any, ros_env: dict[str, str],
                                                                   tmp_path: Path) -> None:
    words, shows = APPS[app]
    env = {**ros_env, "ROS_PACKAGE_PATH": f"{BUILTIN_SHARE}:{make_package(tmp_path / 'pkgs')}"}
    if app == "bag view":
        words = [*words, str(write_counts(tmp_path / "counts.bag"))]
    if app == "launch --tui":
        quiet = write_launch(tmp_path / "quiet.launch", '<node pkg="tuitest" type="quiet" name="quiet"/>')
        words = [*words, str(quiet)]
    served = start_serve(words, env, tmp_path / "serve.log")
    try:
        page = XtermPage(browser)
        page.open(served.url)
        page.wait_for(shows)
        page.wait_for("q quit")
        started = served.apps()  # the app, and for launch --tui its node
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
        assert served.proc.poll() is None
        served.proc.send_signal(2)
        assert served.proc.wait(timeout=60) == 0
    finally:
        served.stop()
    output = served.output()
    assert "Traceback" not in output and "ERROR" not in output, output


@pytest.fixture
def console(ros_env: dict[str, str], tmp_path: Path) -> Iterator[Served]:
    """`rostui serve console FILE` (a rosout.log: no master needed)."""
    log = write_sample_log(tmp_path / "rosout.log")
    with serving(["console", str(log)], ros_env, tmp_path / "serve.log") as served:
        yield served


#: A page of another site: it opens a websocket to the server (and says how that went in its title).
FOREIGN_PAGE = """<!DOCTYPE html><html><head><title>waiting</title></head><body><script>
const socket = new WebSocket("ws://localhost:{port}/ws?width=80&height=24");
socket.onopen = () => {{ document.title = "opened"; }};
socket.onclose = (event) => {{ if (document.title !== "opened") document.title = "refused " + event.code; }};
</script></body></html>"""


class ForeignSite:
    """A web server on another port of this machine (another origin), serving :data:`FOREIGN_PAGE`."""

    def __init__(self, target_port: int) -> None:
        body = FOREIGN_PAGE.format(port=target_port).encode()

        class Handler(BaseHTTPRequestHandler):
            def do_GET(self) -> None:  # noqa: N802 (http.server's name)
                self.send_response(200)
                self.send_header("Content-Type", "text/html")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            def log_message(self, *args: object) -> None:
                pass

        self.port = free_port()
        self.server = ThreadingHTTPServer(("127.0.0.1", self.port), Handler)
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self.thread.start()

    def close(self) -> None:
        """Stop serving."""
        self.server.shutdown()
        self.server.server_close()


@pytest.mark.timeout(180)
def test_a_page_from_another_origin_cannot_open_a_session(console: Served, browser: Any) -> None:
    """The user's own tab holds the cookie; pages of another port and of another host name both fail."""
    page = XtermPage(browser)
    page.open(console.url)
    page.wait_for("divisible by")
    mine = console.apps()
    assert len(mine) == 1
    foreign = ForeignSite(console.port)
    try:
        for host in ("localhost", "127.0.0.1"):  # the same host name (the cookie goes along), another one
            browser.switch_to.new_window("tab")
            browser.get(f"http://{host}:{foreign.port}/")
            wait_until(lambda: browser.title != "waiting", f"the page from {host}:{foreign.port} to try")
            assert browser.title.startswith("refused"), browser.title
            assert console.apps() == mine, [p.cmdline() for p in console.apps()]
    finally:
        foreign.close()
    output = console.output()
    assert "may not use this server (refused 'GET' '/ws' from 127.0.0.1)" in output, output
    assert "Traceback" not in output


#: The acceptance of issue 30: a tab closed after its first screen leaves no app process within 5 s.
TAB_GONE_WITHIN = 5.0


@pytest.mark.timeout(180)
def test_a_tab_closed_right_after_its_first_screen_leaves_no_app(console: Served, browser: Any) -> None:
    """The first bytes, a window resize, the tab closed at once (the app still starting): its app ends."""
    for width in (1000, 900):
        page = XtermPage(browser)
        browser.get(console.url)
        wait_until(lambda: "-first-byte" in browser.execute_script("return document.body.className"),
                   "the app's first bytes")
        browser.set_window_size(width, 700)
        started = console.apps()
        assert started, "the tab's app"
        page.close_tab()
        wait_until(lambda: gone(started), lambda: f"no app left: {[p.cmdline() for p in live(started)]}",
                   timeout=TAB_GONE_WITHIN)
    assert console.proc.poll() is None
    assert "Traceback" not in console.output()
