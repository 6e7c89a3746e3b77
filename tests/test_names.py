"""Tests for rostui.core.names: the book's examples, edge cases, errors, and an
oracle comparison against Debian's rosgraph/rospy under the system Python."""

from __future__ import annotations

import json
import os
import re
import subprocess
import textwrap
from pathlib import Path
from typing import Any

import pytest

from conftest import SYSTEM_PYTHON, need_peer
from rostui.core.names import (
    InvalidNameError,
    NodeArgs,
    anonymous_name,
    base_name,
    canonicalize_name,
    is_global,
    is_legal_base_name,
    is_legal_name,
    is_private,
    join_names,
    make_global_ns,
    namespace_of,
    node_global_name,
    node_namespace,
    parse_argv,
    resolve_name,
    resolve_remappings,
    validate_name,
)

# --------------------------------------------------------------------------- the book


def test_book_relative_names() -> None:
    assert resolve_name("cmd_vel", "/turtle1") == "/turtle1/cmd_vel"
    assert resolve_name("command_velocity", "/turtle1") == "/turtle1/command_velocity"
    assert resolve_name("g/h/i/j/k/l", "/a/b/c/d/e/f") == "/a/b/c/d/e/f/g/h/i/j/k/l"
    assert resolve_name("turtle1/pose", "/") == "/turtle1/pose"


def test_book_global_names_unchanged() -> None:
    for name in ["/teleop_turtle", "/turtle1/pose", "/run_id", "/count_and_log/set_logger_level",
                 "/a/b/c/d/e/f/g/h/i/j/k/l"]:
        assert is_legal_name(name)
        assert resolve_name(name, "/somewhere/else", "/somewhere/else/node") == name


def test_book_private_name() -> None:
    assert resolve_name("~max_vel", "/sim1", "/sim1/pubvel") == "/sim1/pubvel/max_vel"


def test_book_remap_turtle_pose_to_tim() -> None:
    args = parse_argv(["turtle1/pose:=tim"])
    assert args.remaps == {"turtle1/pose": "tim"}
    assert args.args == []
    node = node_global_name("turtlesim", args, env={})
    assert node == "/turtlesim"
    remaps = resolve_remappings(args.remaps, node_namespace(args, env={}), node)
    assert remaps == {"/turtle1/pose": "/tim"}
    assert resolve_name("turtle1/pose", "/", node, remaps) == "/tim"
    assert resolve_name("turtle1/cmd_vel", "/", node, remaps) == "/turtle1/cmd_vel"


def test_book_remap_reversed_velocity_in_namespace() -> None:
    args = parse_argv(["turtle1/command_velocity:=turtle1/command_velocity_reversed", "__ns:=sim"])
    node = node_global_name("turtlesim", args, env={})
    assert node == "/sim/turtlesim"
    remaps = resolve_remappings(args.remaps, node_namespace(args, env={}), node)
    assert remaps == {"/sim/turtle1/command_velocity": "/sim/turtle1/command_velocity_reversed"}


def test_book_name_override() -> None:
    # rosrun turtlesim turtlesim_node __name:=A
    args = parse_argv(["__name:=A"])
    assert args.name == "A"
    assert node_global_name("turtlesim", args, env={}) == "/A"


def test_book_ns_and_env() -> None:
    assert node_namespace(parse_argv([]), env={}) == "/"
    assert node_namespace(parse_argv([]), env={"ROS_NAMESPACE": "robot"}) == "/robot/"
    assert node_namespace(parse_argv(["__ns:=/turtle1"]), env={"ROS_NAMESPACE": "robot"}) == "/turtle1/"
    assert node_namespace(parse_argv(["__ns:=a/b/"]), env={}) == "/a/b/"


def test_book_anonymous_names_unique_and_legal() -> None:
    names = {anonymous_name("anon") for _ in range(200)}
    assert len(names) == 200
    for name in names:
        assert is_legal_base_name(name)
        m = re.fullmatch(r"anon_(\d+)_(\d+)", name)
        assert m and int(m.group(1)) == os.getpid()
        assert abs(int(m.group(2)) / 1000 - __import__("time").time()) < 60


