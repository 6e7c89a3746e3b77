"""Debian's ROS layout on ROS_PACKAGE_PATH: packages without their .msg files must not hide rostui's built-ins.

Debian installs ``/usr/share/rosgraph_msgs/package.xml`` (and cmake files) but no ``msg/Log.msg``.  With
``ROS_PACKAGE_PATH=/usr/share`` a type is looked for in every directory of its package, down to rostui's
built-in copy in ``rostui/share``; when it exists nowhere, the tools say so in one line, never a traceback.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Iterator

import pytest

from cli_helpers import rostui
from conftest import REPO, master_port, stop_process, wait_for_core, wait_until
from rostui.core import packages
from rostui.core.msg import clear_cache, get_message_class, list_message_types, md5sum

DEBIAN_SHARE = Path("/usr/share")
ROSGRAPH_MSGS_XML = Path("/usr/share/rosgraph_msgs/package.xml")
LOG_MD5 = "acffd30cd6b6de30f120938c17c593fb"  # rosgraph_msgs/Log, as genmsg computes it


def need_debian_layout() -> None:
    from conftest import need_peer

    from debian_peers import describe

    need_peer(ROSGRAPH_MSGS_XML.is_file(), describe(str(ROSGRAPH_MSGS_XML)))


def fake_package(root: Path, name: str, log_msg: str | None = None) -> Path:
    """A package dir with package.xml; with ``log_msg``, a msg/Log.msg of that text (else no msg/ at all)."""
    pkg = root / name
    pkg.mkdir(parents=True)
    (pkg / "package.xml").write_text(f"<package><name>{name}</name></package>\n")
    if log_msg is not None:
        (pkg / "msg").mkdir()
        (pkg / "msg" / "Log.msg").write_text(log_msg)
    return pkg


@pytest.fixture
def package_path(monkeypatch: pytest.MonkeyPatch) -> Iterator[pytest.MonkeyPatch]:
    """Types and packages forgotten before and after the test (the test sets ROS_PACKAGE_PATH)."""
    clear_cache()
    yield monkeypatch
    monkeypatch.undo()
    clear_cache()


def test_fake_package_without_msg_does_not_hide_builtin(package_path: pytest.MonkeyPatch, tmp_path: Path) -> None:
    fake = fake_package(tmp_path, "rosgraph_msgs")
    package_path.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    clear_cache()
    assert packages.find_package("rosgraph_msgs") == fake  # rospack's answer is unchanged
    debian = [ROSGRAPH_MSGS_XML.parent] if ROSGRAPH_MSGS_XML.is_file() else []  # found last, as rospack would
    assert packages.find_package_dirs("rosgraph_msgs") == [fake, packages.BUILTIN_SHARE / "rosgraph_msgs", *debian]
    assert md5sum("rosgraph_msgs/Log") == LOG_MD5
    assert get_message_class("rosgraph_msgs/Log")._type == "rosgraph_msgs/Log"
    assert "rosgraph_msgs/Log" in list_message_types("rosgraph_msgs")


def test_debian_share_does_not_hide_builtin(package_path: pytest.MonkeyPatch) -> None:
    need_debian_layout()
    package_path.setenv("ROS_PACKAGE_PATH", str(DEBIAN_SHARE))
    clear_cache()
    assert packages.find_package("rosgraph_msgs") == DEBIAN_SHARE / "rosgraph_msgs"
    assert md5sum("rosgraph_msgs/Log") == LOG_MD5
    assert get_message_class("std_msgs/String")._md5sum == "992ce8a1687cec8c8bd883ec73ca41d1"


def test_a_package_with_the_file_still_wins(package_path: pytest.MonkeyPatch, tmp_path: Path) -> None:
    fake_package(tmp_path, "rosgraph_msgs", "string only_this\n")
    package_path.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    clear_cache()
    assert [f.name for f in get_message_class("rosgraph_msgs/Log")._spec.fields] == ["only_this"]


def start_core(env: dict[str, str], tmp_path: Path) -> tuple[subprocess.Popen, Path, Path]:
    out, err = tmp_path / "core.out", tmp_path / "core.err"
    proc = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(master_port(env))], env=env,
                            cwd=REPO, stdout=out.open("w"), stderr=err.open("w"), stdin=subprocess.DEVNULL)
    return proc, out, err


@pytest.mark.parametrize("layout", ["debian", "fake"])
def test_core_runs_with_packages_lacking_msg(ros_env: dict[str, str], tmp_path: Path, layout: str) -> None:
    """`ROS_PACKAGE_PATH=/usr/share rostui core` printed "started master" and died with a traceback."""
    if layout == "debian":
        need_debian_layout()
        path = str(DEBIAN_SHARE)
    else:
        fake_package(tmp_path / "pkgs", "rosgraph_msgs")
        fake_package(tmp_path / "pkgs", "std_msgs")
        path = str(tmp_path / "pkgs")
    env = dict(ros_env, ROS_PACKAGE_PATH=path)
    proc, out, err = start_core(env, tmp_path)
    try:
        wait_for_core(master_port(env), proc)  # /rosout_agg registered: rosout found rosgraph_msgs/Log
        assert "started core service [/rosout]" in out.read_text()
    finally:
        stop_process(proc)
    assert proc.returncode == 0
    assert "Traceback" not in err.read_text()


def test_core_says_in_one_line_when_log_cannot_load(ros_env: dict[str, str], tmp_path: Path) -> None:
    """A Log.msg that exists but is broken is a real error: one line on stderr, exit 1, no traceback."""
    fake_package(tmp_path / "pkgs", "rosgraph_msgs", "int32 a\nnot a declaration at all\n")
    env = dict(ros_env, ROS_PACKAGE_PATH=str(tmp_path / "pkgs"))
    proc, out, err = start_core(env, tmp_path)
    try:
        proc.wait(timeout=60)
    finally:
        stop_process(proc)
    assert proc.returncode == 1
    lines = err.read_text().strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("ERROR: rostui core cannot start /rosout: "), lines
    assert "Log.msg:2" in lines[0]


def test_launch_with_debian_path_starts_its_master(ros_env: dict[str, str], tmp_path: Path) -> None:
    """`rostui launch` starts its in-process master and /rosout with Debian's /usr/share first on the path."""
    need_debian_layout()
    from launch_helpers import BUILTIN_SHARE

    env = dict(ros_env, ROS_PACKAGE_PATH=f"{DEBIAN_SHARE}:{BUILTIN_SHARE}")
    launch_file = tmp_path / "empty.launch"
    launch_file.write_text('<launch><param name="x" value="1"/></launch>\n')
    out, err = tmp_path / "launch.out", tmp_path / "launch.err"
    proc = subprocess.Popen([sys.executable, "-m", "rostui", "launch", str(launch_file)], env=env, cwd=REPO,
                            stdout=out.open("w"), stderr=err.open("w"), stdin=subprocess.DEVNULL)
    try:
        wait_until(lambda: "started master" in out.read_text() or proc.poll() is not None, "the master", timeout=60)
        assert proc.poll() is None, err.read_text()  # the master (and /rosout) stays up with the launch
    finally:
        stop_process(proc, timeout=60)
    assert "started master (in this process) and /rosout" in out.read_text()
    assert "Traceback" not in err.read_text(), err.read_text()


