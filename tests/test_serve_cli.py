"""`rostui serve` before anything listens: what it refuses (one line, exit 1), the missing web extra,
a port in use, the TTY check under Textual's web driver, and its shutdown of apps that will not quit."""

from __future__ import annotations

import socket
import subprocess
import sys
import textwrap

import pytest

from cli_helpers import rostui
from conftest import REPO, free_port

APPS = "graph, console, loggers, monitor, bag view, turtlesim, launch --tui, view, reconfigure, diagnostics, top, action, publish, call"


def one_error_line(r: subprocess.CompletedProcess[str]) -> str:
    """The single stderr line of a refused command (exit 1, nothing on stdout)."""
    assert r.returncode == 1, (r.returncode, r.stdout, r.stderr)
    assert r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith("rostui serve: "), lines[0]
    return lines[0]


@pytest.mark.parametrize(("words", "says"), [
    ([], f"name the app to serve: rostui serve APP [ARGS], APP one of {APPS}"),
    (["topic", "list"], f"`topic list` is not an app; serve one of {APPS}"),
    (["bag", "play", "run.bag"], "`bag play` is not an app"),
    (["core"], "`core` is not an app"),
    (["teleop"], "`teleop` is not an app"),
    (["launch", "agitr", "doublesim.launch"], "launch serves its monitor only: rostui serve launch --tui"),
    (["launch", "--tui", "--nodes", "agitr", "doublesim.launch"], "launch --nodes prints and exits"),
    (["launch", "--tui"], "launch --tui needs a launch file"),
    (["graph", "--dot"], "graph --dot prints DOT and exits"),
    (["graph", "--vew", "all"], "graph: No such option: --vew"),
    (["monitor", "--period"], "monitor: "),
    (["loggers", "/talker"], "loggers NODE prints or sets levels without the app"),
    (["bag", "view"], "bag view needs a bag"),
    (["console", "--help"], "serving runs the app, not its help: see `rostui console --help`"),
])
def test_serve_refuses_what_is_not_an_app(ros_env: dict[str, str], words: list[str], says: str) -> None:
    port = free_port()
    line = one_error_line(rostui(["serve", "--port", str(port), *words], ros_env))
    assert says in line


def test_serve_refuses_a_bad_port(ros_env: dict[str, str]) -> None:
    assert "--port must be 1-65535, not 70000" in one_error_line(rostui(["serve", "--port", "70000", "graph"], ros_env))


def test_serve_says_when_its_port_is_taken(ros_env: dict[str, str]) -> None:
    with socket.socket() as holder:
        holder.bind(("127.0.0.1", 0))
        holder.listen()
        port = holder.getsockname()[1]
        line = one_error_line(rostui(["serve", "--port", str(port), "graph"], ros_env))
    assert line == f"rostui serve: cannot listen on 127.0.0.1:{port}: Address already in use"


def test_serve_without_the_web_extra_says_how_to_install_it(ros_env: dict[str, str]) -> None:
    """textual_serve made unimportable (None in sys.modules), as in an install without rostui[web]."""
    program = textwrap.dedent(f"""
        import sys
        sys.modules["textual_serve"] = None
        sys.argv = ["rostui", "serve", "--port", "{free_port()}", "graph"]
        from rostui.cli.fast import main
        main()
    """)
    r = subprocess.run([sys.executable, "-c", program], env=ros_env, cwd=REPO, capture_output=True, text=True,
                       timeout=60, stdin=subprocess.DEVNULL)
    line = one_error_line(r)
    assert line.endswith("pip install 'rostui[web]'"), line
    assert "the web extra is missing" in line


def test_serve_help_says_how_to_reach_it(ros_env: dict[str, str]) -> None:
    r = rostui(["serve", "--help"], ros_env)
    assert r.returncode == 0, r.stderr
    text = " ".join(r.stdout.split())
    assert "ssh -L 8000:localhost:8000" in text
    assert "rostui[web]" in text


