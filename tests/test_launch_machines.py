"""<machine> as roslaunch reads it (defaults, inheritance, duplicates, local or remote) and unknown names as warnings."""

from __future__ import annotations

import getpass
import socket
import subprocess
from pathlib import Path

import pytest

from rostui.launch.errors import LaunchError
from rostui.launch.files import LaunchRequest
from rostui.launch.inspect import load_config
from rostui.launch.machines import assign_machines, is_machine_local, local_addresses
from rostui.launch.model import LaunchConfig, Machine

from launch_helpers import BUILTIN_SHARE, CORPUS_ROOT, launch_env, run_rostui

NODE = '<node pkg="a" type="b" name="{0}"{1}/>'


@pytest.fixture(autouse=True)
def package_path(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_PACKAGE_PATH", f"{BUILTIN_SHARE}:{CORPUS_ROOT}")


def write(tmp_path: Path, body: str, name: str = "m.launch") -> str:
    path = tmp_path / name
    path.write_text(f"<launch>\n{body}\n</launch>\n")
    return str(path)


def load(path: str, **args: str) -> LaunchConfig:
    return load_config(LaunchRequest([path], dict(args)))[0]


def machines_of(config: LaunchConfig) -> dict[str, str | None]:
    return {n.resolved_name: n.machine for n in config.all_nodes()}


def test_default_machine_applies_to_later_nodes_and_leaves_groups(tmp_path: Path) -> None:
    """default="true" covers the nodes after it, also after the <group> that declared it ends, as in roslaunch."""
    path = write(tmp_path, "\n".join([
        NODE.format("before", ""),
        '<group ns="g">',
        '  <machine name="arm" address="localhost" default="true"/>',
        "  " + NODE.format("inside", ""),
        "</group>",
        NODE.format("after", ""),
        NODE.format("named", ' machine="base"'),
        '<machine name="base" address="127.0.0.1" default="never"/>',
        NODE.format("last", ""),
    ]))
    config = load(path)
    assert machines_of(config) == {"/before": None, "/g/inside": "arm", "/after": "arm", "/named": "base",
                                   "/last": "arm"}
    assert config.machines["base"].assignable is False
    assert config.machines["arm"].assignable is True


def test_default_false_does_not_change_the_default(tmp_path: Path) -> None:
    path = write(tmp_path, '<machine name="one" address="localhost" default="true"/>\n'
                           '<machine name="two" address="localhost" default="FALSE"/>\n' + NODE.format("n", ""))
    assert machines_of(load(path)) == {"/n": "one"}


def test_identical_duplicate_is_fine_a_different_one_is_an_error(tmp_path: Path) -> None:
    same = write(tmp_path, '<machine name="m" address="far" timeout="10"/>\n<machine name="m" address="far"/>')
    assert load(same).machines["m"].address == "far"
    different = write(tmp_path, '<machine name="m" address="far"/>\n<machine name="m" address="far" user="x"/>',
                      "d.launch")
    with pytest.raises(LaunchError) as caught:
        load(different)
    assert str(caught.value) == (f"{different}:3: Machine [m] already added and does not match duplicate entry "
                                 f"(first declared at {different}:2)")
    never = write(tmp_path, '<machine name="m" address="far"/>\n<machine name="m" address="far" default="never"/>',
                  "n.launch")
    with pytest.raises(LaunchError, match="does not match duplicate entry"):
        load(never)


def test_env_loader_and_address_take_substitutions(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROBOT_HOST", "robot7")
    path = write(tmp_path, '<arg name="distro" default="noetic"/>\n'
                           '<machine name="r" address="$(env ROBOT_HOST)" env-loader="/home/ops/$(arg distro)/env.sh" '
                           'ssh-port="2222" user="ops" password="pw" timeout="4.5"/>')
    machine = load(path, distro="melodic").machines["r"]
    assert (machine.address, machine.env_loader, machine.ssh_port, machine.user, machine.password,
            machine.timeout) == ("robot7", "/home/ops/melodic/env.sh", 2222, "ops", "pw", 4.5)


@pytest.mark.parametrize("body,message", [
    ('<machine name="m" address="a" ros-root="/opt/ros"/>', "ros-* attributes are not supported since ROS Fuerte"),
    ('<machine name="m" address="a"><env name="X" value="1"/></machine>', "<env> tag is not supported"),
    ('<machine name="m" address="a" default="always"/>', "Invalid value for 'default': always"),
    ('<machine name="m" address="a" timeout=""/>', "'timeout' cannot be empty"),
    ('<machine name="m" address="a" timeout="0"/>', "'timeout' must be a positive number: [0.0]"),
    ('<machine name="m" address="a" ssh-port="ssh"/>', "'ssh-port' must be a number: [ssh]"),
    ('<machine name="m"/>', "<machine> tag is missing required attribute: 'address'"),
])
def test_invalid_machines(tmp_path: Path, body: str, message: str) -> None:
    path = write(tmp_path, body)
    with pytest.raises(LaunchError) as caught:
        load(path)
    assert str(caught.value).startswith(f"{path}:2: ") and message in str(caught.value)


def test_unknown_child_of_machine_is_a_warning(tmp_path: Path) -> None:
    path = write(tmp_path, '<machine name="m" address="a">\n  <fake/>\n</machine>')
    assert load(path).warnings == [f"{path}:3: unrecognized 'fake' tag in <machine> tag"]


def test_local_or_remote_as_roslaunch_decides() -> None:
    def local(address: str, user: str | None = None) -> bool:
        return is_machine_local(Machine("m", address, user=user))

    assert local("localhost") and local("127.0.0.1") and local("127.0.1.1") and local("::1")
    assert local(socket.gethostname())
    mine = sorted(a for a in local_addresses() if a != "localhost" and not a.startswith(("127.", "fe80")))
    for address in mine:
        assert local(address), address
    assert local("localhost", user=getpass.getuser())
    assert not local("localhost", user=getpass.getuser() + "x")  # another user: roslaunch logs in over ssh
    assert not local("192.0.2.10")  # TEST-NET-1: never an address of this host
    with pytest.raises(LaunchError, match=r"cannot resolve host address for machine \[no-such-host.invalid\]"):
        local("no-such-host.invalid")


def test_assign_machines_marks_remote_nodes(tmp_path: Path) -> None:
    path = write(tmp_path, "\n".join([
        '<machine name="here" address="localhost"/>',
        '<machine name="far" address="192.0.2.10" user="robot"/>',
        NODE.format("plain", ""), NODE.format("local", ' machine="here"'), NODE.format("remote", ' machine="far"'),
        '<test test-name="t" pkg="a" type="b" machine="far"/>',
    ]))
    config = load(path)
    assert config.remote_nodes() == []  # nothing is decided while loading (--nodes never resolves addresses)
    assign_machines(config)
    assert [n.resolved_name for n in config.remote_nodes()] == ["/remote", "/t"]
    assert config.machines["here"].local is True and config.machines["far"].local is False
    assert config.machine_of(config.nodes[2]) is config.machines["far"]
    assert config.machine_of(config.nodes[0]) is None


def test_assign_machines_errors_point_at_the_file(tmp_path: Path) -> None:
    unknown = write(tmp_path, NODE.format("n", ' machine="nowhere"'))
    with pytest.raises(LaunchError) as caught:
        assign_machines(load(unknown))
    assert str(caught.value) == f"{unknown}:2: unknown machine [nowhere] for node [/n]"
    unresolved = write(tmp_path, '<machine name="m" address="no-such-host.invalid"/>\n' +
                       NODE.format("n", ' machine="m"'), "u.launch")
    with pytest.raises(LaunchError) as caught:
        assign_machines(load(unresolved))
    assert str(caught.value) == f"{unresolved}:2: cannot resolve host address for machine [no-such-host.invalid]"


def test_unknown_names_are_warnings_in_every_place(tmp_path: Path) -> None:
    child = write(tmp_path, '<arg name="x" required="true" default="1"/>', "child.launch")
    path = write(tmp_path, "\n".join([
        '<nodule name="a"/>',
        f'<include file="{child}" args="-x"><arg name="x" value="2"/><param name="p" value="1"/></include>',
        '<node pkg="a" type="b" name="n" colour="red"><fake/><Remap from="a" to="b"/></node>',
        '<rosparam param="caps" tag="format">[1, 2]</rosparam>',
        '<group ns="g" name="ps3"><param name="q" value="1" kind="int"/></group>',
    ]))
    config = load(path)
    assert config.warnings == [
        f"{path}:2: unrecognized tag <nodule>",
        f"{path}:3: unknown <include> attribute 'args'",
        f"{path}:3: unrecognized 'param' tag in <include> tag",
        f"{child}:2: unknown <arg> attribute 'required'",
        f"{path}:4: unknown <node> attribute 'colour'",
        f"{path}:4: unrecognized 'fake' child tag in <node>",
        f"{path}:5: unknown <rosparam> attribute 'tag'",
        f"{path}:6: unknown <group> attribute 'name'",
        f"{path}:6: unknown <param> attribute 'kind'",
    ]
    assert config.params == {"/caps": [1, 2], "/g/q": 1}
    assert config.nodes[0].remaps == [("a", "b")]  # roslaunch reads a node's children case-insensitively


def test_strict_request_raises_one_line_per_problem(tmp_path: Path) -> None:
    from rostui.launch.errors import StrictError

    path = write(tmp_path, '<node pkg="a" type="b" name="n" colour="red" size="2"/>')
    with pytest.raises(StrictError) as caught:
        load_config(LaunchRequest([path], strict=True))
    assert str(caught.value).splitlines() == [f"{path}:2: unknown <node> attribute 'colour'",
                                              f"{path}:2: unknown <node> attribute 'size'"]


def test_a_launch_warns_and_goes_on_strict_starts_nothing(ros_env: dict[str, str],
                                                          rostui_core: subprocess.Popen, tmp_path: Path) -> None:
    """roslaunch prints a WARNING for an unknown attribute and runs the node; --strict refuses the file."""
    env = launch_env(ros_env)
    path = write(tmp_path, '<node pkg="launch_corpus" type="quitter" name="brief" colour="red"/>')
    result = run_rostui([path], env, timeout=120)
    assert result.returncode == 0, result.stderr
    assert f"WARNING: {path}:2: unknown <node> attribute 'colour'" in result.stderr.splitlines()
    assert "process[brief-1]: started with pid" in result.stdout
    strict = run_rostui(["--strict", path], env)
    assert strict.returncode == 1
    assert strict.stderr.strip() == f"rostui launch: {path}:2: unknown <node> attribute 'colour'"
    assert "started" not in strict.stdout


def test_launch_check(ros_env: dict[str, str], tmp_path: Path) -> None:
    env = launch_env(ros_env)
    good = write(tmp_path, '<node pkg="launch_corpus" type="quitter" name="q"/>', "good.launch")
    result = run_rostui(["check", good], env)
    assert (result.returncode, result.stdout, result.stderr) == (0, "", "")
    bad = write(tmp_path, "\n".join([
        '<node pkg="launch_corpus" type="quitter" name="q" colour="red"/>',
        '<node pkg="launch_corpus" type="no_such_program" name="missing"/>',
        '<machine name="far" address="192.0.2.10"/>',
        '<node pkg="launch_corpus" type="no_such_program" name="remote" machine="far"/>',
    ]), "bad.launch")
    result = run_rostui(["check", bad], env)
    assert result.returncode == 1
    lines = result.stderr.splitlines()
    assert lines[0] == f"rostui launch: {bad}:2: unknown <node> attribute 'colour'"
    assert lines[1].startswith(f"rostui launch: {bad}:3: cannot launch node of type [launch_corpus/no_such_program]")
    assert len(lines) == 2  # the remote node's executable is looked for on its own machine, not here
    unknown = write(tmp_path, '<node pkg="launch_corpus" type="quitter" name="q" machine="nowhere"/>', "u.launch")
    result = run_rostui(["check", unknown], env)
    assert result.returncode == 1
    assert result.stderr.strip() == f"rostui launch: {unknown}:2: unknown machine [nowhere] for node [/q]"
