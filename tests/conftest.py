"""Shared fixtures: free ports, private ROS_HOME, rostui and real ROS masters.

Every test process gets its own ROS_HOME and a master on a free port; port 11311
and the user's ~/.ros are never touched.  Interop peers (real roscore, rospy,
roscpp) are required when ROSTUI_REQUIRE_INTEROP=1: a missing peer fails the
test instead of skipping it.
"""

from __future__ import annotations

import asyncio
import collections
import functools
import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import time
import uuid
from contextlib import contextmanager
from pathlib import Path
from typing import Callable, Iterator

import pytest

SYSTEM_PYTHON = "/usr/bin/python3"

# A run started in the background of a shell without job control inherits SIGINT ignored, and would hand that
# on to every process the tests start; the tests press Ctrl-C (SIGINT) as a user's terminal does.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

# Every script a test runs under `rostui python` keeps its compiled message code (rostui/core/msg/codecache.py) in
# a folder of this run's own, whatever its environment's ROS_HOME (tests that copy os.environ have none): never in
# the user's ~/.ros. The workers inherit the folder of the run that made it; that run removes it at its end.
if "ROSTUI_MSG_CACHE" not in os.environ:
    import atexit
    import tempfile

    os.environ["ROSTUI_MSG_CACHE"] = tempfile.mkdtemp(prefix="rostui-msg-code-")
    atexit.register(shutil.rmtree, os.environ["ROSTUI_MSG_CACHE"], ignore_errors=True)

#: Real scripts kept as test data (run by the tests as programs, never imported by pytest:
#: ros_comm's and others' names such as ``timer_test.py`` look like test modules).
collect_ignore_glob = ["python_compat/*"]
REPO = Path(__file__).resolve().parent.parent


#: Test ports come from a block of their own for each pytest-xdist worker, below the kernel's ephemeral
#: range (32768 and up on Linux): the ports that bind(0) and outgoing connections take, in this worker and
#: in every other, never land on a port a test has picked but not yet listened on.  Within its block a worker
#: picks at random, so two test runs on one machine rarely meet either.
PORT_BLOCK = 1400
PORT_BASE = 20000
#: Ports this worker handed out lately: a test may not have bound its port yet when it asks for another.
_recent_ports: collections.deque[int] = collections.deque(maxlen=PORT_BLOCK // 4)
#: A generator of its own: tests that seed the ``random`` module do not make two runs pick alike.
_port_choice = random.Random()


def _worker_index() -> int:
    """This pytest-xdist worker's number (gw0 is 0); 0 when the suite runs in one process."""
    worker = os.environ.get("PYTEST_XDIST_WORKER", "gw0")
    return int(worker[2:]) if worker[2:].isdigit() else 0


def free_port() -> int:
    """Return a TCP port on 127.0.0.1 that nothing listens on right now, from this worker's own block."""
    first = PORT_BASE + (_worker_index() % 8) * PORT_BLOCK
    for _ in range(4 * PORT_BLOCK):
        port = first + _port_choice.randrange(PORT_BLOCK)
        if port in _recent_ports:
            continue
        with socket.socket() as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
        _recent_ports.append(port)
        return port
    raise RuntimeError(f"no free port in {first}..{first + PORT_BLOCK - 1}")


def interop_required() -> bool:
    """True when CI demands that real ROS 1 peers are present."""
    return os.environ.get("ROSTUI_REQUIRE_INTEROP") == "1"


def need_peer(ok: bool, what: str) -> None:
    """Skip (locally) or fail (in CI) when a real ROS 1 peer is missing."""
    if ok:
        return
    if interop_required():
        pytest.fail(f"ROSTUI_REQUIRE_INTEROP=1 but {what} is not installed")
    pytest.skip(f"{what} not installed")


def need_command(name: str) -> None:
    """``need_peer`` for a program on PATH; tests/debian_peers.py names the package that gives it."""
    from debian_peers import describe

    need_peer(shutil.which(name) is not None, describe(name))


def have_rospy() -> bool:
    """True when Debian's rospy imports under the system Python."""
    if not Path(SYSTEM_PYTHON).exists():
        return False
    r = subprocess.run([SYSTEM_PYTHON, "-c", "import rospy"], capture_output=True)
    return r.returncode == 0


def _said(what: str | Callable[[], str]) -> str:
    return what() if callable(what) else what


def wait_until(predicate: Callable[[], bool], what: str | Callable[[], str], timeout: float = 30.0) -> None:
    """Poll ``predicate`` until it holds; fail with ``what`` when it never does (generous: CI machines are slow).

    ``what`` may be a function: its text is then made at the time-out, so it can show the state that failed.
    """
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {_said(what)}")
        time.sleep(0.05)


async def until(predicate: Callable[[], bool], what: str | Callable[[], str], timeout: float = 30.0) -> None:
    """``wait_until`` on a running event loop: poll ``predicate`` without blocking the loop."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + timeout
    while not predicate():
        if loop.time() > deadline:
            raise AssertionError(f"timed out waiting for {_said(what)}")
        await asyncio.sleep(0.02)


def wait_for_port(port: int, timeout: float = 15.0, proc: subprocess.Popen | None = None) -> None:
    """Block until something accepts TCP connections on 127.0.0.1:port."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc is not None and proc.poll() is not None:
            out = proc.stdout.read() if proc.stdout else ""
            raise RuntimeError(f"process exited with {proc.returncode} before listening: {out}")
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=0.5):
                return
        except OSError:
            time.sleep(0.05)
    raise TimeoutError(f"nothing listened on port {port} within {timeout}s")


