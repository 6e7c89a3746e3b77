"""`rostui serve` under attack: pages and clients without the token or from another site, a tab asking for a
terminal of 100000 x 100000 cells, hundreds of sessions at once, and messages no page sends.

The victim is `rostui serve console FILE` (a rosout.log, so no master is needed).  A legitimate tab opened
with the token serve printed stays beside every attack and must keep working: ``?`` opens and closes the app's
help.  Memory is sampled (the hostile tab's app; the server and every app together); the figures are
recorded, never timed.
"""

from __future__ import annotations

import asyncio
import http.client
from pathlib import Path
from typing import Iterator

import psutil
import pytest

from hostile_helpers import MB, Background, LegitClient, RssSampler, attack_figures, record

from conftest import wait_until
from console_helpers import write_sample_log
from serve_helpers import DEADLINE, Loop, Served, Tab, live, loop, serving  # noqa: F401  (loop is a fixture)

#: Sessions the server under attack allows (`--max-sessions`).
MAX_SESSIONS = 3

#: How far one app may grow above its start however large a terminal is asked for (the bare app is ~60 MB).
APP_GROWTH_LIMIT_MB = 250.0

#: How far the server and all its apps together may grow under a flood of sessions.
TREE_GROWTH_LIMIT_MB = 120.0 * MAX_SESSIONS + 100.0

#: Words of the console's sample log, on its first screen.
SHOWS = "divisible by"


@pytest.fixture
def served(ros_env: dict[str, str], tmp_path: Path) -> Iterator[Served]:
    """`rostui serve --max-sessions 3 console FILE`."""
    log = write_sample_log(tmp_path / "rosout.log")
    with serving(["console", str(log)], ros_env, tmp_path / "serve.log", "--max-sessions", str(MAX_SESSIONS)) as served:
        yield served


@pytest.fixture
def legit(served: Served, loop: Loop) -> Iterator[Tab]:
    """A tab opened as a user does (with the token), showing the app's first screen."""
    tab = Tab(loop, served.port, token=served.token)
    assert tab.open(), tab.status
    tab.wait_for(SHOWS)
    try:
        yield tab
    finally:
        tab.close()


def get(port: int, path: str, **headers: str) -> tuple[int, dict[str, str], str]:
    """GET ``path`` with exactly these headers (Host too, when given): status, headers, body."""
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=DEADLINE)
    try:
        connection.putrequest("GET", path, skip_host="Host" in headers, skip_accept_encoding=True)
        for name, value in headers.items():
            connection.putheader(name, value)
        connection.endheaders()
        response = connection.getresponse()
        return response.status, {k.lower(): v for k, v in response.getheaders()}, response.read().decode()
    finally:
        connection.close()


def app_of(served: Served, others: list[psutil.Process]) -> psutil.Process:
    """The one rostui app process of the server that is not among ``others`` (waiting until it starts); other
    short-lived children (a helper the server or an app runs) are not apps."""
    known = {p.pid for p in others}
    found: list[psutil.Process] = []

    def started() -> bool:
        found[:] = [p for p in served.apps() if p.pid not in known and is_rostui(p)]
        return len(found) == 1
    wait_until(started, "the new tab's app to start")
    return found[0]


def is_rostui(process: psutil.Process) -> bool:
    """Whether ``process`` runs rostui (the app a tab started), not a helper."""
    try:
        return "rostui" in " ".join(process.cmdline())
    except psutil.Error:
        return False


