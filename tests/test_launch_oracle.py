"""rostui launch's model equals Debian roslaunch's: --nodes, --args NODE, --dump-params, --files, --ros-args.

The corpus (tests/launch_corpus/launch_corpus) uses every element, attribute
and substitution of roslaunch XML; the book's files live in rostui's agitr
package.  Both launchers see the same ROS_PACKAGE_PATH (rostui's share dir and
the corpus), so real roslaunch finds every package through rospack.
"""

from __future__ import annotations

import subprocess

import pytest

from conftest import SYSTEM_PYTHON, need_peer
from launch_helpers import (
    corpus_file, have_roslaunch, launch_env, run_roslaunch, run_rostui, without_anon,
)

BOOK = [("agitr", "example.launch"), ("agitr", "doublesim.launch"), ("agitr", "triplesim.launch"),
        ("agitr", "reverse.launch"), ("agitr", "fast_yellow.launch")]
CORPUS = [("launch_corpus", "elements.launch"), ("launch_corpus", "include_parent.launch"),
          ("launch_corpus", "substitutions.launch"), ("launch_corpus", "anon_same.launch"),
          ("launch_corpus", "names.launch")]
ARGS = ["needed:=given"]
CASES = [(*case, []) for case in BOOK] + [("agitr", "triplesim.launch", ["use_sim3:=1"])] + \
        [(*case, ARGS) for case in CORPUS] + [("launch_corpus", "elements.launch", ["needed:=other", "robot:=cli"])]
IDS = [f"{pkg}-{name}-{'-'.join(a) or 'defaults'}" for pkg, name, a in CASES]


@pytest.fixture
def env(ros_env: dict[str, str]) -> dict[str, str]:
    """The shared environment; requires Debian's roslaunch."""
    need_peer(have_roslaunch(), "roslaunch (Debian ros-core)")
    return launch_env(ros_env)


Result = subprocess.CompletedProcess[str]


def _both(args: list[str], env: dict[str, str]) -> tuple[Result, Result]:
    return run_rostui(args, env), run_roslaunch(args, env)


@pytest.mark.parametrize("pkg,name,extra", CASES, ids=IDS)
@pytest.mark.parametrize("mode", ["--nodes", "--dump-params", "--ros-args"])
def test_views_equal_roslaunch(env: dict[str, str], pkg: str, name: str, extra: list[str], mode: str) -> None:
    ours, theirs = _both([mode, pkg, name, *extra], env)
    assert theirs.returncode == 0, theirs.stderr
    assert ours.returncode == 0, ours.stderr
    assert without_anon(ours.stdout) == without_anon(theirs.stdout)


@pytest.mark.parametrize("pkg,name,extra", CASES, ids=IDS)
def test_files_equal_roslaunch(env: dict[str, str], pkg: str, name: str, extra: list[str]) -> None:
    ours, theirs = _both(["--files", pkg, name, *extra], env)
    assert ours.returncode == theirs.returncode == 0, ours.stderr + theirs.stderr
    assert sorted(ours.stdout.split()) == sorted(theirs.stdout.split())


NAMED = [(case, case_id) for case, case_id in zip(CASES, IDS) if case[1] != "anon_same.launch"]


@pytest.mark.parametrize("pkg,name,extra", [c for c, _ in NAMED], ids=[i for _, i in NAMED])
def test_node_args_equal_roslaunch(env: dict[str, str], pkg: str, name: str, extra: list[str]) -> None:
    listing = run_roslaunch(["--nodes", pkg, name, *extra], env)
    assert listing.returncode == 0, listing.stderr
    names = [n for n in listing.stdout.split() if without_anon(n) == n]  # an anon name differs per process
    assert names
    for node in names:
        ours, theirs = _both(["--args", node, pkg, name, *extra], env)
        assert theirs.returncode == 0, theirs.stderr
        assert ours.returncode == 0, ours.stderr
        assert ours.stdout == theirs.stdout, node


def test_node_args_show_environment_changes(env: dict[str, str]) -> None:
    """A node's namespace and <env> values show as VAR="value" in front of its command line."""
    ours, theirs = _both(["--args", "/talker", "launch_corpus", "elements.launch", "needed:=x"], env)
    assert ours.stdout == theirs.stdout
    assert 'CORPUS_NODE="node-level"' in ours.stdout and "nice -n 5" in ours.stdout