# --------------------------------------------------------------------------- structure


@pytest.mark.parametrize("name, legal", [
    ("", True), ("/", True), ("a", True), ("/a/b", True), ("/a/b/", True), ("~a", True),
    ("~/a", True), ("~", True), ("a/_b", True), ("/1a", True), ("A9_z", True), ("~1x", True),
    ("1a", False), ("_a", False), ("a-b", False), ("a b", False), ("//a", False), ("a//b", False),
    ("~~a", False), ("a~b", False), ("/~a", False), ("a\n", False), ("aä", False), ("a.b", False),
])
def test_is_legal_name(name: str, legal: bool) -> None:
    assert is_legal_name(name) is legal
    if legal:
        assert validate_name(name) == name
    else:
        with pytest.raises(InvalidNameError) as info:
            validate_name(name, "topic")
        assert repr(name) in str(info.value) and "topic" in str(info.value)
        assert isinstance(info.value, ValueError)


def test_is_legal_base_name() -> None:
    for ok in ["a", "abc_1", "Z"]:
        assert is_legal_base_name(ok)
    for bad in ["", "/a", "a/b", "~a", "1a", "_a", "a-b", "a/"]:
        assert not is_legal_base_name(bad)


def test_canonicalize_namespace_base_join() -> None:
    assert canonicalize_name("/a//b/") == "/a/b"
    assert canonicalize_name("") == "" and canonicalize_name("/") == "/"
    assert canonicalize_name("//a") == "/a"
    assert namespace_of("/a/b") == "/a/"
    assert namespace_of("/a/b/") == "/a/"
    assert namespace_of("/a") == "/"
    assert namespace_of("a/b") == "a/"
    assert namespace_of("b") == "/"
    assert namespace_of("") == "/"
    assert base_name("/a/b") == "b"
    assert base_name("/a/b/") == "b"
    assert base_name("~p") == "p"
    assert base_name("/") == ""
    assert join_names("/a", "b") == "/a/b"
    assert join_names("/a/", "b") == "/a/b"
    assert join_names("", "b") == "b"
    assert join_names("~", "b") == "~b"
    assert join_names("/a", "/b") == "/b"
    assert join_names("/a", "~b") == "~b"
    assert make_global_ns("") == "/"
    assert make_global_ns("a") == "/a/"
    assert make_global_ns("/a/b") == "/a/b/"
    with pytest.raises(InvalidNameError):
        make_global_ns("~a")
    assert is_global("/a") and not is_global("a") and is_global("") is False
    assert is_private("~a") and not is_private("/a") and is_private("") is False


def test_resolve_edge_cases() -> None:
    assert resolve_name("", "/a") == "/a/"
    assert resolve_name("", "") == "/"
    assert resolve_name("x", "") == "/x"
    assert resolve_name("x/", "/a/") == "/a/x"
    assert resolve_name("/x//y/", "/a") == "/x/y"
    assert resolve_name("~", "/a", "/a/node") == "/a/node"
    assert resolve_name("~/p", "/a", "/a/node") == "/a/node/p"
    assert resolve_name("~p", "/", "/") == "/p"
    with pytest.raises(InvalidNameError, match="node name"):
        resolve_name("~p", "/a")


def test_remap_applies_only_to_exact_resolved_name() -> None:
    remaps = {"/a/foo": "/bar"}
    assert resolve_name("foo", "/a", "/a/n", remaps) == "/bar"
    assert resolve_name("/a/foo", "/", "/n", remaps) == "/bar"
    assert resolve_name("foo/x", "/a", "/a/n", remaps) == "/a/foo/x"
    assert resolve_name("foo", "/b", "/b/n", remaps) == "/b/foo"
    # the empty name is never remapped
    assert resolve_name("", "/a", "/a/n", {"/a/": "/z"}) == "/a/"


