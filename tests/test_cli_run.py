"""`rostui run` against real rosrun: lookup, argument pass-through, exec, errors."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from cli_helpers import rostui
from conftest import REPO, need_command

PACKAGE_XML = '<?xml version="1.0"?>\n<package format="2"><name>{name}</name><version>0.0.1</version>' \
              '<description>t</description><maintainer email="t@example.com">t</maintainer>' \
              '<license>BSD</license></package>\n'

ECHO = '#!/bin/sh\necho "args:$#"\nfor a in "$@"; do echo "[$a]"; done\necho "pid:$$"\nexit 7\n'


def write(path: Path, text: str, mode: int = 0o755) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    path.chmod(mode)


@pytest.fixture
def ws(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    """A package with executables in nested folders, a duplicate, a non-executable file and a build/ folder."""
    pkg = tmp_path / "ws" / "tpkg"
    write(pkg / "package.xml", PACKAGE_XML.format(name="tpkg"), 0o644)
    write(pkg / "scripts" / "talker", ECHO)
    write(pkg / "nodes" / "deep" / "deep_node", ECHO)
    write(pkg / "scripts" / "dup", ECHO.replace("args:", "first args:"))
    write(pkg / "other" / "dup", ECHO.replace("args:", "second args:"))
    write(pkg / "build" / "only_in_build", ECHO)
    write(pkg / "data.txt", "x\n", 0o644)
    write(pkg / "scripts" / "plain.py", "import sys\nprint('py', sys.argv[1:])\nsys.exit(4)\n", 0o644)
    env = dict(os.environ)
    env["ROS_PACKAGE_PATH"] = str(tmp_path / "ws")
    env["ROS_HOME"] = str(tmp_path / "home")
    monkeypatch.setenv("ROS_PACKAGE_PATH", env["ROS_PACKAGE_PATH"])
    return env


def rosrun(args: list[str], env: dict[str, str], input: str | None = None) -> subprocess.CompletedProcess[str]:
    need_command("rosrun")
    return subprocess.run(["rosrun", *args], env=env, capture_output=True, text=True, timeout=60, input=input,
                          stdin=None if input is not None else subprocess.DEVNULL)


def without_pid(text: str) -> str:
    return "\n".join(l for l in text.splitlines() if not l.startswith("pid:"))


PASS_THROUGH = [
    ["tpkg", "talker"],
    ["tpkg", "talker", "chatter:=/x", "__name:=talker2", "_rate:=5", "-x", "--flag", "a b", ""],
    ["tpkg", "talker", "-h"],
    ["tpkg", "talker", "--prefix", "p"],
    ["tpkg", "deep_node", "__ns:=/robot"],
    ["tpkg", "scripts/talker", "q"],
]


@pytest.mark.parametrize("args", PASS_THROUGH, ids=[" ".join(a) for a in PASS_THROUGH])
def test_runs_like_rosrun(ws: dict[str, str], args: list[str]) -> None:
    want = rosrun(args, ws)
    got = rostui(["run", *args], ws)
    assert want.returncode == 7, want.stdout + want.stderr
    assert (got.returncode, without_pid(got.stdout), got.stderr) == (7, without_pid(want.stdout), want.stderr)


def test_process_is_replaced(ws: dict[str, str]) -> None:
    proc = subprocess.Popen([sys.executable, "-m", "rostui", "run", "tpkg", "talker"], env=ws, cwd=REPO,
                            stdout=subprocess.PIPE, text=True)
    out, _ = proc.communicate(timeout=30)
    assert proc.returncode == 7
    assert f"pid:{proc.pid}" in out.splitlines()


def test_unknown_package_same_as_rosrun(ws: dict[str, str]) -> None:
    want = rosrun(["no_such_pkg", "talker"], ws)
    got = rostui(["run", "no_such_pkg", "talker"], ws)
    assert (got.returncode, got.stderr) == (want.returncode, want.stderr) == (
        2, "[rospack] Error: package 'no_such_pkg' not found\n")
    assert got.stdout == ""


@pytest.mark.parametrize("args", [["tpkg", "nothere"], ["tpkg", "data.txt"], ["tpkg", "only_in_build"],
                                  ["tpkg", "scripts/nothere"], ["tpkg", "dir/"]])
def test_unknown_executable_same_wording_as_rosrun(ws: dict[str, str], args: list[str]) -> None:
    want = rosrun(args, ws)
    got = rostui(["run", *args], ws)
    # rosrun echoes these lines to stdout; rostui keeps stdout for data and writes them to stderr
    assert (got.returncode, got.stdout, got.stderr) == (want.returncode, "", want.stdout)
    assert got.returncode in (1, 3)


def test_non_unique_executable_prompts_like_rosrun(ws: dict[str, str]) -> None:
    for answer in ("1\n", "2\n"):
        want = rosrun(["tpkg", "dup", "z"], ws, input=answer)
        got = rostui(["run", "tpkg", "dup", "z"], ws, input=answer)
        assert got.returncode == want.returncode == 7
        # same candidates in the same (directory) order, so the same answer starts the same file
        assert without_pid(got.stdout) == without_pid(want.stdout).replace(
            "[rosrun] You have chosen a non-unique executable, please pick one of the following:\n", "")
        assert "args:1" in got.stdout
        assert "1) " in got.stderr and "2) " in got.stderr and "#? " in got.stderr


def test_non_unique_without_answer_fails(ws: dict[str, str]) -> None:
    got = rostui(["run", "tpkg", "dup"], ws)
    assert got.returncode == 3
    assert got.stderr.splitlines()[-1].endswith("[rosrun] No executable chosen")


def test_non_executable_py_runs_with_this_python(ws: dict[str, str]) -> None:
    got = rostui(["run", "tpkg", "plain.py", "a:=b", "-v"], ws)
    assert (got.returncode, got.stdout) == (4, "py ['a:=b', '-v']\n")


def test_usage_error_without_executable(ws: dict[str, str]) -> None:
    got = rostui(["run", "tpkg"], ws)
    assert got.returncode == 2
    assert "Missing argument" in got.stderr


def test_builtin_package_scripts_use_this_python(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from rostui.core import packages
    from rostui.tools import run

    share = tmp_path / "share"
    write(share / "agitr" / "package.xml", PACKAGE_XML.format(name="agitr"), 0o644)
    write(share / "agitr" / "nodes" / "hello", "#!/usr/bin/env python3\nprint('hi')\n")
    write(share / "agitr" / "nodes" / "pubvel.py", "print('hi')\n")
    write(share / "agitr" / "nodes" / "native", "#!/bin/sh\necho hi\n")
    monkeypatch.setattr(packages, "BUILTIN_SHARE", share)
    monkeypatch.setenv("ROS_PACKAGE_PATH", "")
    packages.clear_cache()
    try:
        node = share / "agitr" / "nodes"
        assert run.resolve("agitr", "hello", ["__name:=x"]) == [sys.executable, str(node / "hello"), "__name:=x"]
        assert run.resolve("agitr", "pubvel.py", []) == [sys.executable, str(node / "pubvel.py")]
        assert run.resolve("agitr", "native", ["a"]) == [str(node / "native"), "a"]
        assert run.resolve("agitr", "native", [], prefix="valgrind -q") == ["valgrind", "-q", str(node / "native")]
        from rostui.cli.complete import complete_executables

        class Ctx:
            params = {"package": "agitr"}

        assert complete_executables(Ctx(), "") == ["hello", "native", "pubvel.py"]  # type: ignore[arg-type]
    finally:
        packages.clear_cache()


def test_installed_package_libexec_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A package at <prefix>/share/<pkg> also runs executables from <prefix>/lib/<pkg> (catkin/Debian layout)."""
    from rostui.core import packages
    from rostui.tools import run

    prefix = tmp_path / "usr"
    write(prefix / "share" / "ipkg" / "package.xml", PACKAGE_XML.format(name="ipkg"), 0o644)
    write(prefix / "lib" / "ipkg" / "node", ECHO)
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(prefix / "share"))
    packages.clear_cache()
    assert run.resolve("ipkg", "node", []) == [str(prefix / "lib" / "ipkg" / "node")]
