"""`rostui param` against `rosparam` on the same parameter server (rostui core or a real roscore)."""

from __future__ import annotations

import json

import pytest

from cli_helpers import rostui
from interop_helpers import run_tool

DUCKS = "huey: red\ndewey: blue\nlouie: green\nwebby: pink"
VALUES = ["1.0", "'1'", "[1,2]", "!!str 5", "true", "hello world", "''", "42", "1e3", "{a: {b: 1, c: [1, {d: 2}]}}",
          "héllo", "a\nb", DUCKS, " ".join(["word"] * 30)]


@pytest.mark.parametrize("value", VALUES)
def test_set_then_get_like_rosparam(module_master, module_ros_env, value):
    """Each value is set once by rosparam and once by rostui; every get output matches byte for byte.

    The tests share a parameter server (per worker and master kind); each value has names of its own, as
    setting a dictionary over an existing one merges them.
    """
    env, key = module_ros_env, VALUES.index(value)
    ours, theirs = f"/ours{key}", f"/theirs{key}"
    assert rostui(["param", "set", ours, value], env).returncode == 0
    run_tool(["rosparam", "set", theirs, value], env)
    for tool_get in (lambda k: run_tool(["rosparam", "get", k], env).stdout,
                     lambda k: rostui(["param", "get", k], env).stdout):
        assert tool_get(ours) == tool_get(theirs)
    assert rostui(["param", "get", ours], env).stdout == run_tool(["rosparam", "get", theirs], env).stdout


def test_book_duck_colors_merge(any_master, ros_env):
    assert rostui(["param", "set", "/duck_colors", DUCKS], ros_env).returncode == 0
    assert rostui(["param", "set", "/duck_colors", "huey: x"], ros_env).returncode == 0  # merges, like rosparam
    assert run_tool(["rosparam", "get", "/duck_colors"], ros_env).stdout == \
        "dewey: blue\nhuey: x\nlouie: green\nwebby: pink\n\n"
    for args in (["list"], ["list", "/duck_colors"], ["get", "/"], ["get", "/duck_colors"], ["get", "duck_colors/huey"],
                 ["get", "/run_id"], ["list", "/nons"]):
        assert rostui(["param", *args], ros_env).stdout == run_tool(["rosparam", *args], ros_env).stdout, args


def test_dump_and_load(any_master, ros_env, tmp_path):
    rostui(["param", "set", "/duck_colors", DUCKS], ros_env)
    ours, theirs = tmp_path / "ours.yaml", tmp_path / "theirs.yaml"
    assert rostui(["param", "dump", str(ours), "/duck_colors"], ros_env).returncode == 0
    run_tool(["rosparam", "dump", str(theirs), "/duck_colors"], ros_env)
    assert ours.read_text() == theirs.read_text()
    assert rostui(["param", "dump", "-", "/duck_colors"], ros_env).stdout == theirs.read_text()
    src = tmp_path / "load.yaml"
    src.write_text("p: 1\nq: {r: [1, 2]}\ns: !!str 3\nangle: !degrees 180\n---\nt: 2\n")
    assert rostui(["param", "load", str(src), "/mine"], ros_env).returncode == 0
    run_tool(["rosparam", "load", str(src), "/yours"], ros_env)
    assert rostui(["param", "get", "/mine"], ros_env).stdout == run_tool(["rosparam", "get", "/yours"], ros_env).stdout
    assert rostui(["param", "load", str(src)], ros_env).returncode == 0
    assert run_tool(["rosparam", "get", "/t"], ros_env).stdout == "2\n"


def test_delete(any_master, ros_env):
    rostui(["param", "set", "/gone/a", "1"], ros_env)
    assert rostui(["param", "delete", "/gone"], ros_env).returncode == 0
    assert "/gone/a" not in run_tool(["rosparam", "list"], ros_env).stdout
    theirs = run_tool(["rosparam", "delete", "/nope"], ros_env, check=False)
    ours = rostui(["param", "delete", "/nope"], ros_env)
    assert (ours.stdout, ours.stderr, ours.returncode) == (theirs.stdout, theirs.stderr, theirs.returncode) == \
        ("", "ERROR: parameter [/nope] is not set\n", 1)


