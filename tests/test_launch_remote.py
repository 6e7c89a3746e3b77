"""Nodes on other machines: a launch on host A with nodes on hosts B and C, started over SSH.

The hosts are Linux network namespaces with their own sshd (tests/netns_hosts.py);
the master runs on A.  These tests need root and run in CI.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Iterator

import psutil
import pytest

from conftest import SYSTEM_PYTHON, free_port, have_rospy, need_peer, wait_until
from netns_hosts import NetnsHost, NetnsHosts, make_hosts

VENV_BIN = str(Path(sys.executable).parent)
ROSTUI = str(Path(VENV_BIN) / "rostui")
PARAMIKO = "/usr/lib/python3/dist-packages/paramiko/"
#: What a machine with rostui but no ROS puts on its PATH as ``roslaunch`` (docs/launch.md).
ROSLAUNCH_SHIM = '#!/bin/sh\nexec rostui launch "$@"\n'

LISTENER = textwrap.dedent("""\
    import sys
    import rospy
    rospy.init_node("cross_host_listener")
    message = rospy.wait_for_message(sys.argv[1], rospy.AnyMsg, timeout=60)
    print("received %s from %s" % (message._connection_header["type"], message._connection_header["callerid"]),
          flush=True)
    """)


class LaunchRun:
    """A launch started on host A; its output is in a file so it can be read while it runs."""

    def __init__(self, host: NetnsHost, argv: list[str], env: dict[str, str], log: Path) -> None:
        self.log = log
        self.proc = host.popen(argv, env, stdout=open(log, "w"), stderr=subprocess.STDOUT,  # noqa: SIM115
                               start_new_session=True)

    def output(self) -> str:
        return self.log.read_text(errors="replace")

    def wait_for(self, pattern: str, what: str, timeout: float = 60.0) -> re.Match[str]:
        found: list[re.Match[str]] = []

        def seen() -> bool:
            match = re.search(pattern, self.output())
            if match:
                found.append(match)
            assert self.proc.poll() is None or match, f"the launch ended early:\n{self.output()}"
            return match is not None

        wait_until(seen, what, timeout)
        return found[0]

    def interrupt(self, timeout: float = 90.0) -> int:
        """Ctrl-C, as a terminal sends it, and wait for the launch to end."""
        if self.proc.poll() is None:
            os.kill(self.proc.pid, signal.SIGINT)
        return self.proc.wait(timeout)

    def kill(self) -> None:
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait(10)


def leftovers(host: NetnsHost) -> list[str]:
    """The command lines of every process on ``host`` other than its sshd listener."""
    found = []
    for pid in host.pids():
        if host.sshd is not None and pid == host.sshd.pid:
            continue
        try:
            found.append(" ".join(psutil.Process(pid).cmdline()) or f"pid {pid}")
        except psutil.NoSuchProcess:
            continue
    return found


def node_pids(host: NetnsHost, fragment: str) -> list[int]:
    """Pids of the processes on ``host`` whose command line contains ``fragment``."""
    pids = []
    for pid in host.pids():
        try:
            if fragment in " ".join(psutil.Process(pid).cmdline()):
                pids.append(pid)
        except psutil.NoSuchProcess:
            continue
    return pids


def host_env(hosts: NetnsHosts, host: NetnsHost, master_port: int, tmp_path: Path) -> dict[str, str]:
    """The environment of a program run on ``host`` by the test, with the master on host A."""
    env = hosts.client_env(dict(os.environ))
    home = tmp_path / f"ros_home_{host.name}_test"
    home.mkdir(exist_ok=True)
    env.update(ROS_MASTER_URI=f"http://{hosts['a'].address}:{master_port}/", ROS_IP=host.address,
               ROS_HOME=str(home), PYTHONUNBUFFERED="1", PATH=f"{VENV_BIN}:{os.environ['PATH']}")
    for key in ("ROS_HOSTNAME", "ROS_NAMESPACE"):
        env.pop(key, None)
    return env


@pytest.fixture
def three_hosts(tmp_path: Path) -> Iterator[NetnsHosts]:
    with make_hosts(tmp_path, ["a", "b", "c"], unreachable=["d"]) as hosts:
        yield hosts


def write_launch(path: Path, body: str) -> Path:
    path.write_text(f"<launch>\n{textwrap.dedent(body)}</launch>\n")
    return path


def test_nodes_on_two_other_hosts(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    need_peer(have_rospy(), "rospy (python3-rospy)")
    hosts = three_hosts
    a, b, c = hosts["a"], hosts["b"], hosts["c"]
    launch = write_launch(tmp_path / "robot.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{b.env_loader([VENV_BIN])}" user="root"/>
        <machine name="hostc" address="{c.address}" env-loader="{c.env_loader([VENV_BIN])}" timeout="20"/>
        <node machine="hostc" pkg="agitr" type="pubvel" name="pubvel" output="screen"/>
        <node machine="hostb" pkg="agitr" type="subpose" name="subpose" respawn="true"/>
        <node pkg="agitr" type="count" name="count"/>
        """)
    port = free_port()
    env_a = host_env(hosts, a, port, tmp_path)
    run = LaunchRun(a, [ROSTUI, "launch", str(launch), "--sigint-timeout", "5"], env_a, tmp_path / "launch.out")
    try:
        run.wait_for(r"process\[pubvel-\d+\]: started with pid", "pubvel to start on host C")
        first = run.wait_for(r"process\[subpose-\d+\]: started with pid \[(\d+)\]", "subpose to start on host B")

        def registered() -> bool:
            names = a.run([ROSTUI, "node", "list"], env_a).stdout.split()
            return {"/pubvel", "/subpose", "/count"} <= set(names)

        wait_until(registered, "every node (A, B and C) to register with the master on A")
        subpose_pids = node_pids(b, "subpose")
        assert subpose_pids and int(first.group(1)) in subpose_pids, "subpose runs on host B"
        assert node_pids(c, "pubvel"), "pubvel runs on host C"
        assert not node_pids(a, "pubvel") and not node_pids(a, "subpose"), "nothing remote runs on host A"
        # pubvel's screen output comes back to A's console.
        run.wait_for(r"Sending random velocity command", "pubvel's output on A")

        # A real rospy subscriber on host B receives pubvel's messages from host C.
        (tmp_path / "listener.py").write_text(LISTENER)
        heard = b.run([SYSTEM_PYTHON, str(tmp_path / "listener.py"), "/turtle1/command_velocity"],
                      host_env(hosts, b, port, tmp_path), timeout=90)
        assert "received turtlesim/Velocity from /pubvel" in heard.stdout, heard.stdout + heard.stderr

        # A node killed on B: A reports its death and the child on B respawns it.
        os.kill(int(first.group(1)), signal.SIGKILL)
        run.wait_for(r"\[subpose-\d+\] process has died \[pid \d+, exit code -9\] on machine \[hostb\]",
                     "A to report subpose's death on host B")
        again = run.wait_for(r"process\[subpose-\d+\]: restarted with pid \[(\d+)\]", "subpose to respawn on B")
        assert int(again.group(1)) != int(first.group(1))
        wait_until(lambda: int(again.group(1)) in node_pids(b, "subpose"), "the new subpose on host B")

        # Ctrl-C on A stops every node on every host; nothing stays behind on B or C.
        assert run.interrupt() == 0, run.output()
        for host in (b, c):
            wait_until(lambda host=host: not leftovers(host), f"host {host.name} to have no process left", 30)
        assert not node_pids(a, "agitr"), "no node left on host A"
    finally:
        run.kill()


