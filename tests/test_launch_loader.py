"""The launch loader in-process: scoping rules, substitutions and where errors point (file:line)."""

from __future__ import annotations

import xmlrpc.client
from pathlib import Path

import pytest

from rostui.launch.errors import LaunchError
from rostui.launch.files import LaunchRequest, resolve_request
from rostui.launch.inspect import load_config
from rostui.launch.substitution import SubstitutionContext, resolve

from launch_helpers import BUILTIN_SHARE, CORPUS, CORPUS_ROOT


@pytest.fixture(autouse=True)
def package_path(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_PACKAGE_PATH", f"{BUILTIN_SHARE}:{CORPUS_ROOT}")
    monkeypatch.setenv("CORPUS_ENV", "envval")


def write(tmp_path: Path, name: str, body: str) -> str:
    path = tmp_path / name
    path.write_text(body)
    return str(path)


def load(path: str, **args: str):
    return load_config(LaunchRequest([path], dict(args)))[0]


def test_package_file_is_found_below_the_package(tmp_path: Path) -> None:
    request = resolve_request(["launch_corpus", "include_child.launch", "robot:=r", "_ignored:=1"])
    assert request.files == [str(CORPUS / "launch" / "include_child.launch")]
    assert request.args == {"robot": "r"}
    with pytest.raises(LaunchError, match="is neither a launch file in package"):
        resolve_request(["launch_corpus", "nothing.launch"])


def test_binfile_param_is_binary() -> None:
    config = load(str(CORPUS / "run" / "rosparam_commands.launch"), dump_file="/tmp/x")
    assert isinstance(config.params["/blob"], xmlrpc.client.Binary)
    assert [(c.command, c.param) for c in config.rosparam_commands] == [("delete", "/stale"), ("dump", "/old")]


def test_args_are_scoped_to_their_group(tmp_path: Path) -> None:
    path = write(tmp_path, "g.launch", """<launch>
  <group ns="a"><arg name="x" value="1"/><param name="p" value="$(arg x)"/></group>
  <arg name="x" value="2"/>
  <param name="q" value="$(arg x)"/>
</launch>""")
    assert load(path).params == {"/a/p": 1, "/q": 2}


def test_included_file_does_not_inherit_args(tmp_path: Path) -> None:
    child = write(tmp_path, "child.launch", '<launch>\n  <param name="p" value="$(arg secret)"/>\n</launch>')
    parent = write(tmp_path, "parent.launch", f'<launch>\n  <arg name="secret" default="s"/>\n'
                                             f'  <include file="{child}"/>\n</launch>')
    with pytest.raises(LaunchError) as caught:
        load(parent)
    assert str(caught.value) == f"{child}:2: included file [{child}] requires the 'secret' arg to be set"


def test_unused_include_arg_is_an_error(tmp_path: Path) -> None:
    child = write(tmp_path, "child.launch", "<launch/>")
    parent = write(tmp_path, "parent.launch", f'<launch>\n  <include file="{child}">\n'
                                             f'    <arg name="extra" value="1"/>\n  </include>\n</launch>')
    with pytest.raises(LaunchError, match=r"parent.launch:2: unused args \[extra\]"):
        load(parent)


def test_unknown_attribute_of_node_child_is_a_warning_at_the_child(tmp_path: Path) -> None:
    path = write(tmp_path, "n.launch", '<launch>\n  <node pkg="a" type="b" name="n">\n\n'
                                       '    <param name="x" value="1" value2="3"/>\n  </node>\n</launch>')
    config = load(path)
    assert config.params == {"/n/x": 1}
    assert config.warnings == [f"{path}:4: unknown <param> attribute 'value2'"]


def test_duplicate_node_names_are_an_error(tmp_path: Path) -> None:
    path = write(tmp_path, "d.launch", '<launch>\n  <node pkg="a" type="b" name="n"/>\n'
                                       '  <node pkg="a" type="b" name="n"/>\n</launch>')
    with pytest.raises(LaunchError, match=r"d.launch:3: .*multiple nodes named \[/n\]"):
        load(path)


def test_private_params_of_a_scope_go_to_every_later_node(tmp_path: Path) -> None:
    path = write(tmp_path, "p.launch", """<launch>
  <node pkg="a" type="b" name="early"/>
  <param name="~rate" value="5"/>
  <group ns="g"><node pkg="a" type="b" name="one"/></group>
  <node pkg="a" type="b" name="two"><param name="~rate" value="6"/></node>
</launch>""")
    assert load(path).params == {"/g/one/rate": 5, "/two/rate": 6}


def test_remaps_inherit_and_override(tmp_path: Path) -> None:
    path = write(tmp_path, "r.launch", """<launch>
  <remap from="a" to="b"/>
  <group ns="g">
    <remap from="c" to="d"/>
    <node pkg="x" type="y" name="n"><remap from="a" to="z"/></node>
  </group>
  <node pkg="x" type="y" name="m"/>
</launch>""")
    nodes = {n.name: n for n in load(path).nodes}
    assert nodes["n"].remaps == [("c", "d"), ("a", "z")]
    assert nodes["m"].remaps == [("a", "b")]


@pytest.mark.parametrize("text,expected", [
    ("$(eval 1 + 2)", "3"),
    ("$(optenv CORPUS_NOT_SET a b)", "a b"),
    ("x$(env CORPUS_ENV)y", "xenvvaly"),
    ("$(arg a)/$(arg a)", "1/1"),
])
def test_substitutions(text: str, expected: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("CORPUS_NOT_SET", raising=False)
    assert resolve(text, SubstitutionContext(args={"a": "1"})) == expected


@pytest.mark.parametrize("text,message", [
    ("$(nosuch x)", "Unknown substitution command"),
    ("$(env CORPUS_NOT_SET)", "environment variable 'CORPUS_NOT_SET' is not set"),
    ("$(eval __import__('os'))", "double underscore"),
    ("$(eval undefined_name)", "NameError"),
    ("$(find $(arg a))", "Dollar signs"),
])
def test_substitution_errors(text: str, message: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("CORPUS_NOT_SET", raising=False)
    with pytest.raises(LaunchError, match=message.replace("(", r"\(")):
        resolve(text, SubstitutionContext(args={"a": "1"}))


def test_anon_names_are_shared_within_one_load() -> None:
    config, loader = load_config(LaunchRequest([str(CORPUS / "launch" / "anon_same.launch")], {}))
    assert config.params["/first"] == config.params["/second"] == loader.anons["shared"]
    assert config.nodes[0].name == loader.anons["worker"]