def test_anon_same_base_same_name(env: dict[str, str]) -> None:
    """$(anon shared) twice in one launch gives one name; another base gives another."""
    import yaml

    ours = run_rostui(["--dump-params", "launch_corpus", "anon_same.launch"], env)
    params = yaml.safe_load(ours.stdout)
    assert params["/first"] == params["/second"] != params["/other"]
    assert params["/first"].startswith("shared_")
    nodes = run_rostui(["--nodes", "launch_corpus", "anon_same.launch"], env).stdout.split()
    assert nodes[0].startswith("/worker_")
    args = run_rostui(["--args", nodes[0], "launch_corpus", "anon_same.launch"], env)
    assert args.returncode != 0  # each process draws new anon names, as with roslaunch


def test_unknown_node_for_args(env: dict[str, str]) -> None:
    ours, theirs = _both(["--args", "/nobody", "agitr", "example.launch"], env)
    assert ours.returncode == theirs.returncode == 1
    assert "Cannot find node named [/nobody]" in ours.stderr


ERRORS = [
    ("malformed.launch", [], ":3: ", "mismatched tag"),
    ("respawn_required.launch", [], ":2: ", "respawn and required cannot both be set"),
    ("override_value.launch", ["fixed:=2"], ":2: ", "cannot override arg 'fixed'"),
    ("arg_not_set.launch", [], ":2: ", "arg 'never_set' is used but never set"),
    ("find_unknown.launch", [], ":2: ", "package 'no_such_package_anywhere' not found"),
    ("missing_include.launch", [], ":2: ", "does_not_exist.launch does not exist"),
    ("bad_if.launch", [], ":2: ", "invalid 'if' value 'yes'"),
    ("bad_unless.launch", [], ":2: ", "invalid 'unless' value 'maybe'"),
]


@pytest.mark.parametrize("name,extra,where,message", ERRORS, ids=[e[0] for e in ERRORS])
@pytest.mark.parametrize("mode", [[], ["--nodes"], ["--dump-params"]], ids=["launch", "nodes", "dump-params"])
def test_errors_fail_in_both(env: dict[str, str], name: str, extra: list[str], where: str, message: str,
                             mode: list[str]) -> None:
    """Each broken file fails in roslaunch and in rostui, which says why in one line with file:line."""
    path = str(corpus_file(name))
    ours = run_rostui([*mode, path, *extra], env)
    assert ours.returncode == 1
    lines = ours.stderr.strip().splitlines()
    assert len(lines) == 1, ours.stderr
    assert lines[0].startswith(f"rostui launch: {path}{where}") and message in lines[0], lines[0]
    assert ours.stdout == ""
    theirs = run_roslaunch(["--nodes", path, *extra], env)
    assert theirs.returncode != 0, theirs.stdout


@pytest.mark.parametrize("name,message", [("unknown_attribute.launch", "unknown <node> attribute 'colour'"),
                                          ("unknown_element.launch", "unrecognized tag <nodule>")])
def test_unknown_names_warn_and_strict_refuses(env: dict[str, str], name: str, message: str) -> None:
    """As in roslaunch, unknown elements/attributes do not stop --nodes; --strict and `launch check` refuse them.

    roslaunch's own checker (roslaunch-check's check_roslaunch) reports them as config errors too.
    """
    path = str(corpus_file(name))
    ours, theirs = _both(["--nodes", path], env)
    assert ours.returncode == theirs.returncode == 0, ours.stderr
    assert ours.stdout == theirs.stdout
    strict = run_rostui(["--strict", "--nodes", path], env)
    assert strict.returncode == 1 and strict.stdout == ""
    assert strict.stderr.strip() == f"rostui launch: {path}:2: {message}"
    checked = run_rostui(["check", path], env)
    assert checked.returncode == 1
    assert checked.stderr.strip() == f"rostui launch: {path}:2: {message}"
    check = subprocess.run([SYSTEM_PYTHON, "-c", "import sys, roslaunch.rlutil as r; "
                            "e = r.check_roslaunch(sys.argv[1]); print(e or ''); sys.exit(1 if e else 0)", path],
                           env=env, capture_output=True, text=True, timeout=60)
    assert check.returncode == 1 and "ROSLaunch config error" in check.stdout
