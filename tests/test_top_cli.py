"""`rostui top --once` against real nodes: a rospy and a roscpp node on this host (their pids as the processes
have them, their CPU, memory, threads and connections measured), and a node registered from another host (listed
as remote), under `rostui core` and a real roscore.
"""

from __future__ import annotations

import subprocess
from typing import Any

import psutil

from conftest import rostui_cmd
from interop_helpers import roscpp_peer_bin, spawn  # noqa: F401  (fixtures)
from top_helpers import REMOTE_NODE, register_remote_node, start_nodes


def top_once(env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    """`rostui top --once ARGS`."""
    return subprocess.run(rostui_cmd("top", "--once", "--interval", "0.3", *args), env=env, capture_output=True,
                          text=True, timeout=90)


def table(stdout: str) -> dict[str, list[str]]:
    """Each row's cells by node name (the last column, WHERE, may hold spaces)."""
    lines = stdout.splitlines()
    assert lines[0].split() == ["NODE", "PID", "CPU%", "MEM", "THREADS", "CONNS", "WHERE"], stdout
    rows = {}
    for line in lines[1:]:
        name, pid, cpu, mem, threads, conns, *where = line.split()
        rows[name] = [pid, cpu, mem, threads, conns, " ".join(where)]
    return rows


def test_nodes_here_are_measured_and_a_remote_one_is_listed(any_master: str, ros_env: dict[str, str], spawn: Any,
                                                            roscpp_peer_bin: Any) -> None:
    rospy_node, rospy_name, roscpp_node, roscpp_name = start_nodes(spawn, roscpp_peer_bin, ros_env)
    register_remote_node(ros_env)
    done = top_once(ros_env, "--sort", "name")
    assert done.returncode == 0, done.stderr
    rows = table(done.stdout)
    assert list(rows) == sorted(rows), "--sort name"
    for name, peer in ((rospy_name, rospy_node), (roscpp_name, roscpp_node)):
        pid, cpu, mem, threads, conns, where = rows[name]
        process = psutil.Process(peer.proc.pid)
        assert int(pid) == peer.proc.pid and where == "here", rows[name]
        assert float(cpu) >= 0.0 and mem.endswith("M"), rows[name]
        assert abs(float(mem[:-1]) - process.memory_info().rss / 2 ** 20) < 20, rows[name]
        assert abs(int(threads) - process.num_threads()) <= 3, rows[name]  # rospy's threads come and go
        assert int(conns) >= 1, rows[name]  # its XML-RPC and TCPROS servers, the master's connection
    assert rows[REMOTE_NODE][0] == "-" and rows[REMOTE_NODE][-1].startswith("remote (192.0.2.1)"), rows[REMOTE_NODE]
    assert "/rosout" in rows


def test_errors_are_one_line(ros_env: dict[str, str]) -> None:
    no_master = top_once(ros_env)
    assert no_master.returncode == 1 and len(no_master.stderr.strip().splitlines()) == 1, no_master.stderr
    assert "master" in no_master.stderr.lower()
    for args, said in ((["--sort", "pid"], "unknown sort 'pid': choose cpu, memory or name"),
                       (["--interval", "0"], "--interval must be more than 0 seconds")):
        done = top_once(ros_env, *args)
        assert done.returncode != 0 and said in done.stderr and len(done.stderr.strip().splitlines()) == 1, \
            done.stderr
