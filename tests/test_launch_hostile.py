"""rostui launch under our safety rules: loopback-only sockets by default, and stops that reach a node's group.

1. Every socket the launcher listens on (its XML-RPC server, the in-process master and /rosout) follows
   ROS_IP / ROS_HOSTNAME and the master's host: with a local master and neither set, 127.0.0.1 only.
2. A node is stopped as roslaunch stops it: SIGINT to its whole process group at once (a wrapper script's
   child gets it too), SIGTERM and SIGKILL only after the timeouts.
"""

from __future__ import annotations

import socket
import subprocess
import sys
import xmlrpc.client
from pathlib import Path
from typing import Iterator

import psutil
import pytest

from conftest import REPO, master_port, wait_until
from launch_helpers import Launch, launch_env


@pytest.fixture
def launches() -> Iterator[list[Launch]]:
    started: list[Launch] = []
    yield started
    for launch in started:
        if launch.proc.poll() is None:
            for child in psutil.Process(launch.proc.pid).children(recursive=True):
                child.kill()
            launch.proc.kill()
            launch.proc.wait()


def make_package(root: Path, name: str, scripts: dict[str, str], launch_files: dict[str, str]) -> Path:
    """A ROS package below ``root`` with executable ``scripts`` and ``launch/`` files."""
    pkg = root / name
    (pkg / "scripts").mkdir(parents=True)
    (pkg / "launch").mkdir()
    (pkg / "package.xml").write_text(f"<package format=\"2\"><name>{name}</name><version>0.0.0</version>"
                                     "<description>test</description><maintainer email=\"a@b.c\">t</maintainer>"
                                     "<license>BSD</license></package>\n")
    for file_name, text in scripts.items():
        path = pkg / "scripts" / file_name
        path.write_text(text)
        path.chmod(0o755)
    for file_name, text in launch_files.items():
        (pkg / "launch" / file_name).write_text(text)
    return pkg


SLEEPER_LAUNCH = """<launch>
  <node pkg="hostile_launch" type="sleeper" name="sleeper" args="$(arg pid_file)"/>
</launch>
"""
SLEEPER = """#!/bin/sh
echo $$ > "$1"
exec sleep 1000
"""


def non_loopback_addresses() -> list[str]:
    """This machine's IPv4 addresses that are not loopback."""
    found = []
    for addresses in psutil.net_if_addrs().values():
        for address in addresses:
            if address.family == socket.AF_INET and not address.address.startswith("127."):
                found.append(address.address)
    return found


def listening(pid: int) -> list[tuple[str, int]]:
    """(address, port) of every TCP socket the process listens on."""
    process = psutil.Process(pid)
    connections = process.net_connections(kind="tcp") if hasattr(process, "net_connections") \
        else process.connections(kind="tcp")
    return [(c.laddr.ip, c.laddr.port) for c in connections if c.status == psutil.CONN_LISTEN]


@pytest.fixture
def loopback_env(ros_env: dict[str, str], tmp_path: Path) -> dict[str, str]:
    """A local master URI, no ROS_IP or ROS_HOSTNAME, and a package path with the test package."""
    env = launch_env(ros_env)
    env.pop("ROS_IP", None)
    env.pop("ROS_HOSTNAME", None)
    root = tmp_path / "pkgs"
    make_package(root, "hostile_launch", {"sleeper": SLEEPER}, {"sleeper.launch": SLEEPER_LAUNCH})
    env["ROS_PACKAGE_PATH"] = f"{root}:{env['ROS_PACKAGE_PATH']}"
    return env


def launch_server_uri(env: dict[str, str]) -> str:
    """The URI the launcher registered under /roslaunch/uris."""
    uris = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getParam("/test", "/roslaunch/uris")[2]
    assert isinstance(uris, dict) and len(uris) == 1, uris
    return str(next(iter(uris.values())))


def test_launch_listens_on_loopback_only_by_default(loopback_env: dict[str, str], launches: list[Launch],
                                                     tmp_path: Path) -> None:
    pid_file = tmp_path / "sleeper.pid"
    launch = Launch(["hostile_launch", "sleeper.launch", f"pid_file:={pid_file}"], loopback_env, tmp_path)
    launches.append(launch)
    wait_until(lambda: pid_file.exists() and pid_file.read_text().strip() != "", "the node to start", timeout=60)
    uri = launch_server_uri(loopback_env)
    port = int(uri.rstrip("/").rsplit(":", 1)[1])
    assert uri == f"http://127.0.0.1:{port}/"
    sockets = listening(launch.proc.pid)
    assert (("127.0.0.1", port)) in sockets
    assert ("127.0.0.1", master_port(loopback_env)) in sockets  # the in-process master
    assert all(address == "127.0.0.1" for address, _ in sockets), sockets  # master, rosout and launch server
    for address in non_loopback_addresses():
        with socket.socket() as probe:
            probe.settimeout(5)
            assert probe.connect_ex((address, port)) != 0, f"the launch server answers on {address}"
    assert xmlrpc.client.ServerProxy(uri).getPid("/test")[2] == launch.proc.pid
    assert launch.interrupt() == 0