def read_until_closed(sock: socket.socket) -> bytes:
    """Everything the peer sends until it closes (socket.timeout if it does not)."""
    chunks = []
    while True:
        try:
            chunk = sock.recv(65536)
        except ConnectionResetError:
            break
        if not chunk:
            break
        chunks.append(chunk)
    return b"".join(chunks)


def stop_process(proc: subprocess.Popen, timeout: float = 10.0) -> None:
    """SIGINT a process, then SIGKILL it if it does not exit in time."""
    if proc.poll() is not None:
        return
    proc.send_signal(2)
    try:
        proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


def shared_build(tmp_path_factory: pytest.TempPathFactory, name: str, build: Callable[[Path], None]) -> Path:
    """A folder ``build`` fills once per test run, shared read-only by every pytest-xdist worker.

    The first worker to ask builds it under a lock in the run's common temporary folder; the others wait
    for that lock and reuse the result.  A build that fails leaves no folder, so each asker sees the failure.
    """
    import fcntl

    base = tmp_path_factory.getbasetemp()
    if "PYTEST_XDIST_WORKER" in os.environ:
        base = base.parent
    folder = base / f"shared-{name}"
    with open(base / f"shared-{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (folder / ".built").exists():
            shutil.rmtree(folder, ignore_errors=True)
            folder.mkdir()
            try:
                build(folder)
            except BaseException:
                shutil.rmtree(folder, ignore_errors=True)
                raise
            (folder / ".built").touch()
    return folder


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo) -> Iterator[None]:
    """Under ROSTUI_REQUIRE_INTEROP=1 nothing skips: a skipped test is reported as failed, with its reason."""
    outcome = yield
    report = outcome.get_result()
    if report.skipped and interop_required() and not hasattr(report, "wasxfail"):
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
        report.outcome = "failed"
        report.longrepr = f"skipped under ROSTUI_REQUIRE_INTEROP=1 (CI runs every test): {reason}"


