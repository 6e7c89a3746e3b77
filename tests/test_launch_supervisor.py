"""rostui launch's supervisor: output routing, params before nodes, respawn, required, Ctrl-C, no orphans."""

from __future__ import annotations

import signal
import socket
import subprocess
import time
import sys
from pathlib import Path
from typing import Iterator

import psutil
import pytest

from conftest import master_port, wait_for_port, wait_until
from launch_helpers import CORPUS, Launch, launch_env, run_rostui

RUN = CORPUS / "run"


@pytest.fixture
def env(ros_env: dict[str, str]) -> dict[str, str]:
    return launch_env(ros_env)


@pytest.fixture
def launches(tmp_path: Path) -> Iterator[list[Launch]]:
    started: list[Launch] = []
    yield started
    for launch in started:
        if launch.proc.poll() is None:
            launch.proc.kill()
            launch.proc.wait()


def start(launches: list[Launch], args: list[str], env: dict[str, str], tmp: Path) -> Launch:
    launch = Launch(args, env, tmp)
    launches.append(launch)
    return launch


def pids_in(path: Path) -> list[int]:
    return [int(p) for p in path.read_text().split()] if path.exists() and path.read_text().strip() else []


def gone(pids: list[int]) -> bool:
    return all(not psutil.pid_exists(p) or psutil.Process(p).status() == psutil.STATUS_ZOMBIE for p in pids)


def run_dir(env: dict[str, str]) -> Path:
    dirs = [d for d in (Path(env["ROS_HOME"]) / "log").iterdir() if d.is_dir() and d.name != "latest"]
    assert len(dirs) == 1, dirs
    return dirs[0]


