"""The pieces of remote launch that need no second host: the XML a child gets, labels, output lines, quoting."""

from __future__ import annotations

import asyncio
import os
import subprocess
from pathlib import Path

from rostui.apps.launchmon.rows import node_row
from rostui.launch.loader import XmlLoader
from rostui.launch.model import LaunchConfig, Machine, NodeSpec
from rostui.launch.process import ProcessPlan
from rostui.launch.remote_child import ChildLauncher
from rostui.launch.remote_parent import RemoteProcess, printable
from rostui.launch.remote_protocol import (
    child_command, format_output_line, label_matches, nodes_xml, output_line, started_pid,
)
from rostui.launch.ssh import SshTarget, ssh_argv
from rostui.launch.supervisor import Supervisor, SupervisorOptions


def test_the_xml_a_child_gets_loads_back_to_the_same_nodes(tmp_path: Path) -> None:
    node = NodeSpec(package="agitr", type="pubvel", name="$(anon vel)", namespace="/robot/",
                    args='--say "a & b" <c>', remaps=[("cmd_vel", "/robot/cmd")], env=[("GREETING", "it's \"x\"")],
                    machine="far", respawn=True, respawn_delay=2.5, output="screen", launch_prefix="nice -n 5")
    xml = nodes_xml([node], {"vel": "vel_host_1_2"})
    path = tmp_path / "child.launch"
    path.write_text(xml)
    config = LaunchConfig()
    XmlLoader().load(str(path), config, {})
    [back] = config.nodes
    assert (back.package, back.type, back.name, back.namespace) == ("agitr", "pubvel", "vel_host_1_2", "/robot/")
    assert back.args == '--say "a & b" <c>'
    assert back.remaps == [("cmd_vel", "/robot/cmd")]
    assert back.env == [("GREETING", "it's \"x\"")]
    assert (back.respawn, back.respawn_delay, back.output, back.launch_prefix) == (True, 2.5, "screen", "nice -n 5")
    assert back.machine is None and not config.params


def test_screen_sends_every_remote_node_to_the_screen() -> None:
    assert 'output="screen"' in nodes_xml([NodeSpec(package="p", type="t", name="n")], {}, screen=True)
    assert "output=" not in nodes_xml([NodeSpec(package="p", type="t", name="n")], {})


def test_labels_of_rostui_and_roslaunch_children_name_their_nodes() -> None:
    node = NodeSpec(package="p", type="t", name="talker", namespace="/robot/arm/")
    assert label_matches("robot-arm-talker-3", node)  # rostui's label
    assert label_matches("robot/arm/talker-12", node)  # roslaunch's
    assert not label_matches("robot-arm-talker", node)
    assert not label_matches("robot-arm-walker-3", node)
    assert started_pid("process[robot/arm/talker-3]: started with pid [4711]") == ("robot/arm/talker-3", 4711)
    assert started_pid("process[talker-1]: restarted with pid [12]") == ("talker-1", 12)
    assert started_pid("[talker-1] restarting process") is None


def test_output_lines_carry_their_label_and_roslaunch_lines_do_not_pass_for_them() -> None:
    assert output_line(format_output_line("talker-1", "[ INFO] hello\tworld")) == ("talker-1", "[ INFO] hello\tworld")
    assert output_line("[talker-1] restarting process") is None  # a real roslaunch child's own line
    assert output_line("plain") is None and output_line("[]\tx") is None


def test_a_peers_text_reaches_the_console_without_escapes() -> None:
    assert printable("\x1b[31mred\x1b[0m \x1b]0;title\x07bell\x00") == "red ]0;titlebell"
    assert len(printable("x" * 100000)) == 16384


def test_the_remote_command_survives_the_remote_shell(tmp_path: Path) -> None:
    """What ssh would hand the remote shell: run it with sh and a `rostui` that prints its arguments."""
    fake = tmp_path / "bin"
    fake.mkdir()
    (fake / "rostui").write_text('#!/bin/sh\nprintf "%s\\n" "$ROS_MASTER_URI" "$@"\n')
    (fake / "rostui").chmod(0o755)
    loader = tmp_path / "env loader.sh"
    loader.write_text(f'#!/bin/sh\nexport PATH="{fake}:$PATH"\nexec "$@"\n')
    loader.chmod(0o755)
    command = child_command("10.0.0.2-0", "http://10.0.0.1:4242/", "run 'id'", "http://10.0.0.1:11311/", 15.0, 2.0,
                            env_loader=f"'{loader}'")
    remote = ssh_argv(SshTarget("10.0.0.2"), command)[-1]
    out = subprocess.run(["sh", "-c", remote], capture_output=True, text=True, env={"PATH": os.environ["PATH"]},
                         check=True).stdout.splitlines()
    assert out == ["http://10.0.0.1:11311/", "launch", "--child", "10.0.0.2-0", "-u", "http://10.0.0.1:4242/",
                   "--run_id", "run 'id'", "--sigint-timeout", "15", "--sigterm-timeout", "2"]


