"""actionlib_tutorials' Fibonacci server and client, unmodified, under rostui's actionlib and Debian's, mixed.

The tutorial's SimpleActionServer (node ``fibonacci``, feedback once a second) and SimpleActionClient
(``wait_for_server``, a goal of order 20, ``wait_for_result``) run as real processes: both under `rostui
python`, rostui's client against Debian's server, and Debian's client against rostui's server, so
rostui's actionlib speaks the protocol to the real one both ways. The client prints the sequence; the
server logs its start and success. Sources: tests/python_compat/real/SOURCES.md. Debian ships no
actionlib_tutorials, so Debian's side gets its messages made by Debian's genaction and genpy.
"""

from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_peer, shared_build
from rospy_scripts import Running, script_command
from test_rospy_tutorials import masked

TUTORIALS = REPO / "tests" / "python_compat" / "real" / "common_tutorials"
PACKAGE = TUTORIALS / "actionlib_tutorials"
SHARE = REPO / "rostui" / "share"
GENACTION = Path("/usr/lib/actionlib_msgs/genaction.py")
GENMSG = Path("/usr/lib/genpy/genmsg_py.py")
FIBONACCI_20 = "Result: 0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233, 377, 610, 987, 1597, 2584, 4181, 6765"
#: What Debian's SimpleActionClient logs when it meets actionlib#206 (see UPSTREAM_RACE_TIMEOUT below): a status that
#: came before its send_goal stored the goal handle is dropped, and the client goes on with the next one.
UNTRACKED_GOAL_LOG = re.compile(r"\[ERROR\] \[\d+\.\d+\]: "
                                r"Got a transition callback on a goal handle that we're not tracking")


def _generate(out: Path) -> None:
    """actionlib_tutorials' action messages for Debian's rospy: genaction's .msg files, then genpy's modules."""
    msg_dir, py_dir = out / "msg", out / "python" / "actionlib_tutorials" / "msg"
    subprocess.run([SYSTEM_PYTHON, str(GENACTION), "-o", str(msg_dir), str(PACKAGE / "action" / "Fibonacci.action")],
                   check=True, capture_output=True)
    includes = [f"-Iactionlib_tutorials:{msg_dir}", f"-Iactionlib_msgs:{SHARE / 'actionlib_msgs' / 'msg'}",
                f"-Istd_msgs:{SHARE / 'std_msgs' / 'msg'}"]
    base = [SYSTEM_PYTHON, str(GENMSG), "-p", "actionlib_tutorials", "-o", str(py_dir), *includes]
    subprocess.run([*base, *sorted(str(p) for p in msg_dir.iterdir())], check=True, capture_output=True)
    subprocess.run([SYSTEM_PYTHON, str(GENMSG), "--initpy", "-p", "actionlib_tutorials", "-o", str(py_dir)],
                   check=True, capture_output=True)
    (py_dir.parent / "__init__.py").write_text("")


@pytest.fixture(scope="session")
def tutorials_python(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Debian's Python modules of actionlib_tutorials, made once for the run."""
    need_peer(GENACTION.exists() and GENMSG.exists(), "genaction, genpy (Debian libactionlib-msgs-dev, python3-genpy)")
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import actionlib"], capture_output=True).returncode == 0,
              "actionlib (Debian python3-actionlib)")
    return shared_build(tmp_path_factory, "actionlib_tutorials_genpy", _generate) / "python"


@pytest.mark.parametrize("client,server,master", [("shim", "shim", "rostui"), ("shim", "real", "rostui"),
                                                  ("real", "shim", "rostui"), ("shim", "real", "roscore"),
                                                  ("real", "shim", "roscore")])
def test_fibonacci_client_gets_the_sequence(client: str, server: str, master: str, request: pytest.FixtureRequest,
                                            ros_env: dict[str, str], tutorials_python: Path, tmp_path: Path) -> None:
    """Each side against the other on rostui core and on a real roscore (and rostui's on both sides). Debian's
    client may log actionlib#206's complaint beside the result (rostui's server answers fast enough to meet it);
    that line, and only that one, is not held against the pairing."""
    request.getfixturevalue("rostui_core" if master == "rostui" else "real_roscore")
    base = {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}
    envs = {"shim": dict(base, ROS_PACKAGE_PATH=str(TUTORIALS)),
            "real": dict(base, PYTHONPATH=os.pathsep.join(filter(None, [str(tutorials_python),
                                                                         base.get("PYTHONPATH")])))}
    scripts = PACKAGE / "scripts"
    serving = Running(script_command(server, scripts / "fibonacci_server.py"), envs[server], tmp_path / "server.log")
    asking = Running(script_command(client, scripts / "fibonacci_client.py"), envs[client], tmp_path / "client.log")
    try:
        asking.wait_for(FIBONACCI_20)
        assert asking.proc.wait(timeout=60) == 0, asking.output()
        serving.wait_for("fibonacci: Succeeded")
    finally:
        server_said = serving.interrupt()
        asking.interrupt()
    client_said = [line for line in asking.output().strip().splitlines()
                   if not (client == "real" and UNTRACKED_GOAL_LOG.fullmatch(line))]
    assert client_said == [FIBONACCI_20], asking.output()
    assert masked(server_said)[:2] == [
        "[INFO] /fibonacci: Executing, creating fibonacci sequence of order N with seeds N, N",
        "[INFO] /fibonacci: Succeeded",
    ], server_said