def test_requests_without_the_token_or_from_another_site_are_refused(served: Served, loop: Loop,
                                                                     legit: Tab) -> None:
    port, token = served.port, served.token
    here = f"localhost:{port}"
    refused: list[tuple[str, dict[str, str]]] = [
        ("/", {}),  # the page, no token
        ("/ws?width=80&height=24", {"Upgrade": "websocket", "Connection": "Upgrade", "Sec-WebSocket-Version": "13",
                                    "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ=="}),
        ("/static/js/textual.js", {}),
        ("/?token=" + "x" * len(token), {}),  # a wrong token
        (f"/?token={token}", {"Host": f"attacker.example:{port}"}),  # DNS rebinding: the right token, a foreign Host
        (f"/?token={token}", {"Origin": "http://attacker.example"}),  # another site's page
        (f"/?token={token}", {"Origin": f"http://localhost:{port + 1}"}),  # another port is another site
        (f"/?token={token}", {"Origin": "null"}),
        ("/%1b]0;owned%07%1b[2J", {"Host": "x" * 5000}),  # escapes and a flood of text for serve's terminal
    ]
    for path, headers in refused:
        status, _headers, body = get(port, path, **headers)
        assert status == 403, (path, headers, status, body)
        assert body.startswith("rostui serve: ") and body.count("\n") == 1, body
        assert token not in body
    # control characters in a header: refused by aiohttp's parser before any handler
    assert get(port, f"/?token={token}", Origin="http://\x1b]0;owned\x07.example")[0] == 400
    # another site's page opening the websocket, with the token and with the cookie a user's browser holds
    for tab in (Tab(loop, port, token=token, origin="http://attacker.example"),
                Tab(loop, port, token=token, host="attacker.example")):
        assert not tab.open() and tab.status == 403
    assert len(served.apps()) == 1, "no app started for a refused request"

    status, headers, body = get(port, f"/?token={token}&fontsize=14", Host=here)  # as a user opens it
    assert status == 303 and headers["location"] == "./?fontsize=14", (status, headers)
    cookie = headers["set-cookie"]
    assert token in cookie and "HttpOnly" in cookie and "SameSite=Strict" in cookie, cookie
    jar = cookie.split(";")[0]
    status, headers, page = get(port, "/?fontsize=14", Host=here, Cookie=jar, Origin=f"http://{here}")
    assert status == 200, page
    assert "https://" not in page and "http://" not in page.replace('xmlns="http://www.w3.org/2000/svg"', "")
    assert "default-src 'self'" in headers["content-security-policy"]
    assert get(port, "/static/js/textual.js", Host=here, Cookie=jar)[0] == 200
    legit.help_round()
    output = served.output()
    assert "refused" in output and "Traceback" not in output, output
    assert "\x1b" not in output and max(len(line) for line in output.splitlines()) < 400, output


def test_a_huge_terminal_is_clamped_beside_a_legitimate_tab(served: Served, loop: Loop, legit: Tab) -> None:
    others = served.apps()
    hostile = Tab(loop, served.port, token=served.token, width=100000, height=100000)
    assert hostile.open(), hostile.status
    app = app_of(served, others)
    with RssSampler(app.pid) as rss, LegitClient(legit.help_round, pause=0.2) as legit_client:
        wait_until(lambda: hostile.frames > 0 or rss.growth_mb > APP_GROWTH_LIMIT_MB,
                   "the hostile tab's first screen (or its app past the limit)")
        for width, height in ((100000, 100000), (10 ** 12, 3), (-7, 0), (100000, 100000)):
            mark = hostile.mark()
            hostile.resize(width, height)
            wait_until(lambda: len(hostile.since(mark)) > 0 or rss.growth_mb > APP_GROWTH_LIMIT_MB,
                       f"the app to redraw at {width} x {height} (or go past the limit)")
        wait_until(lambda: len(legit_client.latencies) >= 2, "two help rounds of the legitimate tab")
    figures = attack_figures(rss, legit_client, tried=4)
    record("huge terminal size", "rostui serve console", **figures)
    assert rss.growth_mb < APP_GROWTH_LIMIT_MB, figures
    assert not legit_client.failures, legit_client.failures
    assert served.proc.poll() is None
    hostile.close()
    assert "Traceback" not in served.output()


class TreeRss(Background):
    """The resident memory of a process and all its descendants together, sampled every 50 ms."""

    def __init__(self, pid: int) -> None:
        self.root = psutil.Process(pid)
        self.baseline = self.total()
        self.peak = self.baseline
        self.most_apps = 0
        super().__init__()

    def total(self) -> int:
        """The tree's resident memory now."""
        total = 0
        for p in [self.root, *live(self.root.children(recursive=True))]:
            try:
                total += p.memory_info().rss
            except psutil.Error:
                pass
        return total

    def _run(self) -> None:
        while not self._stop.wait(0.05):
            self.peak = max(self.peak, self.total())
            self.most_apps = max(self.most_apps, len(live(self.root.children())))

    @property
    def growth_mb(self) -> float:
        """How far the peak rose above the memory before the attack, in MiB."""
        return (self.peak - self.baseline) / MB


