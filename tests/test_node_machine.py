"""`rostui node machine [HOST]` prints what Debian's `rosnode machine` prints on the same graph."""

from __future__ import annotations

import socket
import subprocess

import pytest

from cli_helpers import rostui
from conftest import need_command
from interop_helpers import Spawn, run_tool, spawn, wait_for_node  # noqa: F401  (spawn is a fixture)


def _both(args: list[str], env: dict[str, str]) -> tuple[subprocess.CompletedProcess, subprocess.CompletedProcess]:
    return rostui(["node", "machine", *args], env), run_tool(["rosnode", "machine", *args], env, check=False)


def test_machines_and_their_nodes_equal_rosnode(ros_env: dict[str, str], real_roscore: subprocess.Popen,
                                                spawn: Spawn) -> None:
    """Nodes advertising three host spellings: the host list and each host's nodes are rosnode's."""
    need_command("rosnode")
    need_command("rostopic")
    hostname = socket.gethostname()
    for label, variable, value in (("by_ip", "ROS_IP", "127.0.0.1"), ("by_name", "ROS_HOSTNAME", "localhost"),
                                   ("by_host", "ROS_HOSTNAME", hostname)):
        env = {k: v for k, v in ros_env.items() if k not in ("ROS_IP", "ROS_HOSTNAME")}
        env[variable] = value
        spawn(["rostopic", "pub", "-r", "1", f"/{label}_topic", "std_msgs/String", "hi", f"__name:={label}"],
              label=label, env=env)
    for label in ("by_ip", "by_name", "by_host"):
        wait_for_node(ros_env, f"/{label}")
    ours, theirs = _both([], ros_env)
    assert theirs.returncode == 0, theirs.stderr
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout == theirs.stdout
    assert {"127.0.0.1", "localhost", hostname} <= set(ours.stdout.split())
    for host in sorted({"127.0.0.1", "localhost", hostname}):
        ours, theirs = _both([host], ros_env)
        assert theirs.returncode == 0, theirs.stderr
        assert ours.returncode == 0, ours.stderr
        assert ours.stdout == theirs.stdout, host
        assert "/by_ip" in ours.stdout.split() or host == hostname


def test_unknown_host_fails_like_rosnode(ros_env: dict[str, str], real_roscore: subprocess.Popen) -> None:
    need_command("rosnode")
    ours, theirs = _both(["no-such-host.invalid"], ros_env)
    assert theirs.returncode != 0
    assert ours.returncode == 1 and ours.stdout == ""
    assert ours.stderr.strip() == "ERROR: cannot resolve machine name [no-such-host.invalid] to address"


def test_without_a_master_one_line(ros_env: dict[str, str]) -> None:
    result = rostui(["node", "machine"], ros_env)
    assert result.returncode != 0
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