def test_output_routing_and_clean_stop(env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    launch = start(launches, [str(RUN / "output.launch")], env, tmp_path)
    wait_until(lambda: "stdout of shown" in launch.out, "the screen node's stdout on the console")
    wait_until(lambda: launch.err.count("stderr of") == 3, "every node's stderr on the console")
    logs = run_dir(env)
    wait_until(lambda: (logs / "logged-1-stdout.log").exists()
               and "stdout of logged" in (logs / "logged-1-stdout.log").read_text(), "the log node's stdout file")
    assert "stdout of nested" in (logs / "deep-nested-3-stdout.log").read_text()
    assert "stdout of logged" not in launch.out and "stdout of nested" not in launch.out
    assert not (logs / "shown-2-stdout.log").exists()
    children = launch.descendants()
    assert len([c for c in children if c.name() == "sleep"]) == 3
    assert launch.interrupt() == 0
    assert gone([c.pid for c in children])


def test_screen_option_sends_every_stdout_to_console(env: dict[str, str], launches: list[Launch],
                                                      tmp_path: Path) -> None:
    launch = start(launches, ["--screen", str(RUN / "output.launch")], env, tmp_path)
    wait_until(lambda: all(f"stdout of {n}" in launch.out for n in ("logged", "shown", "nested")), "all stdout")
    assert not list(run_dir(env).glob("*-stdout.log"))
    launch.interrupt()


def test_params_are_set_before_nodes_start(env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    launch = start(launches, ["-v", "launch_corpus", "params.launch"], env, tmp_path)
    wait_until(lambda: "uris=" in launch.out, "the reader's report", timeout=60)
    assert "launch_value=set before start" in launch.out
    assert "private=42" in launch.out
    out = launch.out
    assert out.index("set parameter [/reader/private_value]") < out.index("process[reader-1]: started")
    assert "/roslaunch/uris/host_" in launch.out
    assert "started master (in this process)" in launch.out
    launch.interrupt()


def test_running_master_is_reused(env: dict[str, str], rostui_core: subprocess.Popen, launches: list[Launch],
                                  tmp_path: Path) -> None:
    launch = start(launches, ["launch_corpus", "params.launch"], env, tmp_path)
    wait_until(lambda: "uris=" in launch.out, "the reader's report", timeout=60)
    assert "started master" not in launch.out
    assert "launch_value=set before start" in launch.out
    launch.interrupt()
    assert rostui_core.poll() is None


def test_respawn_restarts_a_dying_node(env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    count = tmp_path / "count.txt"
    launch = start(launches, [str(RUN / "respawn.launch"), f"count_file:={count}"], env, tmp_path)
    wait_until(lambda: count.exists() and len(count.read_text().splitlines()) >= 3, "three starts", timeout=90)
    assert "exit code 3" in launch.err
    assert "restarting process" in launch.out
    launch.interrupt()


def test_required_node_ends_the_launch(env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    pid_file = tmp_path / "bystander.pid"
    launch = start(launches, [str(RUN / "required.launch"), f"pid_file:={pid_file}"], env, tmp_path)
    wait_until(lambda: len(pids_in(pid_file)) == 2, "the bystander's pids")
    bystander = pids_in(pid_file)
    launch.proc.wait(timeout=60)  # no signal: the required node's exit ends the launch
    assert "REQUIRED process [boss-2] has died!" in launch.err
    assert gone(bystander)


def test_node_ignoring_sigint_is_killed(env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    stubborn, polite = tmp_path / "stubborn.pid", tmp_path / "polite.pid"
    launch = start(launches, ["--sigint-timeout", "1", "--sigterm-timeout", "1", str(RUN / "stubborn.launch"),
                              f"stubborn_file:={stubborn}", f"sleeper_file:={polite}"], env, tmp_path)
    wait_until(lambda: len(pids_in(stubborn)) == 2 and len(pids_in(polite)) == 2, "both nodes' pids")
    assert launch.interrupt() == 0
    assert "[stubborn-1] did not stop on SIGINT: sent SIGKILL" in launch.err
    assert gone(pids_in(stubborn) + pids_in(polite))


def test_load_error_starts_nothing(env: dict[str, str], tmp_path: Path) -> None:
    result = run_rostui([str(CORPUS / "errors" / "respawn_required.launch")], env)
    assert result.returncode == 1
    assert result.stderr.strip().endswith("respawn and required cannot both be set to true")
    assert result.stdout == ""
    with socket.socket() as probe:
        assert probe.connect_ex(("127.0.0.1", master_port(env))) != 0  # no master was started


def test_a_remote_machine_that_cannot_be_reached_is_one_error(env: dict[str, str], tmp_path: Path) -> None:
    """192.0.2.10 (TEST-NET-1) never answers: one line names the machine, and no node starts.

    tests/test_launch_remote.py runs nodes on other hosts for real.
    """
    (tmp_path / "ssh_config").write_text("")  # never the real ~/.ssh/config
    result = run_rostui([str(RUN / "remote.launch")], {**env, "ROSTUI_SSH_CONFIG": str(tmp_path / "ssh_config")},
                        timeout=120)
    assert result.returncode == 1
    errors = result.stderr.strip().splitlines()
    assert len(errors) == 1, result.stderr
    assert errors[0].startswith(f"rostui launch: {RUN / 'remote.launch'}:2: cannot start nodes on machine [faraway] "
                                "(robot@192.0.2.10:22): "), errors[0]
    assert "process[" not in result.stdout


def test_rosparam_commands_and_clear_params_run_before_params(env: dict[str, str], rostui_core: subprocess.Popen,
                                                    launches: list[Launch], tmp_path: Path) -> None:
    from cli_helpers import rostui

    for key, value in (("/stale", "going"), ("/old/a", "1"), ("/old/b", "two"), ("/cleared/old", "x"),
                       ("/reader/old", "y")):
        assert rostui(["param", "set", key, value], env).returncode == 0
    dump = tmp_path / "dump.yaml"
    launch = start(launches, [str(RUN / "rosparam_commands.launch"), f"dump_file:={dump}"], env, tmp_path)
    wait_until(lambda: "uris=" in launch.out, "the reader's report", timeout=60)
    assert dump.read_text().split() == ["a:", "1", "b:", "two"]
    assert rostui(["param", "get", "/stale"], env).returncode != 0
    assert rostui(["param", "get", "/fresh"], env).stdout.strip() == "from the launch"
    for cleared in ("/cleared/old", "/reader/old"):  # clear_params on a group and on a node
        assert rostui(["param", "get", cleared], env).returncode != 0
    assert rostui(["param", "get", "/cleared/new"], env).stdout.strip() == "1"
    import xmlrpc.client

    blob = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getParam("/t", "/blob")[2]
    assert blob.data == (CORPUS / "config" / "blob.bin").read_bytes()
    launch.interrupt()


def test_wait_waits_for_a_master(env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    launch = start(launches, ["--wait", "launch_corpus", "params.launch"], env, tmp_path)
    wait_until(lambda: "waiting for a master" in launch.out, "the launcher to wait")
    assert "process[" not in launch.out
    core = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(master_port(env))], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_until(lambda: "launch_value=set before start" in launch.out, "the nodes to start", timeout=60)
        assert "started master" not in launch.out
        launch.interrupt()
    finally:
        core.send_signal(signal.SIGINT)
        core.wait(timeout=30)


def test_port_option_sets_the_master_port(env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    from conftest import free_port

    port = free_port()
    launch = start(launches, ["-p", str(port), "launch_corpus", "params.launch"], env, tmp_path)
    wait_until(lambda: "launch_value=" in launch.out, "the reader's report", timeout=60)
    assert f"started master (in this process) and /rosout at http://127.0.0.1:{port}/" in launch.out
    assert "launch_value=set before start" in launch.out  # the node was pointed at that master
    launch.interrupt()


def test_rosbag_record_in_a_launch_file(env: dict[str, str], launches: list[Launch], tmp_path: Path) -> None:
    """A `<node pkg="rosbag" type="record">` records until Ctrl-C and leaves a readable bag."""
    from cli_helpers import rostui

    bag = tmp_path / "out.bag"
    launch = start(launches, [str(RUN / "record.launch"), f"bag:={bag}"], env, tmp_path)
    wait_until(lambda: "process[recorder-1]: started" in launch.out, "the recorder to start")
    wait_for_port(master_port(env))
    publisher = subprocess.Popen([sys.executable, "-m", "rostui", "topic", "pub", "-r", "20", "/chatter",
                                  "std_msgs/String", "data: hi"], env=env, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL)
    try:
        wait_until(lambda: bag.exists() or Path(str(bag) + ".active").exists(), "the bag file", timeout=60)
        time.sleep(2.0)  # let some messages reach the bag; the assertion below does not depend on how many
    finally:
        publisher.send_signal(signal.SIGINT)
        publisher.wait(timeout=30)
    assert launch.interrupt() == 0
    info = rostui(["bag", "info", str(bag)], env)
    assert info.returncode == 0, info.stderr
    assert "/chatter" in info.stdout and "std_msgs/String" in info.stdout