EXERCISE = REPO / "tests" / "python_compat" / "real" / "actionlib" / "test"
PAIRINGS = pytest.mark.parametrize("client,server", [("shim", "shim"), ("shim", "real"), ("real", "shim")])


def run_unittest_against(server: str, server_script: str, client: str, client_script: str, ros_env: dict[str, str],
                         tmp_path: Path, ready: str | None = None) -> tuple[list[str], str, str]:
    """Start ``server_script`` on one side, run the rostest-style ``client_script`` on the other; the client's
    ``[Testcase: ...]`` lines, all it printed and all the server printed."""
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import actionlib, rostest"], capture_output=True).returncode
              == 0, "actionlib with rostest (Debian python3-actionlib, python3-rostest)")
    env = {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}
    serving = Running(script_command(server, EXERCISE / server_script), env, tmp_path / "server.log")
    try:
        if ready is not None:
            serving.wait_for(ready)
        out = subprocess.run(script_command(client, EXERCISE / client_script), env=env, capture_output=True,
                             text=True, timeout=240)
    finally:
        server_said = serving.interrupt()
    said = out.stdout + out.stderr
    assert out.returncode == 0, said + server_said
    return [line for line in said.splitlines() if line.startswith("[Testcase: ")], said, server_said


#: Debian's SimpleActionClient (actionlib 1.14, the noetic release) drops an answer that comes before its
#: send_goal has stored the goal handle ("Got a transition callback on a goal handle that we're not tracking",
#: https://github.com/ros/actionlib/issues/206, never fixed upstream) and then waits out the exercise's 60 s
#: wait_for_result before it reads the result it already holds: the case still passes, 60 s late. rostui's
#: server answers within a millisecond, so on a loaded machine about one run in seven of the real-client
#: pairing meets it once (measured: 5 of 35 runs). Two such cases in one run must not end the test.
UPSTREAM_RACE_TIMEOUT = 300


@pytest.mark.timeout(UPSTREAM_RACE_TIMEOUT)
@PAIRINGS
def test_simple_client_exercise_passes(client: str, server: str, rostui_core: object, ros_env: dict[str, str],
                                       tmp_path: Path) -> None:
    """actionlib's own exercise of SimpleActionClient against its mock SimpleActionServer: success, abort,
    preempt, a dropped goal, an execute callback that raises, an ignored cancel and a goal the server loses
    (it deletes the goal from its status list), all seven passing in every pairing."""
    cases, said, server_said = run_unittest_against(server, "mock_simple_server.py", client,
                                                    "exercise_simple_client.py", ros_env, tmp_path, ready="Spinning")
    assert cases == [f"[Testcase: test_{name}] ... ok" for name in (
        "drop", "exception", "ignore_cancel_and_succeed", "just_abort", "just_preempt", "just_succeed", "lose")], said
    assert "\033[32m * RESULT: SUCCESS\033[0m" in said
    assert "Your executeCallback did not set the goal to a terminal status." in server_said
    assert "Exception in your execute callback: Terminating by throwing an exception" in server_said


@PAIRINGS
def test_raw_action_client_against_the_reference_server(client: str, server: str, rostui_core: object,
                                                       ros_env: dict[str, str], tmp_path: Path) -> None:
    """actionlib's test of the raw ActionClient (goal handles, feedback callbacks, results) against its
    reference ActionServer subclass (accept, succeed, abort, reject, feedback by hand), in every pairing."""
    cases, said, _ = run_unittest_against(server, "ref_server.py", client, "test_ref_action_server.py", ros_env,
                                          tmp_path)
    assert cases == [f"[Testcase: {name}] ... ok" for name in ("test_abort", "test_feedback", "test_result",
                                                             "testsimple")], said
