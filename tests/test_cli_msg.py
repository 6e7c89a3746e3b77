"""`rostui msg` / `rostui srv` against real rosmsg / rossrv on the same ROS_PACKAGE_PATH."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from cli_helpers import rostui
from conftest import REPO, SYSTEM_PYTHON, need_command, need_peer

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>0.0.1</version>
  <description>test package</description>
  <maintainer email="test@example.com">test</maintainer>
  <license>BSD</license>
</package>
"""

THING = """# a comment line
uint8 RED=1
int8 NEG = -5
float32 X=1.50
string NAME=hello # not a comment
Header header
geometry_msgs/Pose pose
Inner[] inners
float64[3] vals
time stamp
duration d
"""
INNER = "int32 a\nstring b   # trailing comment\nuint8 C=3\n"
DO = "int32 x\nInner inner\n---\nbool ok\nstring msg\n"


def make_package(root: Path, name: str, msgs: dict[str, str] = {}, srvs: dict[str, str] = {}) -> Path:  # noqa: B006
    """A package directory with package.xml and the given .msg/.srv files."""
    pkg = root / name
    pkg.mkdir(parents=True)
    (pkg / "package.xml").write_text(PACKAGE_XML.format(name=name))
    for sub, files in (("msg", msgs), ("srv", srvs)):
        if files:
            (pkg / sub).mkdir()
            for stem, text in files.items():
                (pkg / sub / f"{stem}.{sub}").write_text(text)
    return pkg


@pytest.fixture
def ws(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    """ROS_PACKAGE_PATH with tpkg plus copies of rostui's std_msgs/geometry_msgs (Debian ships no .msg files)."""
    root = tmp_path / "ws"
    make_package(root, "tpkg", {"Thing": THING, "Inner": INNER, "Empty": ""}, {"Do": DO})
    for dep in ("std_msgs", "geometry_msgs"):
        shutil.copytree(REPO / "rostui" / "share" / dep, root / dep)
    env = dict(os.environ)
    env["ROS_PACKAGE_PATH"] = str(root)
    env["ROS_HOME"] = str(tmp_path / "home")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(root))
    return env


