"""The real projects' own tests of rospkg and rosgraph, unmodified, under Debian's python3 and ``rostui python``.

rospkg's test suite (its RosPack, RosStack, manifest, environment tests and their package trees) and ros_comm's
rosgraph tests (names, rosenv, myargv, the master API offline and against a live master) are kept in
tests/python_compat/real/ (sources and licences in its SOURCES.md). Each file runs under Debian's
python3-rospkg/python3-rosgraph and under rostui's, test by test (tests/python_compat/own/run_test_functions.py
prints a line a test); both must give the same outcome for every test. ros_comm's online master test runs as it
is written, through ``rostest.rosrun``, against rostui core and a real roscore.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_peer, rostui_cmd

REAL = REPO / "tests" / "python_compat" / "real"
RUNNER = REPO / "tests" / "python_compat" / "own" / "run_test_functions.py"
OFFLINE_SUITES = sorted(
    [*(REAL / "rospkg_tests").glob("test_*.py")]
    + [REAL / "rosgraph_tests" / name for name in ("test_names.py", "test_rosenv.py", "test_myargv.py",
                                                    "test_rosgraph_masterapi_offline.py")]
)
#: Tests that fail under Debian's rospkg as they do under rostui's, for the same reason: both add folders
#: after ROS_PACKAGE_PATH (/usr/share for Debian's rospkg; its built-in packages, then /usr/share, for rostui's), so
#: ``get_ros_package_path`` is never None and a RosPack with no ROS environment still finds roscpp.
FAIL_UNDER_BOTH = {"test_get_ros_package_path", "test_RosPack_no_env"}


def script_env(ros_env: dict[str, str]) -> dict[str, str]:
    """ros_env without a ROS_PACKAGE_PATH or a choice of implementation (the suites set their own paths)."""
    return {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON") and k != "ROS_PACKAGE_PATH"}


def outcomes(argv: list[str], env: dict[str, str], cwd: Path) -> list[str]:
    """The runner's lines ("NAME ok" / "NAME FAIL Type") for one suite."""
    done = subprocess.run(argv, env=env, cwd=cwd, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


@pytest.mark.parametrize("suite", OFFLINE_SUITES, ids=lambda path: f"{path.parent.name}/{path.stem}")
def test_a_suite_gives_what_it_gives_under_debian(suite: Path, ros_env: dict[str, str]) -> None:
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import rosgraph, rospkg"], capture_output=True).returncode == 0,
              "rosgraph, rospkg (Debian python3-rosgraph, python3-rospkg)")
    env = script_env(ros_env)
    debian = outcomes([SYSTEM_PYTHON, str(RUNNER), str(suite)], env, suite.parent)
    ours = outcomes(rostui_cmd("python", "--rostui", str(RUNNER), str(suite)), env, suite.parent)
    assert ours and all(line.split(" ")[1] in ("ok", "FAIL") for line in ours), ours
    failed = {line.split(" ")[0] for line in ours if " FAIL " in line}
    assert failed <= FAIL_UNDER_BOTH, ours
    assert ours == debian


def test_ros_comms_online_master_test_passes_as_written(any_master: str, ros_env: dict[str, str]) -> None:
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import rosgraph, rostest"], capture_output=True).returncode == 0,
              "rosgraph, rostest (Debian python3-rosgraph, python3-rostest)")
    suite = REAL / "rosgraph_tests" / "test_rosgraph_masterapi_online.py"
    env = script_env(ros_env)
    reports = []
    for argv in ([SYSTEM_PYTHON, str(suite)], rostui_cmd("python", "--rostui", str(suite))):
        done = subprocess.run(argv, env=env, capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stdout + done.stderr
        reports.append([line for line in done.stdout.splitlines() if " * " in line or line.startswith("[ROSUNIT]")])
    debian, ours = reports
    assert " * TESTS: 19" in ours and any("RESULT: SUCCESS" in line for line in ours), ours
    assert ours == debian