@pytest.fixture
def ros_env(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    """An environment with a private ROS_HOME and a master URI on a free port.

    It is also applied to this test process, so in-process rostui nodes see it.
    """
    env = new_ros_env(tmp_path)
    apply_ros_env(monkeypatch, env)
    return env


#: What a test's ROS environment sets, and the ROS variables of the machine it leaves out.
_OWN_VARIABLES = ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP", "PYTHONUNBUFFERED")
_FOREIGN_ROS_VARIABLES = ("ROS_HOSTNAME", "ROS_NAMESPACE", "ROS_LOG_DIR", "ROSCONSOLE_FORMAT")


def new_ros_env(where: Path) -> dict[str, str]:
    """This process's environment with a master URI on a free port and a private ROS_HOME under *where*."""
    port = free_port()
    home = where / "ros_home"
    home.mkdir()
    own = dict(zip(_OWN_VARIABLES, (f"http://127.0.0.1:{port}", str(home), "127.0.0.1", "1")))
    env = {k: v for k, v in os.environ.items() if k not in _FOREIGN_ROS_VARIABLES}
    return {**env, **own, "ROSTUI_TEST_MASTER_PORT": str(port)}


def apply_ros_env(monkeypatch: pytest.MonkeyPatch, env: dict[str, str]) -> None:
    """Make *env*'s ROS variables this test process's own (in-process rostui nodes and completions read them)."""
    for key in _FOREIGN_ROS_VARIABLES:
        monkeypatch.delenv(key, raising=False)
    for key in _OWN_VARIABLES:
        monkeypatch.setenv(key, env[key])


@pytest.fixture(scope="module")
def module_ros_env(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    """A ROS environment for a graph that one module's read-only tests share (its own port and ROS_HOME).

    Starting a core and its peers costs a few CPU seconds; tests that only look at a graph share one
    per worker instead of making their own. Not applied to this process: see :func:`apply_ros_env`.
    """
    return new_ros_env(tmp_path_factory.mktemp("module_ros"))


@pytest.fixture(scope="module", params=["rostui", "roscore"])
def module_master(request: pytest.FixtureRequest, module_ros_env: dict[str, str]) -> Iterator[str]:
    """``any_master`` for a module's shared graph: a `rostui core` or a real core on module_ros_env's port."""
    with running_core(request.param, module_ros_env):
        yield request.param


def core_argv(kind: str, port: int) -> list[str]:
    """The command of a `rostui core` (*kind* "rostui") or a real `roscore` (*kind* "roscore") on *port*."""
    return rostui_cmd("core", "-p", str(port)) if kind == "rostui" else ["roscore", "-p", str(port)]


@contextmanager
def running_core(kind: str, env: dict[str, str]) -> Iterator[subprocess.Popen]:
    """A `rostui core` (*kind* "rostui") or a real ROS core (*kind* "roscore", see :func:`running_real_core`) on
    *env*'s port, rosout up; the master's process."""
    if kind == "roscore":
        with running_real_core(env) as master:
            yield master
        return
    port = master_port(env)
    proc = subprocess.Popen(core_argv(kind, port), env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        wait_for_core(port, proc, timeout=30)
        yield proc
    finally:
        stop_process(proc)


ROSOUT = "/usr/lib/rosout/rosout"


@functools.cache
def roscore_versions() -> tuple[str, str]:
    """``/rosversion`` and ``/rosdistro`` as roscore sets them: what `rosversion roslaunch` and `rosversion -d`
    print, newline included (roscore.xml's ``command=`` parameters)."""
    def rosversion(*args: str) -> str:
        return subprocess.run(["rosversion", *args], capture_output=True, text=True, check=True).stdout

    return rosversion("roslaunch"), rosversion("-d")


@contextmanager
def running_real_core(env: dict[str, str]) -> Iterator[subprocess.Popen]:
    """What `roscore -p PORT` runs, started as roscore's roslaunch starts it: Debian's `rosmaster --core`, the
    parameters of roscore.xml and roslaunch's ``/run_id``, then Debian's rosout logging to
    ``$ROS_HOME/log/<run_id>/`` (``latest`` pointing there); yields the master's process.

    Without roslaunch itself (so without the ``/roslaunch/uris`` entry of its server): its start and its two
    `rosversion` runs cost about 1.2 s of CPU a core, 7% of the suite's CPU over the 170 cores a run
    started.  Tests of the `roscore` command itself run it.
    """
    from rostui.core.xmlrpc import call_sync

    need_command("rosmaster")
    port = master_port(env)
    run_id = str(uuid.uuid1())
    log_dir = Path(env["ROS_HOME"]) / "log" / run_id
    log_dir.mkdir(parents=True)
    latest = log_dir.parent / "latest"
    if latest.is_symlink():
        latest.unlink()
    latest.symlink_to(log_dir)

    def start(*argv: str) -> subprocess.Popen:
        return subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                start_new_session=True)

    master = start("rosmaster", "--core", "-p", str(port), "-w", "3", f"__log:={log_dir}/master.log")
    rosout: subprocess.Popen | None = None
    try:
        wait_for_port(port, timeout=60, proc=master)
        uri = f"http://127.0.0.1:{port}/"
        rosversion, rosdistro = roscore_versions()
        for name, value in (("/run_id", run_id), ("/rosversion", rosversion), ("/rosdistro", rosdistro)):
            call_sync(uri, "setParam", "/roslaunch", name, value)
        rosout = start(ROSOUT, "__name:=rosout", f"__log:={log_dir}/rosout-1.log")
        wait_for_core(port, master, timeout=60)
        yield master
    finally:
        if rosout is not None:
            stop_process(rosout)
        stop_process(master)


def master_port(env: dict[str, str]) -> int:
    """The port of the master URI in a ros_env environment."""
    return int(env["ROSTUI_TEST_MASTER_PORT"])


def rostui_cmd(*args: str) -> list[str]:
    """The argv that runs the installed rostui command line with this Python."""
    return [sys.executable, "-m", "rostui", *args]


def wait_for_core(port: int, proc: subprocess.Popen, timeout: float = 30.0) -> None:
    """Wait until a core (`rostui core` or a real `roscore`) on ``port`` listens and its rosout has registered
    (/rosout_agg published, /rosout subscribed).

    The master answers before its rosout node has registered; a core is only what `roscore` is once both run.
    """
    from rostui.core.xmlrpc import XmlRpcConnectionError, call_sync

    wait_for_port(port, timeout=timeout, proc=proc)

    def rosout_up() -> bool:
        assert proc.poll() is None, f"the core exited with {proc.returncode}"
        try:
            publishers, subscribers, _ = call_sync(f"http://127.0.0.1:{port}/", "getSystemState", "/test")[2]
        except (OSError, XmlRpcConnectionError):
            return False
        return (any(topic == "/rosout_agg" for topic, _nodes in publishers)
                and any(topic == "/rosout" for topic, _nodes in subscribers))

    wait_until(rosout_up, f"rosout of the core on port {port} to register", timeout=timeout)


def start_rostui_core(env: dict[str, str]) -> subprocess.Popen:
    """A `rostui core` on the ros_env port, with rosout registered when this returns (output discarded)."""
    port = master_port(env)
    proc = subprocess.Popen(core_argv("rostui", port), env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_for_core(port, proc)
    return proc


@pytest.fixture
def rostui_core(ros_env: dict[str, str]) -> Iterator[subprocess.Popen]:
    """A `rostui core` master (with rosout) on the ros_env port."""
    with running_core("rostui", ros_env) as proc:
        yield proc


@pytest.fixture
def real_roscore(ros_env: dict[str, str]) -> Iterator[subprocess.Popen]:
    """A real ROS 1 core on the ros_env port (required in CI): :func:`running_real_core`."""
    with running_core("roscore", ros_env) as proc:
        yield proc


@pytest.fixture(params=["rostui", "roscore"])
def any_master(request: pytest.FixtureRequest, ros_env: dict[str, str]) -> str:
    """Run the test once against `rostui core` and once against a real roscore."""
    fixture = "rostui_core" if request.param == "rostui" else "real_roscore"
    request.getfixturevalue(fixture)
    return request.param


@pytest.fixture
def rospy_available() -> None:
    """Require Debian's rospy under /usr/bin/python3."""
    need_peer(have_rospy(), "rospy (Debian python3-rospy)")