def test_many_sessions_hold_the_limit_beside_a_legitimate_tab(served: Served, loop: Loop, legit: Tab) -> None:
    attempts = 200

    async def flood(token: str | None) -> list[Tab]:
        tabs = [Tab(loop, served.port, token=token) for _ in range(attempts)]
        await asyncio.gather(*(tab._open() for tab in tabs))
        return tabs

    with TreeRss(served.proc.pid) as tree, LegitClient(legit.help_round, pause=0.2) as legit_client:
        no_token = loop.run(flood(None), timeout=120)
        assert {t.status for t in no_token} == {403}
        tabs = loop.run(flood(served.token), timeout=120)
        wait_until(lambda: all(t.closed() or t.frames > 0 for t in tabs), "every session refused or drawn")
        accepted = [t for t in tabs if not t.closed()]
        refused = [t for t in tabs if t.close_code == 1013]
        assert len(accepted) == MAX_SESSIONS - 1 and len(refused) == attempts - len(accepted), \
            (len(accepted), len(refused), {t.close_code for t in tabs})
        reason = refused[0].close_reason
        assert reason.startswith("rostui serve: ") and f"--max-sessions {MAX_SESSIONS}" in reason, reason
        for tab in accepted:
            tab.wait_for(SHOWS)
        wait_until(lambda: len(legit_client.latencies) >= 2, "two help rounds of the legitimate tab")
        for tab in [*accepted, *refused, *no_token]:
            tab.close()
    figures = {"tried": 2 * attempts, "most_apps": tree.most_apps, "peak_tree_rss_growth_mb": round(tree.growth_mb, 1),
               "legit_calls": len(legit_client.latencies), "legit_failures": len(legit_client.failures),
               "legit_median_ms": round(legit_client.median_ms, 2), "legit_max_ms": round(legit_client.max_ms, 1)}
    record("session flood", "rostui serve console", **figures)
    assert tree.most_apps <= MAX_SESSIONS, figures
    assert tree.growth_mb < TREE_GROWTH_LIMIT_MB, figures
    assert not legit_client.failures, legit_client.failures
    wait_until(lambda: len(served.apps()) == 1, "the closed tabs' apps to end")
    legit.help_round()
    output = served.output()
    assert "Traceback" not in output and f"--max-sessions {MAX_SESSIONS}" in output, output


#: Messages no page sends, by name.
GARBAGE = {
    "not json": "not json",
    "empty list": "[]",
    "object": '{"stdin": "q"}',
    "resize without size": '["resize"]',
    "resize with words": '["resize", {"width": "wide", "height": 24}]',
    "resize with fractions": '["resize", {"width": 2.5, "height": [1]}]',
    "stdin number": '["stdin", 5]',
    "ping object": '["ping", {"x": 1}]',
    "unknown kind": '["shutdown"]',
    "deep nesting": "[" * 100000,
    "2 MiB paste": '["stdin", "' + "a" * (2 << 20) + '"]',
}


def test_a_message_no_page_sends_ends_that_tab_only(served: Served, loop: Loop, legit: Tab) -> None:
    others = served.apps()
    for name, garbage in GARBAGE.items():
        tab = Tab(loop, served.port, token=served.token)
        assert tab.open(), name
        tab.wait_for(SHOWS)
        app = app_of(served, others)
        tab.send_text(garbage)
        wait_until(tab.closed, f"the server to close the tab that sent {name}")
        assert tab.close_code in (1003, 1008, 1009), (name, tab.close_code, tab.close_reason)
        wait_until(lambda: not live([app]), f"the app of the tab that sent {name} to end")
        tab.close()
    legit.help_round()
    output = served.output()
    assert "Traceback" not in output, output
    assert served.proc.poll() is None
