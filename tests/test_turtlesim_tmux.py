"""`rostui turtlesim` end to end in real terminals: tmux (screen-256color, xterm), `ssh -t`, raw ptys.

A shell runs in a detached 80x24 tmux pane; the test types the command there
with a fresh ROS_HOME and a master URI on a free port where nothing listens,
so the app embeds its master.  It waits for the status line, sends arrow
keys with `tmux send-keys`, reads the moved pose from the screen and from
`rostui topic echo -n 1 /turtle1/pose`, then quits with q and checks that
the shell prompt is back with exit status 0 and the master is gone.
"""

from __future__ import annotations

import fcntl
import getpass
import os
import pty
import re
import select
import shlex
import shutil
import struct
import subprocess
import sys
import termios
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator

import pytest

from cli_helpers import rostui
from conftest import REPO, free_port, master_port, need_peer, stop_process, wait_for_port, wait_until
from tmux_helpers import Pane, shell_pane

DEADLINE = 30.0
POSE = re.compile(r"turtle1 x (-?\d+\.\d+) y (-?\d+\.\d+) \S (-?\d+\.\d+)")
EXIT_MARK = "TURTLESIM_EXIT="


class TurtlePane(Pane):
    """A tmux pane that can read turtle1's pose off the app's status line."""

    def pose(self) -> tuple[float, float, float] | None:
        """turtle1's pose as the status line shows it, if it is on screen."""
        match = POSE.search(self.screen())
        return None if match is None else (float(match[1]), float(match[2]), float(match[3]))


@pytest.fixture
def pane() -> Iterator[TurtlePane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("turtles", 80, 24, TurtlePane) as pane:
        yield pane


def turtlesim_command(env: dict[str, str], term: str) -> str:
    """The shell line that starts `rostui turtlesim` with the test's ROS environment."""
    values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    values["TERM"] = term
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    return f"env -u COLORTERM {assignments} {shlex.quote(sys.executable)} -m rostui turtlesim"


def drive_and_quit(pane: TurtlePane, env: dict[str, str]) -> None:
    """The user's session: wait for the app, drive turtle1, compare screen and topic, quit."""
    wait_until(lambda: pane.pose() == (5.54, 5.54, 0.0), "the status line with turtle1 at the centre")
    wait_until(lambda: "(@)" in pane.screen(), "turtle1 drawn")
    assert "embedded master" in pane.screen()
    for _ in range(3):
        pane.keys("Up")
        time.sleep(0.2)
    wait_until(lambda: (pane.pose() or (0, 0, 0))[0] > 6.5, "turtle1 to move east on screen")
    pane.keys("Left")
    wait_until(lambda: (pane.pose() or (0, 0, 0))[2] > 0.5, "turtle1 to turn left on screen")
    settled: list[tuple[float, float, float] | None] = [None]

    def still() -> bool:
        before = pane.pose()
        time.sleep(0.5)
        settled[0] = pane.pose()
        return before is not None and before == settled[0]

    wait_until(still, "turtle1 to stop (commands expire after 1 s)")
    echo = rostui(["topic", "echo", "-n", "1", "/turtle1/pose"], env)
    assert echo.returncode == 0, echo.stderr
    fields = dict(line.split(": ", 1) for line in echo.stdout.splitlines() if ": " in line)
    x, y, theta = settled[0]
    assert abs(float(fields["x"]) - x) < 0.006
    assert abs(float(fields["y"]) - y) < 0.006
    assert abs(float(fields["theta"]) - theta) < 0.006
    pane.keys("q")
    wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
    screen = pane.screen()
    assert POSE.search(screen) is None, "the app's screen was left behind"
    assert screen.rstrip().endswith("$"), "no shell prompt after the app quit"


@pytest.mark.parametrize("term", ["screen-256color", "xterm"])
def test_turtlesim_in_tmux(pane: TurtlePane, ros_env: dict[str, str], term: str) -> None:
    """One command on a fresh ROS_HOME: embedded master, arrow keys drive, screen and topic agree, q quits."""
    port = master_port(ros_env)
    pane.type(f"{turtlesim_command(ros_env, term)}; echo {EXIT_MARK}$?")
    drive_and_quit(pane, ros_env)
    result = rostui(["node", "list"], ros_env)
    assert result.returncode != 0 and "Unable to communicate with master" in result.stderr, \
        f"master on port {port} still answers after q"


def sgr_codes(output: bytes) -> list[set[str]]:
    """The parameter sets of every SGR (colour/attribute) escape sequence in ``output``."""
    return [set(m.decode().split(";")) for m in re.findall(rb"\x1b\[([0-9;]*)m", output)]


@pytest.mark.parametrize("term,colorterm,forbidden", [
    ("xterm", None, ("38;2;", "48;2;", "38;5;", "48;5;")),
    ("xterm-256color", None, ("38;2;", "48;2;")),
])
def test_colour_codes_follow_the_terminal(ros_env: dict[str, str], term: str, colorterm: str | None,
                                          forbidden: tuple[str, ...]) -> None:
    """Under TERM=xterm only 16-colour codes reach the terminal: the world in bright blue (104) and
    turtle1 in bold bright yellow on it (1;93;104); with 256 colours no truecolor codes."""
    env = dict(ros_env, TERM=term)
    env.pop("COLORTERM", None)
    if colorterm:
        env["COLORTERM"] = colorterm
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 80, 0, 0))
    proc = subprocess.Popen([sys.executable, "-m", "rostui", "turtlesim"], env=env, cwd=REPO, stdin=slave,
                            stdout=slave, stderr=slave, start_new_session=True)
    os.close(slave)
    output = bytearray()
    try:
        deadline = time.monotonic() + DEADLINE
        def drawn() -> bool:
            """Status line and turtle1 on screen; under TERM=xterm, turtle1 already drawn as selected."""
            if b"turtle1 x 5.54" not in output or b"(@)" not in output:
                return False
            return term != "xterm" or any({"1", "93", "104"} <= c for c in sgr_codes(bytes(output)))

        while not drawn():
            ready, _, _ = select.select([master], [], [], 0.2)
            if ready:
                output += os.read(master, 65536)
            assert time.monotonic() < deadline, "the app did not draw turtle1 and its status line"
        os.write(master, b"q")
        proc.wait(timeout=DEADLINE)
        assert proc.returncode == 0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        os.close(master)
    text = bytes(output).decode(errors="replace")
    for code in forbidden:
        assert code not in text
    if term == "xterm":
        codes = sgr_codes(bytes(output))
        assert any({"104"} <= c for c in codes), "no bright blue world"
        assert any({"1", "93", "104"} <= c for c in codes), "no bold bright yellow turtle on the world"