def test_the_tty_check_lets_textual_s_web_driver_draw(monkeypatch: pytest.MonkeyPatch,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    """Under pytest stdin and stdout are no TTY: only textual-serve's exact driver setting passes."""
    from rostui.apps.terminal import WEB_DRIVER, terminal_missing

    monkeypatch.setenv("TEXTUAL_DRIVER", WEB_DRIVER)
    assert not terminal_missing("rostui graph", "use `rostui graph --dot` without one")
    assert capsys.readouterr().err == ""
    for other in ("textual.drivers.headless_driver:HeadlessDriver", WEB_DRIVER + "X", "web"):
        monkeypatch.setenv("TEXTUAL_DRIVER", other)
        assert terminal_missing("rostui graph", "use `rostui graph --dot` without one")
        assert "stdin and stdout must be a TTY" in capsys.readouterr().err
    monkeypatch.delenv("TEXTUAL_DRIVER")
    assert terminal_missing("rostui graph", "use `rostui graph --dot` without one")


def test_an_app_without_a_tty_still_refuses_outside_a_browser(ros_env: dict[str, str]) -> None:
    r = rostui(["graph"], {**ros_env, "TEXTUAL_DRIVER": "textual.drivers.headless_driver:HeadlessDriver"})
    assert r.returncode == 1
    assert "rostui graph draws in a terminal: stdin and stdout must be a TTY" in r.stderr


def test_urls_and_the_ssh_line() -> None:
    from rostui.cli.serve_cmd import announcement, public_url

    assert public_url("127.0.0.1", 8000) == "http://localhost:8000"
    assert public_url("192.0.2.7", 9000) == "http://192.0.2.7:9000"
    assert public_url("::1", 8000) == "http://localhost:8000"
    assert public_url("0.0.0.0", 8000) == f"http://{socket.gethostname()}:8000"
    local = announcement("graph", "127.0.0.1", 8001, "http://localhost:8001", "TOKEN", 8)
    assert local[0] == "rostui serve: graph listening on 127.0.0.1:8001; open http://localhost:8001/?token=TOKEN"
    assert local[1].startswith("The token is required: a page or websocket without it is refused. ")
    assert "(at most 8: --max-sessions)" in local[1]
    assert local[2] == (f"From another machine: ssh -L 8001:localhost:8001 {socket.gethostname()}, "
                        "then open http://localhost:8001/?token=TOKEN there")
    tunnel = announcement("graph", "127.0.0.1", 8001, "http://localhost:9000", "TOKEN", 8)
    assert tunnel[2].startswith("From another machine: ssh -L 9000:localhost:8001 ")
    assert tunnel[2].endswith(", then open http://localhost:9000/?token=TOKEN there")
    shared = announcement("graph", "0.0.0.0", 8001, "http://robot:8001", "TOKEN", 8)
    assert shared[0].startswith("rostui serve: graph listening on 0.0.0.0:8001; ")
    assert "has the token can use the app" in shared[2]


def test_shutdown_ends_an_app_that_ignores_sigterm() -> None:
    """The server's last resort: apps still there after the grace get SIGTERM, then SIGKILL."""
    program = textwrap.dedent("""
        import asyncio, sys
        import psutil
        from rostui.apps.serve.server import end_children

        STUBBORN = ("import signal, time; signal.signal(signal.SIGTERM, signal.SIG_IGN); "
                    "print(1, flush=True); time.sleep(60)")

        async def main():
            child = await asyncio.create_subprocess_exec(sys.executable, "-c", STUBBORN, stdout=asyncio.subprocess.PIPE)
            await child.stdout.readline()
            await end_children(0.2, 0.5)
            print(child.pid, await child.wait(), psutil.Process().children())

        asyncio.run(main())
    """)
    r = subprocess.run([sys.executable, "-c", program], cwd=REPO, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    pid, status, left = r.stdout.split(maxsplit=2)
    assert status == "-9" and left.strip() == "[]", r.stdout