def test_launch_follows_ros_ip(loopback_env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    """With ROS_IP set to an address of this machine the server is reachable there and advertises it."""
    addresses = non_loopback_addresses()
    if not addresses:
        pytest.skip("this machine has no non-loopback IPv4 address")
    env = dict(loopback_env, ROS_IP=addresses[0])
    pid_file = tmp_path / "sleeper.pid"
    launch = Launch(["hostile_launch", "sleeper.launch", f"pid_file:={pid_file}"], env, tmp_path)
    launches.append(launch)
    wait_until(lambda: pid_file.exists() and pid_file.read_text().strip() != "", "the node to start", timeout=60)
    uri = launch_server_uri(env)
    assert uri.startswith(f"http://{addresses[0]}:")
    assert xmlrpc.client.ServerProxy(uri).getPid("/test")[2] == launch.proc.pid
    assert launch.interrupt() == 0


# ---------------------------------------------------------------------------------- stopping a node's group

WRAPPER = """#!/bin/sh
# A wrapper, as many nodes are: it runs the real program in the foreground and waits for it.
"{python}" "$(dirname "$0")/child.py" "$1"
"""
CHILD = """import os, signal, sys, time
path = sys.argv[1]


def got(signum, _frame):
    with open(path, "a") as f:
        f.write(signal.Signals(signum).name + "\\n")
    sys.exit(0)


signal.signal(signal.SIGINT, got)
signal.signal(signal.SIGTERM, got)
with open(path, "a") as f:
    f.write(f"ready {os.getpid()}\\n")
while True:
    time.sleep(1)
"""
WRAPPED_LAUNCH = """<launch>
  <node pkg="hostile_signals" type="wrapper" name="wrapped" args="$(arg record)"/>
</launch>
"""


@pytest.mark.parametrize("how", ["ctrl-c", "tui-stop"])
def test_wrapper_scripts_child_gets_sigint_at_once(ros_env: dict[str, str], launches: list[Launch],
                                                   tmp_path: Path, how: str) -> None:
    """The child of a node's wrapper script gets the SIGINT itself (before: SIGTERM after --sigint-timeout)."""
    root = tmp_path / "pkgs"
    make_package(root, "hostile_signals", {"wrapper": WRAPPER.format(python=sys.executable), "child.py": CHILD},
                 {"wrapped.launch": WRAPPED_LAUNCH})
    env = launch_env(ros_env)
    env["ROS_PACKAGE_PATH"] = f"{root}:{env['ROS_PACKAGE_PATH']}"
    record = tmp_path / "record.txt"
    args = ["--sigint-timeout", "20", "hostile_signals", "wrapped.launch", f"record:={record}"]
    if how == "ctrl-c":
        launch = Launch(args, env, tmp_path)
        launches.append(launch)
        wait_until(lambda: record.exists() and record.read_text().startswith("ready"), "the child to start",
                   timeout=60)
        child_pid = int(record.read_text().split()[1])
        assert launch.interrupt() == 0
    else:
        child_pid = asyncio_stop_on_request(args, env, record)
    lines = record.read_text().splitlines()
    assert lines[1:] == ["SIGINT"], lines
    assert not psutil.pid_exists(child_pid) or psutil.Process(child_pid).status() == psutil.STATUS_ZOMBIE


STOP_ON_REQUEST = """
import asyncio, os, sys
from rostui.launch.files import resolve_request
from rostui.launch.supervisor import SupervisorOptions, keep_quiet, load_supervisor

record, words = sys.argv[1], sys.argv[2:]


def ready():
    return os.path.exists(record) and open(record).read().startswith("ready")


async def main():
    options = SupervisorOptions(sigint_timeout=20.0, capture=True, handle_signals=False, stay_when_all_ended=True)
    supervisor = load_supervisor(resolve_request(words), options, reporter=keep_quiet)
    run = asyncio.get_running_loop().create_task(supervisor.run())
    for _ in range(1200):
        if ready():
            break
        await asyncio.sleep(0.05)
    await supervisor.stop_node("/wrapped")
    print("stopped", flush=True)
    supervisor.request_stop()
    await run


asyncio.run(main())
"""


def asyncio_stop_on_request(args: list[str], env: dict[str, str], record: Path) -> int:
    """Stop the node as the launch monitor's `k` does (Supervisor.stop_node), in a child Python; the child's pid."""
    result = subprocess.run([sys.executable, "-c", STOP_ON_REQUEST, str(record), *args[2:]], env=env, cwd=REPO,
                            capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
    assert result.returncode == 0 and "stopped" in result.stdout, result.stderr
    return int(record.read_text().split()[1])