@dataclass
class SshServer:
    """A private sshd on 127.0.0.1 that accepts one key for the current user."""

    port: int
    key: Path


@pytest.fixture
def sshd(tmp_path: Path) -> Iterator[SshServer]:
    """`/usr/sbin/sshd -D` on a free port with a temporary host key and authorized key."""
    need_peer(Path("/usr/sbin/sshd").exists() and shutil.which("ssh") is not None
              and shutil.which("ssh-keygen") is not None, "sshd, ssh (openssh-server, openssh-client)")
    root = tmp_path / "sshd"
    root.mkdir()
    for name in ("host_key", "client_key"):
        subprocess.run(["ssh-keygen", "-q", "-t", "ed25519", "-N", "", "-f", str(root / name)], check=True,
                       timeout=DEADLINE)
    (root / "authorized_keys").write_text((root / "client_key.pub").read_text())
    if os.geteuid() == 0:
        Path("/run/sshd").mkdir(mode=0o755, exist_ok=True)  # sshd's privilege-separation directory
    port = free_port()
    config = root / "sshd_config"
    config.write_text("\n".join([
        f"Port {port}",
        "ListenAddress 127.0.0.1",
        f"HostKey {root / 'host_key'}",
        f"AuthorizedKeysFile {root / 'authorized_keys'}",
        f"PidFile {root / 'sshd.pid'}",
        "PubkeyAuthentication yes",
        "PasswordAuthentication no",
        "KbdInteractiveAuthentication no",
        "PermitRootLogin prohibit-password",
        "StrictModes no",
        "UsePAM no",
        "",
    ]))
    log = open(root / "sshd.log", "w")
    proc = subprocess.Popen(["/usr/sbin/sshd", "-D", "-e", "-f", str(config)], stdout=log, stderr=subprocess.STDOUT)
    try:
        wait_for_port(port, proc=proc)
        yield SshServer(port, root / "client_key")
    finally:
        stop_process(proc)
        log.close()


def test_turtlesim_over_ssh(pane: TurtlePane, sshd: SshServer, ros_env: dict[str, str]) -> None:
    """`ssh -t` to this machine and run `rostui turtlesim` there: same keys, same screen, same pose."""
    remote = f"cd {shlex.quote(str(REPO))} && {turtlesim_command(ros_env, 'xterm-256color')}"
    ssh = [
        "ssh", "-t", "-F", "/dev/null", "-p", str(sshd.port), "-i", str(sshd.key),
        "-o", "StrictHostKeyChecking=no", "-o", "UserKnownHostsFile=/dev/null", "-o", "BatchMode=yes",
        "-o", "LogLevel=ERROR", f"{getpass.getuser()}@127.0.0.1", remote,
    ]
    pane.type(f"{shlex.join(ssh)}; echo {EXIT_MARK}$?")
    drive_and_quit(pane, ros_env)