def test_private_remap() -> None:
    args = parse_argv(["~image:=/camera/raw", "scan:=~scan_in"])
    remaps = resolve_remappings(args.remaps, "/r/", "/r/node")
    assert remaps == {"/r/node/image": "/camera/raw", "/r/scan": "/r/node/scan_in"}


# --------------------------------------------------------------------------- argv


def test_parse_argv_everything() -> None:
    argv = ["--verbose", "a:=b", "_rate:=10", "_x:=1.5", "_b:=true", "_s:=hello", "_l:=[1,2]",
            "__name:=n", "__ns:=/ns", "__log:=/tmp/n.log", "__ip:=10.0.0.1",
            "__hostname:=robot.local", "__master:=http://m:11311", "__other:=1", "file.txt", "-x"]
    a = parse_argv(argv)
    assert a.remaps == {"a": "b"}
    assert a.params == {"rate": 10, "x": 1.5, "b": True, "s": "hello", "l": [1, 2]}
    assert type(a.params["rate"]) is int and type(a.params["x"]) is float
    assert (a.name, a.namespace, a.log, a.ip, a.hostname, a.master) == (
        "n", "/ns", "/tmp/n.log", "10.0.0.1", "robot.local", "http://m:11311")
    assert a.specials["__other"] == "1"
    assert a.args == ["--verbose", "file.txt", "-x"]


def test_parse_argv_defaults() -> None:
    a = parse_argv([])
    assert a == NodeArgs()
    assert a.name is None and a.namespace is None and a.remaps == {} and a.params == {}


def test_parse_argv_yaml_and_whitespace() -> None:
    a = parse_argv(["_d:={a: 1}", "_n:=null", "_q:=\"10\"", "_y:=yes", "_neg:=-3", "x:= y ",
                    "_e:=", "e:=", "_p:=1", "_p:=2"])
    assert a.params == {"d": {"a": 1}, "n": None, "q": "10", "y": True, "neg": -3, "p": 2}
    assert a.remaps == {"x": "y"}


def test_parse_argv_empty_ns_means_root() -> None:
    a = parse_argv(["__ns:="])
    assert a.namespace == ""
    assert node_namespace(a, env={"ROS_NAMESPACE": "/elsewhere"}) == "/"


@pytest.mark.parametrize("arg", ["a-b:=c", "1a:=b", ":=b", "a:=b:=c", "a:=b c", "a:=1b",
                                 "a//b:=c", "a:=~~b", "_a-b:=1", "__a-b:=1"])
def test_parse_argv_illegal_remap(arg: str) -> None:
    with pytest.raises(InvalidNameError):
        parse_argv([arg])


def test_parse_argv_bad_yaml() -> None:
    with pytest.raises(ValueError, match="_bad"):
        parse_argv(["_bad:=[1"])


def test_node_global_name() -> None:
    env = {"ROS_NAMESPACE": "/env_ns"}
    assert node_global_name("talker", parse_argv([]), env={}) == "/talker"
    assert node_global_name("talker", parse_argv([]), env=env) == "/env_ns/talker"
    assert node_global_name("talker", parse_argv(["__ns:=x"]), env=env) == "/x/talker"
    anon = node_global_name("talker", parse_argv([]), env={}, anonymous=True)
    assert re.fullmatch(r"/talker_\d+_\d+", anon)
    # __name disables anonymity
    assert node_global_name("talker", parse_argv(["__name:=fixed"]), env={}, anonymous=True) == "/fixed"
    # an empty __name is ignored, as in rospy
    assert node_global_name("talker", parse_argv(["__name:="]), env={}) == "/talker"


@pytest.mark.parametrize("default, argv, env", [
    ("a/b", [], {}), ("", [], {}), ("1node", [], {}), ("n", ["__name:=bad-name"], {}),
    ("n", ["__name:=/abs"], {}), ("n", ["__ns:=~x"], {}), ("n", [], {"ROS_NAMESPACE": "a-b"}),
])
def test_node_global_name_errors(default: str, argv: list[str], env: dict[str, str]) -> None:
    with pytest.raises(InvalidNameError):
        node_global_name(default, parse_argv(argv), env=env)