def real(tool: str, args: list[str], env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    """Run a real ROS tool (rosmsg / rossrv)."""
    need_command(tool)
    return subprocess.run([tool, *args], env=env, capture_output=True, text=True, timeout=60,
                          stdin=subprocess.DEVNULL)


SAME_OUTPUT = [
    ("rosmsg", ["show", "tpkg/Thing"]),
    ("rosmsg", ["show", "-r", "tpkg/Thing"]),
    ("rosmsg", ["show", "--raw", "tpkg/Inner"]),
    ("rosmsg", ["info", "tpkg/Inner"]),
    ("rosmsg", ["show", "Thing"]),
    ("rosmsg", ["show", "-r", "Inner"]),
    ("rosmsg", ["show", "tpkg/Empty"]),
    ("rosmsg", ["show", "std_msgs/Header"]),
    ("rosmsg", ["show", "geometry_msgs/PoseStamped"]),
    ("rosmsg", ["md5", "std_msgs/Header"]),
    ("rosmsg", ["md5", "std_msgs/String"]),
    ("rosmsg", ["package", "tpkg"]),
    ("rosmsg", ["package", "-s", "tpkg"]),
    ("rossrv", ["show", "tpkg/Do"]),
    ("rossrv", ["show", "-r", "tpkg/Do"]),
    ("rossrv", ["show", "Do"]),
    ("rossrv", ["package", "tpkg"]),
]


@pytest.mark.parametrize("tool,args", SAME_OUTPUT, ids=[" ".join([t, *a]) for t, a in SAME_OUTPUT])
def test_same_output_as_real_tool(ws: dict[str, str], tool: str, args: list[str]) -> None:
    want = real(tool, args, ws)
    assert want.returncode == 0, want.stderr
    got = rostui([tool[3:], *args], ws)
    assert (got.returncode, got.stdout) == (0, want.stdout)


ERRORS = [
    ("rosmsg", ["show", "Nope"]),
    ("rosmsg", ["show", "tpkg/Do"]),
    ("rossrv", ["show", "Nope"]),
    ("rossrv", ["show", "tpkg/Thing"]),
    ("rosmsg", ["show", "tpkg/"]),
]


@pytest.mark.parametrize("tool,args", ERRORS, ids=[" ".join([t, *a]) for t, a in ERRORS])
def test_same_error_as_real_tool(ws: dict[str, str], tool: str, args: list[str]) -> None:
    want = real(tool, args, ws)
    got = rostui([tool[3:], *args], ws)
    assert (got.returncode, got.stdout, got.stderr) == (want.returncode, want.stdout, want.stderr)


def test_unknown_package_type_error_starts_like_rosmsg(ws: dict[str, str]) -> None:
    want = real("rosmsg", ["show", "nope/Foo"], ws)
    got = rostui(["msg", "show", "nope/Foo"], ws)
    assert got.returncode == want.returncode == 1
    assert got.stderr.strip() == "Unable to load msg [nope/Foo]: Cannot locate message [Foo]: unknown package [nope]"
    assert want.stderr.startswith(got.stderr.strip())


def test_package_of_unknown_package(ws: dict[str, str]) -> None:
    want = real("rosmsg", ["package", "nope"], ws)
    got = rostui(["msg", "package", "nope"], ws)
    assert got.returncode == want.returncode == 64
    assert got.stderr.splitlines()[:2] == want.stderr.splitlines()[:2]


def test_md5_without_match_is_a_notice(ws: dict[str, str]) -> None:
    want = real("rosmsg", ["md5", "Zork"], ws)
    got = rostui(["msg", "md5", "Zork"], ws)
    assert (got.returncode, got.stdout, got.stderr) == (want.returncode, want.stdout, want.stderr)


def test_list_matches_rosmsg_on_shared_packages(ws: dict[str, str]) -> None:
    for tool in ("rosmsg", "rossrv"):
        want = real(tool, ["list"], ws).stdout.splitlines()
        got = rostui([tool[3:], "list"], ws).stdout.splitlines()
        shared = {"tpkg", "std_msgs", "geometry_msgs"}
        # rosmsg lists a package found in two places (the workspace and Debian's /usr/share) twice; rostui once
        once = list(dict.fromkeys(want))
        assert [t for t in got if t.split("/")[0] in shared] == [t for t in once if t.split("/")[0] in shared]
        assert set(want) <= set(got)
    packages = real("rosmsg", ["packages"], ws).stdout.splitlines()
    assert set(packages) <= set(rostui(["msg", "packages"], ws).stdout.splitlines())


def genmsg_md5(ws: dict[str, str], kind: str, type_name: str) -> str:
    """The md5 genmsg (real ROS's generator library) computes for a type in the workspace."""
    code = f"""
import sys, os, genmsg, genmsg.msg_loader as ml
from genmsg.gentools import compute_md5
root = {os.environ['ROS_PACKAGE_PATH']!r}
search = {{p: [os.path.join(root, p, 'msg')] for p in os.listdir(root)}}
ctx = genmsg.MsgContext.create_default()
if {kind!r} == 'msg':
    spec = ml.load_msg_by_type(ctx, {type_name!r}, search)
else:
    pkg, name = {type_name!r}.split('/')
    spec = ml.load_srv_from_file(ctx, os.path.join(root, pkg, 'srv', name + '.srv'), {type_name!r})
ml.load_depends(ctx, spec, search)
print(compute_md5(ctx, spec))
"""
    need_peer(Path(SYSTEM_PYTHON).exists(), "system python3 with genmsg")
    r = subprocess.run([SYSTEM_PYTHON, "-c", code], env=ws, capture_output=True, text=True, timeout=60)
    need_peer(r.returncode == 0 or "No module named 'genmsg'" not in r.stderr, "genmsg (python3-genmsg)")
    assert r.returncode == 0, r.stderr
    return r.stdout.strip()


@pytest.mark.parametrize("kind,type_name", [("msg", "tpkg/Thing"), ("msg", "tpkg/Inner"), ("srv", "tpkg/Do")])
def test_md5_matches_genmsg(ws: dict[str, str], kind: str, type_name: str) -> None:
    got = rostui([kind, "md5", type_name], ws)
    assert got.returncode == 0, got.stderr
    assert got.stdout == genmsg_md5(ws, kind, type_name) + "\n"


def test_md5_bare_name_has_header(ws: dict[str, str]) -> None:
    got = rostui(["msg", "md5", "Inner"], ws)
    assert got.stdout == f"[tpkg/Inner]: {genmsg_md5(ws, 'msg', 'tpkg/Inner')}\n"


def test_show_json(ws: dict[str, str]) -> None:
    got = rostui(["msg", "show", "--json", "tpkg/Thing"], ws)
    assert got.returncode == 0, got.stderr
    (item,) = json.loads(got.stdout)
    assert item["type"] == "tpkg/Thing"
    assert [c["name"] for c in item["constants"]] == ["RED", "NEG", "X", "NAME"]
    assert item["constants"][3]["value"] == "hello # not a comment"
    fields = {f["name"]: f for f in item["fields"]}
    assert fields["header"]["type"] == "std_msgs/Header"
    assert fields["inners"]["message"]["type"] == "tpkg/Inner"
    assert fields["vals"]["array_length"] == 3
    srv = json.loads(rostui(["srv", "show", "--json", "tpkg/Do"], ws).stdout)[0]
    assert [f["name"] for f in srv["response"]["fields"]] == ["ok", "msg"]
    listed = json.loads(rostui(["msg", "list", "--json"], ws).stdout)
    assert listed == rostui(["msg", "list"], ws).stdout.split() and "geometry_msgs/Accel" in listed


def test_type_completion(ws: dict[str, str]) -> None:
    from rostui.cli.complete import complete_msg_types, complete_srv_types
    from rostui.core import packages

    packages.clear_cache()
    assert complete_msg_types("tpkg/") == ["tpkg/Empty", "tpkg/Inner", "tpkg/Thing"]
    assert complete_srv_types("tpkg/") == ["tpkg/Do"]