def test_launch_says_in_one_line_when_log_cannot_load(ros_env: dict[str, str], tmp_path: Path) -> None:
    fake_package(tmp_path / "pkgs", "rosgraph_msgs", "int32 a\nnot a declaration at all\n")
    env = dict(ros_env, ROS_PACKAGE_PATH=str(tmp_path / "pkgs"))
    launch_file = tmp_path / "empty.launch"
    launch_file.write_text('<launch><param name="x" value="1"/></launch>\n')
    result = subprocess.run([sys.executable, "-m", "rostui", "launch", str(launch_file)], env=env, cwd=REPO,
                            capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)
    assert result.returncode == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("rostui launch: cannot start a master with /rosout: "), lines


def test_msg_show_and_list_find_built_in_types_behind_debians_packages() -> None:
    """`rostui msg show/list` look in every directory of a package, as the registry does."""
    need_debian_layout()
    env = dict(os.environ, ROS_PACKAGE_PATH=str(DEBIAN_SHARE))
    shown = rostui(["msg", "show", "rosgraph_msgs/Log"], env)
    assert shown.returncode == 0, shown.stderr
    assert shown.stdout.splitlines()[:3] == ["byte DEBUG=1", "byte INFO=2", "byte WARN=4"]
    listed = rostui(["msg", "list"], env)
    assert "rosgraph_msgs/Log" in listed.stdout.splitlines()
    md5 = rostui(["msg", "md5", "rosgraph_msgs/Log"], env)
    assert md5.stdout.strip() == LOG_MD5


def test_pkg_find_sees_debians_packages_without_ros_package_path() -> None:
    """A Debian user sets no ROS_PACKAGE_PATH: `rostui pkg find` answers as Debian's rospack for its packages."""
    need_debian_layout()
    from conftest import need_peer

    from debian_peers import describe

    need_peer(shutil.which("rospack") is not None, describe("rospack"))
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH")}
    debian_only = [p.parent.name for p in sorted(DEBIAN_SHARE.glob("*/package.xml"))
                   if not (packages.BUILTIN_SHARE / p.parent.name).exists()][:5]
    assert debian_only, "Debian's ROS installs packages under /usr/share"
    for name in debian_only:
        theirs = subprocess.run(["rospack", "find", name], env=env, capture_output=True, text=True, timeout=30)
        ours = rostui(["pkg", "find", name], env)
        assert (ours.returncode, ours.stdout) == (0, theirs.stdout), (name, ours.stderr)
    builtin = rostui(["pkg", "find", "rosgraph_msgs"], env)  # rostui's own copy keeps its tools
    assert builtin.stdout.strip() == str(packages.BUILTIN_SHARE / "rosgraph_msgs")