def test_anonymous_name_rejects_bad_base() -> None:
    with pytest.raises(InvalidNameError):
        anonymous_name("a/b")


def test_default_env_is_os_environ(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_NAMESPACE", "from_env")
    assert node_namespace(parse_argv([])) == "/from_env/"
    monkeypatch.delenv("ROS_NAMESPACE")
    assert node_global_name("n", parse_argv([])) == "/n"


def test_module_has_no_ui_imports() -> None:
    import rostui.core.names as mod

    text = Path(mod.__file__).read_text()
    for banned in ("textual", "typer", "rich"):
        assert not re.search(rf"^\s*(import|from)\s+{banned}\b", text, re.M)


# --------------------------------------------------------------------------- oracle

RESOLVE_CASES: list[tuple[str, str, dict[str, str] | None]] = [
    (name, node, None)
    for node in ["/", "/node", "/a/node", "/a/b/node", "/sim1/pubvel"]
    for name in ["", "foo", "foo/bar", "foo/", "/x", "/x/y/", "//x//y", "~", "~p", "~/p", "~p/q", "a//b"]
] + [
    ("foo", "/a/node", {"/a/foo": "/bar"}),
    ("foo", "/a/node", {"/a/foo/": "/bar"}),
    ("~foo", "/a/node", {"/a/node/foo": "/bar"}),
    ("/a/foo", "/n", {"/a/foo": "relative"}),
    ("", "/a/node", {"/a/": "/z", "/a": "/y"}),
]

STRING_CASES = ["", "/", "/a/b", "/a/b/", "a", "a/b", "a/b/", "~a", "~/a", "~", "//a", "a//b",
                "/a//b", "1a", "_a", "a-b", "a b", "/1a", "a/", "~~a", "a~b", "/a/1b", "a/_b",
                "/_a", "~1x", "/~a", "A_9/z"]

ARGV_CASES: list[list[str]] = [
    [],
    ["turtle1/pose:=tim"],
    ["a", "b:=c", "-x", "__name:=n", "d"],
    ["_rate:=10", "_x:=1.5", "_b:=true", "_s:=hello", "_l:=[1,2]", "_d:={a: 1}", "_n:=null",
     "_o:=0x10", "_y:=yes", "_t:=1e3", "_q:=\"quoted\"", "_neg:=-3", "_inf:=.inf", "_p/q:=5"],
    ["__ns:=robot", "~img:=/cam/raw", "scan:=~scan_in", "/abs:=rel/x", "x:= y "],
    ["__ns:=/r1/", "__name:=drive", "cmd_vel:=/r1/cmd", "__log:=/tmp/l.log", "__ip:=1.2.3.4",
     "__hostname:=h", "__master:=http://m:1", "__custom:=v", "rest"],
    ["_e:=", "e:=", "__name:=", "f:=g", "f:=h"],
    ["__ns:=", "a:=b"],
]

ORACLE_SCRIPT = textwrap.dedent(r"""
    import json, sys
    import rosgraph.names as gn
    import rospy.client as rc
    import rospy.names as rn

    cases = json.load(sys.stdin)
    out = {"resolve": [], "strings": [], "argv": []}
    for name, node, remaps in cases["resolve"]:
        out["resolve"].append(gn.resolve_name(name, node, remaps))
    for s in cases["strings"]:
        row = {
            "is_legal_name": gn.is_legal_name(s),
            "is_legal_base_name": gn.is_legal_base_name(s),
            "canonicalize_name": gn.canonicalize_name(s),
            "namespace": gn.namespace(s),
            "is_global": bool(gn.is_global(s)),
            "is_private": bool(gn.is_private(s)),
            "join_a": gn.ns_join("/a", s),
            "join_s": gn.ns_join(s, "b") if s else None,
        }
        try:
            row["make_global_ns"] = gn.make_global_ns(s)
        except ValueError:
            row["make_global_ns"] = "ValueError"
        out["strings"].append(row)
    for argv, env in cases["argv"]:
        full = ["prog"] + argv
        mappings = gn.load_mappings(full)
        ns = rn.get_ros_namespace(env=env, argv=full)
        name = mappings.get("__name", "default_node")
        node = gn.resolve_name(name, ns + "unnamed")
        rn.reload_mappings(full)
        rn.initialize_mappings(node)
        resolved = {k: v for k, v in rn.get_resolved_mappings().items() if not k.startswith("__")}
        out["argv"].append({
            "mappings": mappings,
            "params": rc.load_command_line_node_params(full),
            "myargv": rc.myargv(full)[1:],
            "namespace": ns,
            "node": node,
            "resolved": resolved,
        })
    json.dump(out, sys.stdout)
""")


def _oracle_available() -> bool:
    if not Path(SYSTEM_PYTHON).exists():
        return False
    r = subprocess.run([SYSTEM_PYTHON, "-c", "import rosgraph.names, rospy.client, rospy.names"],
                       capture_output=True)
    return r.returncode == 0


ENVS: list[dict[str, str]] = [{}, {"ROS_NAMESPACE": "/env_ns"}]


@pytest.fixture(scope="module")
def oracle() -> dict[str, Any]:
    """Everything Debian's rosgraph/rospy say about the case tables, from one subprocess."""
    need_peer(_oracle_available(), "rosgraph (Debian python3-rosgraph / python3-rospy)")
    payload = {
        "resolve": RESOLVE_CASES,
        "strings": STRING_CASES,
        "argv": [(argv, env) for argv in ARGV_CASES for env in ENVS],
    }
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "VIRTUAL_ENV"))}
    env.pop("ROS_NAMESPACE", None)
    r = subprocess.run([SYSTEM_PYTHON, "-c", ORACLE_SCRIPT], input=json.dumps(payload),
                       capture_output=True, text=True, env=env, timeout=60)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def test_oracle_resolve_name(oracle: dict[str, Any]) -> None:
    for (name, node, remaps), expected in zip(RESOLVE_CASES, oracle["resolve"], strict=True):
        got = resolve_name(name, namespace_of(node), node, remaps)
        assert got == expected, (name, node, remaps)