def test_get_missing(any_master, ros_env):
    theirs = run_tool(["rosparam", "get", "/nope"], ros_env, check=False)
    ours = rostui(["param", "get", "/nope"], ros_env)
    assert (ours.stdout, ours.stderr, ours.returncode) == (theirs.stdout, theirs.stderr, 1)


def test_malformed_yaml_changes_nothing(any_master, ros_env, tmp_path):
    ours = rostui(["param", "set", "/bad", "{a: ["], ros_env)
    assert ours.returncode == 1 and ours.stdout == "" and len(ours.stderr.splitlines()) == 1
    bad = tmp_path / "bad.yaml"
    bad.write_text("p: 1\nq: [\n")
    ours = rostui(["param", "load", str(bad), "/bad"], ros_env)
    assert ours.returncode == 1 and len(ours.stderr.splitlines()) == 1
    assert ours.stderr.startswith(f"ERROR: {bad}:3:1: "), ours.stderr
    for value in ("null", "99999999999", "2024-01-01"):
        ours = rostui(["param", "set", "/bad", value], ros_env)
        assert ours.returncode == 1 and len(ours.stderr.splitlines()) == 1, value
    ours = rostui(["param", "load", str(tmp_path / "missing.yaml")], ros_env)
    assert ours.stderr == f"ERROR: file [{tmp_path / 'missing.yaml'}] does not exist\n" and ours.returncode == 1
    assert "/bad" not in run_tool(["rosparam", "list"], ros_env).stdout  # nothing was set


def test_json(any_master, ros_env):
    rostui(["param", "set", "/j", "{a: 1, b: [x, 2.5]}"], ros_env)
    assert json.loads(rostui(["param", "get", "--json", "/j"], ros_env).stdout) == {"a": 1, "b": ["x", 2.5]}
    assert json.loads(rostui(["param", "list", "--json", "/j"], ros_env).stdout) == ["/j/a", "/j/b"]


def test_fast_path_matches_full_command(any_master, ros_env):
    """`rostui param get NAME` answered before Typer loads prints exactly what the Typer command prints."""
    import subprocess
    import sys

    from interop_helpers import wait_for_param

    wait_for_param(ros_env, "/run_id")
    full_cli = "import sys; sys.argv[0] = 'rostui'; from rostui.cli.main import main; main()"
    for key in ("/run_id", "/", "/nope"):
        fast = rostui(["param", "get", key], ros_env)
        full = subprocess.run([sys.executable, "-c", full_cli, "param", "get", key], env=ros_env,
                              capture_output=True, text=True, timeout=30)
        assert (fast.stdout, fast.stderr, fast.returncode) == (full.stdout, full.stderr, full.returncode)


def test_no_master(ros_env, tmp_path):
    for args in (["list"], ["get", "/run_id"], ["set", "/x", "1"], ["delete", "/x"], ["dump", str(tmp_path / "d")]):
        ours = rostui(["param", *args], ros_env)
        assert ours.returncode == 1 and ours.stdout == ""
        assert ours.stderr.startswith("ERROR: Unable to communicate with master at http://127.0.0.1:")
        assert len(ours.stderr.splitlines()) == 1


def test_completion(any_master, ros_env):
    from interop_helpers import wait_until
    from rostui.cli.param_cmd import complete_params

    wait_until(lambda: "/run_id" in run_tool(["rosparam", "list"], ros_env).stdout, "/run_id to be set")
    assert complete_params("/run") == ["/run_id"]


def test_completion_without_master(ros_env):
    from rostui.cli.param_cmd import complete_params

    assert complete_params("/") == []