def test_ssh_never_prompts_and_never_accepts_an_unknown_host() -> None:
    argv = ssh_argv(SshTarget("robot.local", 2222, "ubuntu", 7.0), ["true"])
    assert argv[0] == "ssh"
    for option in ("BatchMode=yes", "StrictHostKeyChecking=yes", "ConnectTimeout=7"):
        assert option in argv
    assert argv[argv.index("-p") + 1] == "2222" and argv[argv.index("-l") + 1] == "ubuntu"


def test_the_parent_api_shrugs_off_garbage() -> None:
    async def scenario() -> None:
        supervisor = Supervisor(LaunchConfig(), {}, SupervisorOptions(capture=True), reporter=lambda *_: None)
        node = NodeSpec(package="p", type="t", name="far_node")
        process = supervisor.remote.add(RemoteProcess(ProcessPlan(node, "far_node-1", [], {}, "", None, True),
                                                      machine=Machine("far", "192.0.2.1")))
        remote = supervisor.remote
        assert remote.register("stranger", "http://x/")[0] == -1
        assert remote.register(["not", "a", "name"], 42)[0] == -1  # type: ignore[arg-type]
        assert remote.process_died("nobody-1", 3)[0] == 1
        assert remote.process_died({"x": 1}, "three")[0] == 1  # type: ignore[arg-type]
        assert remote.log("stranger", "loud", "\x1b[2J process[far_node-1]: started with pid [5]")[0] == 1  # type: ignore[arg-type]
        assert process.remote_pid is None, "a stranger's line changes no node"
        assert remote.log("192.0.2.1-0", 2, "process[far_node-1]: started with pid [77]")[0] == 1
        assert process.remote_pid == 77 and process.running
        assert remote.list_children() == [1, "roslaunch children", []]
        row = node_row(process, None)
        assert (row.node, row.state, row.pid, row.cpu, row.mem) == ("/far_node @far", "running", "77", "-", "-")

    asyncio.run(scenario())


def test_a_child_refuses_a_broken_launch_document() -> None:
    async def scenario() -> None:
        child = ChildLauncher("c-0", "http://127.0.0.1:9/", "run", SupervisorOptions())
        code, message, value = await child.launch_xml("<launch><node pkg=")
        assert code == -1 and message.startswith("ERROR: ") and value == [[], []]
        code, message, _ = await child.launch_xml(
            '<launch><node pkg="p" type="t" name="n" respawn="true" required="true"/></launch>')
        assert code == -1 and "respawn and required cannot both be set to true" in message
        assert not child.processes

    asyncio.run(scenario())


def test_a_child_reports_a_node_it_cannot_find(ros_env: dict[str, str]) -> None:
    async def scenario() -> None:
        child = ChildLauncher("c-0", "http://127.0.0.1:9/", "run", SupervisorOptions())
        code, _, (started, failed) = await child.launch_xml(
            '<launch><node pkg="no_such_package" type="t" name="ghost"/></launch>')
        assert (code, started, failed) == (1, [], ["ghost-1"])
        [process] = child.processes
        assert process.state.value == "failed" and "no_such_package" in process.problem

    asyncio.run(scenario())


def test_child_mode_takes_its_three_options_and_nothing_else(ros_env: dict[str, str]) -> None:
    from conftest import rostui_cmd

    alone = subprocess.run(rostui_cmd("launch", "--child", "x-0"), env=ros_env, capture_output=True, text=True)
    assert alone.returncode == 2 and alone.stderr == "rostui launch: --child, -u and --run_id go together\n"
    with_file = subprocess.run(rostui_cmd("launch", "-c", "x-0", "-u", "http://127.0.0.1:9/", "--run_id", "r",
                                          "robot.launch"), env=ros_env, capture_output=True, text=True)
    assert with_file.returncode == 2 and "--child takes no launch files" in with_file.stderr
