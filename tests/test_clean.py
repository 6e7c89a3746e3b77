"""`rostui clean check|purge` on a private ROS_HOME with fake runs."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from rostui.core.log.clean import (
    active_run, check_lines, disk_usage, execute_purge, human_size, plan_purge,
)
from rostui.core.log.files import update_latest_link

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture
def home(tmp_path: Path) -> Path:
    """ROS_HOME with three runs (the newest is `latest`) and a stray node log."""
    home = tmp_path / "ros home"
    for index, (name, size) in enumerate([("run-old", 300_000), ("run-mid", 50_000), ("run-new", 20_000)]):
        run = home / "log" / name
        run.mkdir(parents=True)
        (run / "rosout.log").write_bytes(b"x" * size)
        (run / "master.log").write_bytes(b"m" * 100)
        os.utime(run, (1_000_000 + index * 1000, 1_000_000 + index * 1000))
    (home / "log" / "talker.log").write_bytes(b"t" * 5000)
    os.utime(home / "log" / "talker.log", (999_000, 999_000))
    update_latest_link(home / "log" / "run-new")
    return home


def run_cli(home: Path, *args: str, stdin: int | None = subprocess.DEVNULL, input: str | None = None,
            extra_env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ("ROS_LOG_DIR", "ROS_HOME")}
    env["ROS_HOME"] = str(home)
    env.update(extra_env or {})
    kwargs = {"input": input} if input is not None else {"stdin": stdin}
    return subprocess.run([sys.executable, "-m", "rostui", "clean", *args], env=env, cwd=REPO,
                          capture_output=True, text=True, timeout=60, **kwargs)


@pytest.mark.parametrize("size,text", [
    (0, "0"), (512, "512"), (1023, "1023"), (1024, "1.0K"), (1025, "1.1K"), (4096, "4.0K"),
    (10 * 1024 - 1, "10K"), (10 * 1024, "10K"), (413_696, "404K"), (1024 * 1024 - 1, "1.0M"),
    (1024 * 1024, "1.0M"), (1_153_459_550, "1.1G"),
])
def test_human_size_is_du_h(size: int, text: str) -> None:
    assert human_size(size) == text


@pytest.mark.skipif(shutil.which("du") is None, reason="needs du")
def test_check_matches_du_sh(home: Path) -> None:
    du = subprocess.run(["du", "-sh", str(home / "log")], capture_output=True, text=True).stdout.split()[0]
    assert check_lines({"ROS_HOME": str(home)}) == [f"{du} ROS node logs"]
    result = run_cli(home, "check")
    assert result.returncode == 0, result.stderr
    assert result.stdout == f"{du} ROS node logs\n"


def test_check_prints_nothing_without_a_log_dir(tmp_path: Path) -> None:
    result = run_cli(tmp_path / "empty", "check")
    assert result.returncode == 0 and result.stdout == ""


def test_check_honours_ros_log_dir(home: Path, tmp_path: Path) -> None:
    other = tmp_path / "elsewhere"
    other.mkdir()
    (other / "a.log").write_bytes(b"a" * 70_000)
    result = run_cli(home, "check", extra_env={"ROS_LOG_DIR": str(other)})
    assert result.stdout == f"{human_size(disk_usage(other))} ROS node logs\n"


def test_plan_keeps_latest_and_its_run(home: Path) -> None:
    root = home / "log"
    assert active_run(root) == root / "run-new"
    plan = plan_purge(root)
    assert sorted(p.name for p in plan.targets) == ["run-mid", "run-old", "talker.log"]
    assert plan.kept == [root / "run-new"]
    kept_too = plan_purge(root, keep_run_ids=["run-mid"])
    assert sorted(p.name for p in kept_too.targets) == ["run-old", "talker.log"]


def test_size_limit_removes_oldest_first(home: Path) -> None:
    plan = plan_purge(home / "log", size_limit=100_000)
    assert [p.name for p in plan.targets] == ["talker.log", "run-old"]


def test_execute_reports_freed_bytes(home: Path) -> None:
    plan = plan_purge(home / "log")
    expected = sum(disk_usage(p) for p in plan.targets)
    result = execute_purge(plan)
    assert result.freed == expected and not result.failed
    assert sorted(p.name for p in (home / "log").iterdir()) == ["latest", "run-new"]


def test_purge_refuses_without_tty_or_y(home: Path) -> None:
    before = sorted(p.name for p in (home / "log").iterdir())
    result = run_cli(home, "purge")
    assert result.returncode != 0
    assert result.stderr.strip().count("\n") == 0 and "-y" in result.stderr
    assert sorted(p.name for p in (home / "log").iterdir()) == before


def test_purge_y_keeps_the_active_run(home: Path) -> None:
    freed = human_size(sum(disk_usage(p) for p in plan_purge(home / "log").targets))
    result = run_cli(home, "purge", "-y")
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[0] == "Purging ROS node logs."
    assert f"Freed {freed} from ROS node logs (3 of 3 entries removed)." in result.stdout
    assert sorted(p.name for p in (home / "log").iterdir()) == ["latest", "run-new"]
    assert (home / "log" / "latest").is_symlink() and (home / "log" / "run-new" / "rosout.log").exists()
    again = run_cli(home, "purge", "-y")
    assert again.returncode == 0 and "Nothing to purge" in again.stdout


def test_purge_asks_on_a_terminal(home: Path) -> None:
    import pty

    leader, follower = pty.openpty()
    try:
        env = {k: v for k, v in os.environ.items() if k not in ("ROS_LOG_DIR",)}
        env["ROS_HOME"] = str(home)
        proc = subprocess.Popen([sys.executable, "-m", "rostui", "clean", "purge"], env=env, cwd=REPO,
                                stdin=follower, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        os.write(leader, b"maybe\nn\n")
        out, err = proc.communicate(timeout=60)
    finally:
        os.close(follower)
        os.close(leader)
    assert proc.returncode == 0, err
    assert "PLEASE BE CAREFUL TO VERIFY THE COMMAND BELOW!\nOkay to perform:\n\n" in out
    assert f"rm -rf \"{home / 'log' / 'run-old'}\"" in out and out.rstrip().endswith("Nothing deleted.")
    assert "(y/n)?" in out
    assert (home / "log" / "run-old").exists()