def test_a_host_that_does_not_answer(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    hosts = three_hosts
    a, b, d = hosts["a"], hosts["b"], hosts["d"]
    launch = write_launch(tmp_path / "far.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{b.env_loader([VENV_BIN])}"/>
        <machine name="faraway" address="{d.address}" timeout="3"/>
        <node machine="hostb" pkg="agitr" type="subpose" name="subpose"/>
        <node machine="faraway" pkg="agitr" type="pubvel" name="pubvel"/>
        <node pkg="agitr" type="count" name="count"/>
        """)
    env_a = host_env(hosts, a, free_port(), tmp_path)
    result = a.run([ROSTUI, "launch", str(launch)], env_a, timeout=120)
    assert result.returncode == 1
    errors = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(errors) == 1, result.stderr
    assert errors[0].startswith(f"rostui launch: {launch}:3: cannot start nodes on machine [faraway] "
                                f"({d.address}:22): "), errors[0]
    assert "process[" not in result.stdout, "no node started anywhere"
    wait_until(lambda: not leftovers(b), "host B to have no process left", 30)


def test_a_host_missing_from_known_hosts_is_refused(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    hosts = three_hosts
    a, c = hosts["a"], hosts["c"]
    known = hosts.home / ".ssh" / "known_hosts"
    known.write_text("".join(line + "\n" for line in known.read_text().splitlines()
                             if not line.startswith(c.address + " ")))
    launch = write_launch(tmp_path / "unknown.launch", f"""\
        <machine name="hostc" address="{c.address}" env-loader="{c.env_loader([VENV_BIN])}"/>
        <node machine="hostc" pkg="agitr" type="pubvel" name="pubvel"/>
        """)
    result = a.run([ROSTUI, "launch", str(launch)], host_env(hosts, a, free_port(), tmp_path), timeout=120)
    assert result.returncode == 1
    assert f"cannot start nodes on machine [hostc] ({c.address}:22): Host key verification failed." \
        in result.stderr, result.stderr
    assert c.address not in known.read_text(), "the unknown host key was not added"
    wait_until(lambda: not leftovers(c), "host C to have no process left", 30)


def test_real_roslaunch_drives_rostui_children(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    """Debian's roslaunch on A starts `roslaunch -c` on B, which the env-loader there makes rostui's child."""
    need_peer(have_rospy() and Path(PARAMIKO).exists(), "roslaunch's SSH (python3-paramiko) with rospy")
    hosts = three_hosts
    a, b = hosts["a"], hosts["b"]
    shim = tmp_path / "rostui-roslaunch"
    shim.mkdir()
    (shim / "roslaunch").write_text(ROSLAUNCH_SHIM)
    (shim / "roslaunch").chmod(0o755)
    launch = write_launch(tmp_path / "robot.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{b.env_loader([str(shim), VENV_BIN])}"/>
        <node machine="hostb" pkg="agitr" type="pubvel" name="pubvel" respawn="true"/>
        """)
    port = free_port()
    env_a = host_env(hosts, a, port, tmp_path)
    env_a["PATH"] = "/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin"  # only Debian's ROS on A
    run = LaunchRun(a, ["roslaunch", str(launch), "--sigint-timeout", "5"], env_a, tmp_path / "launch.out")
    try:
        first = run.wait_for(r"process\[pubvel-\d+\]: started with pid \[(\d+)\]", "pubvel to start on B")
        assert int(first.group(1)) in node_pids(b, "pubvel"), "rostui's child runs pubvel on host B"
        assert node_pids(b, "rostui launch -c"), "the child on B is rostui's"
        (tmp_path / "listener.py").write_text(LISTENER)
        heard = a.run([SYSTEM_PYTHON, str(tmp_path / "listener.py"), "/turtle1/command_velocity"],
                      host_env(hosts, a, port, tmp_path), timeout=90)
        assert "received turtlesim/Velocity from /pubvel" in heard.stdout, heard.stdout + heard.stderr

        os.kill(int(first.group(1)), signal.SIGKILL)
        run.wait_for(r"\[pubvel-\d+\] process has died \[pid \d+, exit code -9", "roslaunch to hear of the death")
        again = run.wait_for(r"process\[pubvel-\d+\]: restarted with pid \[(\d+)\]", "the respawn on B")
        assert int(again.group(1)) != int(first.group(1))

        assert run.interrupt() == 0, run.output()
        wait_until(lambda: not leftovers(b), "host B to have no process left", 30)
    finally:
        run.kill()


def test_rostui_drives_a_real_roslaunch_child(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    """rostui on A starts Debian's `roslaunch -c` on C, a machine whose PATH has ROS but no rostui."""
    need_peer(have_rospy(), "rospy (python3-rospy)")
    hosts = three_hosts
    a, b, c = hosts["a"], hosts["b"], hosts["c"]
    launch = write_launch(tmp_path / "robot.launch", f"""\
        <machine name="hostc" address="{c.address}" env-loader="{c.env_loader([])}"/>
        <node machine="hostc" pkg="rostopic" type="rostopic" name="pub" respawn="true"
              args="pub -r 5 /chatter std_msgs/String hello"/>
        """)
    port = free_port()
    env_a = host_env(hosts, a, port, tmp_path)
    run = LaunchRun(a, [ROSTUI, "launch", str(launch), "--sigint-timeout", "5"], env_a, tmp_path / "launch.out")
    try:
        first = run.wait_for(r"process\[pub-\d+\]: started with pid \[(\d+)\]", "pub to start on C")
        assert int(first.group(1)) in node_pids(c, "/chatter"), "roslaunch's child runs the node on host C"
        assert node_pids(c, "/usr/bin/roslaunch -c"), "the child on C is Debian's roslaunch"
        (tmp_path / "listener.py").write_text(LISTENER)
        heard = b.run([SYSTEM_PYTHON, str(tmp_path / "listener.py"), "/chatter"],
                      host_env(hosts, b, port, tmp_path), timeout=90)
        assert "received std_msgs/String from /pub" in heard.stdout, heard.stdout + heard.stderr

        os.kill(int(first.group(1)), signal.SIGKILL)
        run.wait_for(r"\[pub-\d+\] process has died \[pid \d+, exit code -9\] on machine \[hostc\]",
                     "A to report the death on C")
        wait_until(lambda: any(pid != int(first.group(1)) for pid in node_pids(c, "/chatter")),
                   "roslaunch's child to respawn the node on C")
        run.wait_for(r"process\[pub-\d+\]: started with pid \[(?!" + first.group(1) + r"\])\d+\]",
                     "A to hear of the new process")

        assert run.interrupt() == 0, run.output()
        wait_until(lambda: not leftovers(c), "host C to have no process left", 30)
    finally:
        run.kill()


def test_a_required_node_on_another_host_ends_the_launch(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    hosts = three_hosts
    a, b, c = hosts["a"], hosts["b"], hosts["c"]
    launch = write_launch(tmp_path / "required.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{b.env_loader([VENV_BIN])}"/>
        <machine name="hostc" address="{c.address}" env-loader="{c.env_loader([VENV_BIN])}"/>
        <node machine="hostb" pkg="agitr" type="subpose" name="brain" required="true"
              launch-prefix="sh -c 'sleep 3; exit 3' --"/>
        <node machine="hostc" pkg="agitr" type="pubvel" name="pubvel"/>
        """)
    env_a = host_env(hosts, a, free_port(), tmp_path)
    run = LaunchRun(a, [ROSTUI, "launch", str(launch), "--sigint-timeout", "5"], env_a, tmp_path / "launch.out")
    try:
        assert run.proc.wait(120) == 1, run.output()
        output = run.output()
        assert re.search(r"\[brain-\d+\] process has died \[pid \d+, exit code 3\] on machine \[hostb\]", output), output
        assert re.search(r"REQUIRED process \[brain-\d+\] has died! Initiating shutdown!", output), output
        for host in (b, c):
            wait_until(lambda host=host: not leftovers(host), f"host {host.name} to have no process left", 30)
    finally:
        run.kill()


def test_killing_the_launcher_stops_the_remote_nodes(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    """Without a word from the parent (SIGKILL), the SSH connection's end stops each child and its nodes."""
    hosts = three_hosts
    a, b = hosts["a"], hosts["b"]
    launch = write_launch(tmp_path / "robot.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{b.env_loader([VENV_BIN])}"/>
        <node machine="hostb" pkg="agitr" type="pubvel" name="pubvel"/>
        """)
    env_a = host_env(hosts, a, free_port(), tmp_path)
    run = LaunchRun(a, [ROSTUI, "launch", str(launch)], env_a, tmp_path / "launch.out")
    try:
        run.wait_for(r"process\[pubvel-\d+\]: started with pid", "pubvel to start on B")
        assert node_pids(b, "pubvel")
        os.kill(run.proc.pid, signal.SIGKILL)
        run.proc.wait(10)
        for host in (a, b):
            wait_until(lambda host=host: not leftovers(host), f"host {host.name} to have no process left", 40)
    finally:
        run.kill()


@pytest.mark.parametrize("parent", ["rostui", "roslaunch"])
def test_one_file_with_a_rostui_host_and_a_ros_host(three_hosts: NetnsHosts, tmp_path: Path, parent: str) -> None:
    """The same file under either launcher: B has only rostui (its `roslaunch` is rostui), C has only ROS."""
    need_peer(have_rospy() and Path(PARAMIKO).exists(), "roslaunch's SSH (python3-paramiko) with rospy")
    hosts = three_hosts
    a, b, c = hosts["a"], hosts["b"], hosts["c"]
    shim = tmp_path / "rostui-roslaunch"
    shim.mkdir()
    (shim / "roslaunch").write_text(ROSLAUNCH_SHIM)
    (shim / "roslaunch").chmod(0o755)
    launch = write_launch(tmp_path / "mixed.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{b.env_loader([str(shim), VENV_BIN])}"/>
        <machine name="hostc" address="{c.address}" env-loader="{c.env_loader([])}"/>
        <node machine="hostb" pkg="agitr" type="pubvel" name="pubvel"/>
        <node machine="hostc" pkg="rostopic" type="rostopic" name="pub" args="pub -r 5 /chatter std_msgs/String hi"/>
        """)
    port = free_port()
    env_a = host_env(hosts, a, port, tmp_path)
    if parent == "roslaunch":
        env_a["PATH"] = "/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin"
        argv = ["roslaunch", str(launch), "--sigint-timeout", "5"]
    else:
        argv = [ROSTUI, "launch", str(launch), "--sigint-timeout", "5"]
    run = LaunchRun(a, argv, env_a, tmp_path / "launch.out")
    try:
        run.wait_for(r"process\[pubvel-\d+\]: started with pid", "pubvel to start on B")
        run.wait_for(r"process\[pub-\d+\]: started with pid", "pub to start on C")
        assert node_pids(b, "rostui launch -c") or node_pids(b, "rostui launch --child"), "B runs rostui's child"
        assert node_pids(c, "/usr/bin/roslaunch -c"), "C runs Debian's roslaunch child"
        (tmp_path / "listener.py").write_text(LISTENER)
        on_b = b.run([SYSTEM_PYTHON, str(tmp_path / "listener.py"), "/chatter"], host_env(hosts, b, port, tmp_path),
                     timeout=90)
        assert "received std_msgs/String from /pub" in on_b.stdout, on_b.stdout + on_b.stderr
        on_a = a.run([SYSTEM_PYTHON, str(tmp_path / "listener.py"), "/turtle1/command_velocity"],
                     host_env(hosts, a, port, tmp_path), timeout=90)
        assert "received turtlesim/Velocity from /pubvel" in on_a.stdout, on_a.stdout + on_a.stderr
        assert run.interrupt() == 0, run.output()
        for host in (b, c):
            wait_until(lambda host=host: not leftovers(host), f"host {host.name} to have no process left", 30)
    finally:
        run.kill()


MONITOR_DRIVER = textwrap.dedent("""\
    import asyncio, json, sys
    from rostui.launch.files import LaunchRequest
    from rostui.launch.supervisor import SupervisorOptions, load_supervisor

    async def main():
        options = SupervisorOptions(capture=True, handle_signals=False, stay_when_all_ended=True, sigint_timeout=5)
        supervisor = load_supervisor(LaunchRequest([sys.argv[1]]), options, reporter=lambda *_: None)
        run = asyncio.get_running_loop().create_task(supervisor.run())
        far = None
        for _ in range(600):
            await asyncio.sleep(0.1)
            if supervisor.processes:
                far = supervisor.processes[0]
                streams = {line.stream for line in far.output.since(0)}
                if {"stdout", "stderr"} <= streams and far.running:
                    break
        lines = [[line.stream, line.text] for line in far.output.since(0)]
        state, pid, local = far.state.value, far.pid, far.local
        supervisor.request_stop()
        await run
        print(json.dumps({"lines": lines, "state": state, "pid": pid, "local": local,
                          "after": far.state.value}))

    asyncio.run(main())
    """)


def test_the_monitor_gets_a_remote_nodes_output(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    """With --tui's capture, a remote node's stdout and stderr lines land in its own output ring."""
    import json

    hosts = three_hosts
    a, b = hosts["a"], hosts["b"]
    launch = write_launch(tmp_path / "robot.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{b.env_loader([VENV_BIN])}"/>
        <node machine="hostb" pkg="agitr" type="pubvel" name="pubvel" output="screen"
              launch-prefix="sh -c 'echo warming up &gt;&amp;2; exec &quot;$@&quot;' --"/>
        """)
    (tmp_path / "driver.py").write_text(MONITOR_DRIVER)
    result = a.run([sys.executable, str(tmp_path / "driver.py"), str(launch)], host_env(hosts, a, free_port(), tmp_path),
                   timeout=120)
    assert result.returncode == 0, result.stderr
    seen = json.loads(result.stdout.splitlines()[-1])
    assert ["stderr", "warming up"] in seen["lines"]
    assert any(stream == "stdout" and "Sending random velocity command" in text for stream, text in seen["lines"])
    assert seen["state"] == "running" and seen["local"] is False
    assert isinstance(seen["pid"], int) and seen["pid"] > 0, "the node's pid on host B"
    assert seen["after"] == "stopped"
    wait_until(lambda: not leftovers(b), "host B to have no process left", 30)


def test_a_missing_env_loader_is_one_error(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    hosts = three_hosts
    a, b = hosts["a"], hosts["b"]
    missing = tmp_path / "nowhere" / "env.sh"
    launch = write_launch(tmp_path / "robot.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{missing}"/>
        <node machine="hostb" pkg="agitr" type="pubvel" name="pubvel"/>
        """)
    result = a.run([ROSTUI, "launch", str(launch)], host_env(hosts, a, free_port(), tmp_path), timeout=120)
    assert result.returncode == 1
    errors = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(errors) == 1, result.stderr
    assert errors[0].startswith(f"rostui launch: {launch}:2: cannot start nodes on machine [hostb] "
                                f"({b.address}:22): "), errors[0]
    assert str(missing) in errors[0], errors[0]
    wait_until(lambda: not leftovers(b), "host B to have no process left", 30)


def test_a_host_cut_off_the_network_stops_its_nodes(three_hosts: NetnsHosts, tmp_path: Path) -> None:
    """B loses its network: its child stops its nodes (the parent no longer answers), and A reports them lost."""
    hosts = three_hosts
    a, b = hosts["a"], hosts["b"]
    launch = write_launch(tmp_path / "robot.launch", f"""\
        <machine name="hostb" address="{b.address}" env-loader="{b.env_loader([VENV_BIN])}"/>
        <node machine="hostb" pkg="agitr" type="pubvel" name="pubvel"/>
        <node pkg="agitr" type="count" name="count"/>
        """)
    run = LaunchRun(a, [ROSTUI, "launch", str(launch)], host_env(hosts, a, free_port(), tmp_path),
                    tmp_path / "launch.out")
    try:
        run.wait_for(r"process\[pubvel-\d+\]: started with pid", "pubvel to start on B")
        subprocess.run(b.command(["ip", "link", "set", "eth0", "down"]), check=True)
        wait_until(lambda: not node_pids(b, "pubvel") and not node_pids(b, "launch --child"),
                   "the child on B to stop its node and exit", 120)
        run.wait_for(r"the connection to machine \[hostb\] closed", "A to report the lost connection", 120)
        assert run.proc.poll() is None, "the launch goes on with its local node"
        assert run.interrupt() == 0, run.output()
    finally:
        run.kill()
