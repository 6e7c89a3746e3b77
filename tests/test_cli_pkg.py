"""`rostui pkg list | find | ls` against real rospack and rosls on the same ROS_PACKAGE_PATH."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest
from cli_helpers import rostui
from conftest import need_command, need_peer
from debian_peers import describe

ROSBASH = Path("/usr/share/bash-completion/completions/rosbash")

PACKAGE_XML = '<?xml version="1.0"?>\n<package format="2"><name>{name}</name><version>0.0.1</version>' \
              '<description>t</description><maintainer email="t@example.com">t</maintainer>' \
              '<license>BSD</license></package>\n'


@pytest.fixture
def ws(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    """Two roots: tpkg (with a nested folder) and a package whose directory name differs from its name."""
    a, b = tmp_path / "a", tmp_path / "b"
    pkg = a / "group" / "tpkg"
    (pkg / "msg").mkdir(parents=True)
    (pkg / "package.xml").write_text(PACKAGE_XML.format(name="tpkg"))
    for name in ("Zeta.msg", "alpha.msg", "Beta.msg"):
        (pkg / "msg" / name).write_text("int32 a\n")
    (pkg / ".hidden").write_text("")
    (pkg / "CMakeLists.txt").write_text("")
    other = b / "dir_name"
    other.mkdir(parents=True)
    (other / "package.xml").write_text(PACKAGE_XML.format(name="other_pkg"))
    shadow = b / "tpkg_copy"
    shadow.mkdir()
    (shadow / "package.xml").write_text(PACKAGE_XML.format(name="tpkg"))
    env = dict(os.environ)
    env["ROS_PACKAGE_PATH"] = f"{a}:{b}"
    env["ROS_HOME"] = str(tmp_path / "home")
    monkeypatch.setenv("ROS_PACKAGE_PATH", env["ROS_PACKAGE_PATH"])
    return env


def rospack(args: list[str], env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    need_command("rospack")
    return subprocess.run(["rospack", *args], env=env, capture_output=True, text=True, timeout=60)


def rosls(arg: str, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    need_peer(ROSBASH.exists(), describe(str(ROSBASH)))
    return subprocess.run(["bash", "-c", f'source {ROSBASH}; rosls "$1"', "rosls", arg], env=env,
                          capture_output=True, text=True, timeout=60)


@pytest.mark.parametrize("package", ["tpkg", "other_pkg"])
def test_find_same_as_rospack(ws: dict[str, str], package: str) -> None:
    want = rospack(["find", package], ws)
    got = rostui(["pkg", "find", package], ws)
    assert (got.returncode, got.stdout, got.stderr) == (0, want.stdout, "")


def test_find_unknown_package_same_as_rospack(ws: dict[str, str]) -> None:
    want = rospack(["find", "no_such_pkg"], ws)
    got = rostui(["pkg", "find", "no_such_pkg"], ws)
    assert (got.returncode, got.stdout, got.stderr) == (want.returncode, want.stdout, want.stderr)
    assert got.stderr == "[rospack] Error: package 'no_such_pkg' not found\n"


def test_list_same_lines_as_rospack(ws: dict[str, str]) -> None:
    want = rospack(["list"], ws).stdout.splitlines()
    got = rostui(["pkg", "list"], ws).stdout.splitlines()
    mine = {"tpkg", "other_pkg"}
    assert [l for l in got if l.split()[0] in mine] == [l for l in want if l.split()[0] in mine]
    assert got == sorted(got)
    assert any(l.startswith("std_msgs ") for l in got)  # built-in packages are listed too
    listed = json.loads(rostui(["pkg", "list", "--json"], ws).stdout)
    assert listed["other_pkg"].endswith("dir_name")


@pytest.mark.parametrize("arg", ["tpkg", "tpkg/msg", "tpkg/msg/", "other_pkg", "tpkg/CMakeLists.txt"])
def test_ls_same_as_rosls(ws: dict[str, str], arg: str) -> None:
    want = rosls(arg, ws)
    got = rostui(["pkg", "ls", arg], ws)
    assert (got.returncode, got.stdout) == (want.returncode, want.stdout)


@pytest.mark.parametrize("arg", ["tpkg/nothere", "tpkg/CMakeLists.txt/x"])
def test_ls_missing_path_same_as_rosls(ws: dict[str, str], arg: str) -> None:
    want = rosls(arg, ws)
    got = rostui(["pkg", "ls", arg], ws)
    assert (got.returncode, got.stdout, got.stderr) == (want.returncode, want.stdout, want.stderr)


def test_ls_unknown_package(ws: dict[str, str]) -> None:
    want = rosls("no_such_pkg", ws)
    got = rostui(["pkg", "ls", "no_such_pkg"], ws)
    assert got.returncode == want.returncode == 2
    assert got.stderr == "[rospack] Error: package 'no_such_pkg' not found\n"


def test_ls_json_and_columns(ws: dict[str, str]) -> None:
    from rostui.tools.pkg import columns

    assert json.loads(rostui(["pkg", "ls", "--json", "tpkg/msg"], ws).stdout) == \
        rostui(["pkg", "ls", "tpkg/msg"], ws).stdout.splitlines()
    assert columns(["a", "bb", "ccc", "d"], 80) == ["a  bb  ccc  d"]
    assert columns(["a", "bb", "ccc", "d"], 8) == ["a   ccc", "bb  d"]
    assert columns([], 80) == []


def test_package_completion(ws: dict[str, str]) -> None:
    from rostui.cli.complete import complete_packages
    from rostui.core import packages

    packages.clear_cache()
    assert complete_packages("tp") == ["tpkg"]
    assert "std_msgs" in complete_packages("")