def test_oracle_string_functions(oracle: dict[str, Any]) -> None:
    for s, exp in zip(STRING_CASES, oracle["strings"], strict=True):
        assert is_legal_name(s) == exp["is_legal_name"], s
        assert is_legal_base_name(s) == exp["is_legal_base_name"], s
        assert canonicalize_name(s) == exp["canonicalize_name"], s
        assert is_global(s) == exp["is_global"], s
        assert is_private(s) == exp["is_private"], s
        assert join_names("/a", s) == exp["join_a"], s
        if s:
            assert join_names(s, "b") == exp["join_s"], s
        if "//" not in s:  # we collapse '//' where rosgraph keeps it
            assert namespace_of(s) == exp["namespace"], s
            try:
                got = make_global_ns(s)
            except InvalidNameError:
                got = "ValueError"
            assert got == exp["make_global_ns"], s


def test_oracle_argv(oracle: dict[str, Any]) -> None:
    cases = [(argv, env) for argv in ARGV_CASES for env in ENVS]
    for (argv, env), exp in zip(cases, oracle["argv"], strict=True):
        a = parse_argv(argv)
        ctx = (argv, env)
        mappings = {**a.remaps, **{k: v for k, v in a.specials.items() if v}}
        assert mappings == exp["mappings"], ctx
        assert a.params == exp["params"], ctx
        assert a.args == exp["myargv"], ctx
        ns = node_namespace(a, env=env)
        assert ns == exp["namespace"], ctx
        node = node_global_name("default_node", a, env=env)
        assert node == exp["node"], ctx
        assert resolve_remappings(a.remaps, ns, node) == exp["resolved"], ctx
