"""`rostui diagnostics --once` against Debian's diagnostics: a rospy diagnostic_updater node, Debian's aggregator,
and Debian's rosdiagnostic as the reference for the rosdiagnostic format (tests/diagnostics_helpers.py).
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path
from typing import Any, Iterator

import pytest

from conftest import rostui_cmd
from diagnostics_helpers import ROSDIAGNOSTIC, clean_env, need_debian_diagnostics, start_aggregator, start_publisher

STAMP = re.compile(r"^(Diagnostics generated on: |    timestamp:   )\d{4}-\d\d-\d\d \d\d:\d\d:\d\d(\.\d+)?[+-]\d\d:\d\d$")


def rostui_diagnostics(env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    """`rostui diagnostics ARGS`, its output kept."""
    return subprocess.run(rostui_cmd("diagnostics", *args), env=env, capture_output=True, text=True, timeout=90)


def without_stamps(text: str) -> list[str]:
    """The lines of ``text`` with each stamp (the two tools read different messages) checked and replaced."""
    lines = []
    for line in text.splitlines():
        if line.startswith(("Diagnostics generated on:", "    timestamp:")):
            assert STAMP.match(line), line
            line = line.split(":", 1)[0] + ": STAMP"
        lines.append(line)
    return lines


@pytest.fixture
def robot(any_master: str, ros_env: dict[str, str], tmp_path: Path) -> Iterator[dict[str, str]]:
    """The diagnostics publisher and Debian's aggregator on the test's master, the aggregator heard once."""
    need_debian_diagnostics()
    env = clean_env(ros_env)
    publisher = start_publisher(env, tmp_path / "publisher.log")
    aggregator = start_aggregator(env, tmp_path / "aggregator.log")
    try:
        first = rostui_diagnostics(env, "--once", "--topic", "/diagnostics_agg", "--wait", "60")
        assert first.returncode == 0, first.stderr + aggregator.output()
        yield env
    finally:
        aggregator.interrupt()
        publisher.interrupt()


def test_the_rosdiagnostic_format_prints_what_rosdiagnostic_prints(robot: dict[str, str]) -> None:
    """All levels, the details, rosdiagnostic's default (WARN and worse) and a filter, each as Debian's prints it."""
    for args in (["-l", "0"], ["-d", "-l", "0"], [], ["--filter", "Power|Motors"]):
        debian = subprocess.run([*ROSDIAGNOSTIC, "--nocolor", *args], env=robot, capture_output=True, text=True,
                                timeout=90)
        assert debian.returncode == 0, debian.stderr
        ours = rostui_diagnostics(robot, "--once", "--format", "rosdiagnostic", "--nocolor", *args)
        assert ours.returncode == 0, ours.stderr
        assert without_stamps(ours.stdout) == without_stamps(debian.stdout), args
        assert "[ ERROR ] /Power/robot_driver: battery charge - Charge low" in ours.stdout


def test_the_tree_shows_the_aggregators_groups(robot: dict[str, str]) -> None:
    done = rostui_diagnostics(robot, "--once", "-d")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    for expected in ("[ERROR] Power: Error", "[ERROR] └─ robot_driver: battery charge: Charge low",
                     "[WARN]  Motors: Warning", "[WARN]  └─ robot_driver: motor temperature: Running hot",
                     "[OK]    Sensors: OK", "[OK]    └─ robot_driver: laser connection: Scanning"):
        assert expected in lines, done.stdout
    assert any(line.strip() == "voltage: 10.9" for line in lines), done.stdout
    warn = rostui_diagnostics(robot, "--once", "--level", "warn")
    assert "Sensors" not in warn.stdout and "Motors" in warn.stdout, warn.stdout


def test_without_an_aggregator_the_flat_topic_is_listed(rostui_core: Any, ros_env: dict[str, str],
                                                        tmp_path: Path) -> None:
    need_debian_diagnostics()
    env = clean_env(ros_env)
    publisher = start_publisher(env, tmp_path / "publisher.log")
    try:
        done = rostui_diagnostics(env, "--once")
    finally:
        publisher.interrupt()
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["[ERROR] robot_driver: battery charge: Charge low",
                                        "[OK]    robot_driver: laser connection: Scanning",
                                        "[WARN]  robot_driver: motor temperature: Running hot"]


def test_nothing_to_hear_and_bad_words_are_one_line_errors(rostui_core: Any, ros_env: dict[str, str]) -> None:
    quiet = rostui_diagnostics(ros_env, "--once", "--wait", "1")
    assert quiet.returncode == 1 and quiet.stderr.strip().splitlines() == [
        "no diagnostics on /diagnostics_agg or /diagnostics within 1 s"], quiet.stderr
    for args, said in ((["--level", "loud"], "unknown level 'loud': choose ok, warn, error or stale"),
                       (["--once", "--filter", "("], "--filter '(' is not a regular expression"),
                       (["--once", "--format", "xml"], "unknown format 'xml': choose tree or rosdiagnostic")):
        done = rostui_diagnostics(ros_env, *args)
        assert done.returncode != 0 and len(done.stderr.strip().splitlines()) == 1, done.stderr
        assert said in done.stderr


def test_no_master_is_one_line(ros_env: dict[str, str]) -> None:
    done = rostui_diagnostics(ros_env, "--once")
    assert done.returncode == 1 and len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert "master" in done.stderr.lower()
