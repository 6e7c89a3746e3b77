"""`rostui reconfigure`: from a key press to the real server's callback, and the app with many servers.

    .venv/bin/python bench/bench_reconfigure.py                 # about 1.5 minutes
    .venv/bin/python bench/bench_reconfigure.py --load          # the same with a busy loop on every core

Under `rostui core`:

1. Key to server. Debian's dynamic_reconfigure runs its own test server (rospy, Test.cfg). The app runs
   headless (Textual's pilot) with the cursor on ``double_``; each → press sends one change. The server logs
   each callback with rospy's wall-clock stamp; the latency is that stamp minus the time of the press.
   For reference, the same change made by Debian's ``dynparam set`` and by ``rostui dynparam set`` (whole
   commands: start-up, connection, call), from the command's start to the callback.
2. Many servers. 200 reconfigure servers (one rostui python process, Test.cfg each) and 1000 topics (another
   process) on the master. Measured: from the app's start to all 200 servers listed; a ↓ press in the server
   list until the next server's parameters are shown; and the key-to-server latency against one of the 200.
"""

from __future__ import annotations

import argparse
import asyncio
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import REPO, free_port, ros_env, wait_port

TESTSERVER = REPO / "tests" / "python_compat" / "real" / "dynamic_reconfigure" / "test" / "testserver.py"
DYNPARAM = "/usr/lib/dynamic_reconfigure/dynparam"
NODE = "/dynamic_reconfigure_test_server"
STAMP = re.compile(r"\[INFO\] \[(\d+\.\d+)\]: Reconfigure request")
PRESSES = 30

MANY_SERVERS = """
import sys, time, rospy
from dynamic_reconfigure.server import Server
from dynamic_reconfigure.cfg import TestConfig
def callback(config, level, watched):
    if watched:  # the stamp the benchmark reads, as Debian's test server logs it
        print("[INFO] [%.6f]: Reconfigure request" % time.time(), flush=True)
    return config
rospy.init_node("many_servers")
keep = [Server(TestConfig, lambda config, level, i=i: callback(config, level, i == 150), namespace="/bench/s%03d" % i)
        for i in range(int(sys.argv[1]))]
rospy.spin()
"""

MANY_TOPICS = """
import sys
from rostui import client as ros
from std_msgs.msg import Int32
ros.init_node("many_topics")
keep = [ros.Publisher("/bench/topic_%04d" % i, Int32, queue_size=1) for i in range(int(sys.argv[1]))]
ros.spin()
"""


class ServerLog:
    """The test server's output, read on a thread: each callback's wall-clock stamp."""

    def __init__(self, proc: subprocess.Popen[str]) -> None:
        import threading

        self.proc = proc
        self.stamps: list[float] = []
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            found = STAMP.search(line)
            if found:
                self.stamps.append(float(found.group(1)))

    def wait_count(self, count: int, timeout: float = 20.0) -> float:
        """The stamp of the *count*-th callback, once it came."""
        deadline = time.monotonic() + timeout
        while len(self.stamps) < count:
            if time.monotonic() > deadline:
                raise SystemExit(f"the server logged {len(self.stamps)} callbacks, not {count}")
            time.sleep(0.002)
        return self.stamps[count - 1]


def wait_services(env: dict[str, str], prefix: str, count: int, timeout: float = 120.0) -> None:
    """Until *count* ``.../set_parameters`` services under *prefix* are on the master."""
    from rostui.core.xmlrpc import call_sync

    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        services = call_sync(env["ROS_MASTER_URI"], "getSystemState", "/bench")[2][2]
        if sum(1 for name, _ in services if name.startswith(prefix) and name.endswith("/set_parameters")) >= count:
            return
        time.sleep(0.2)
    raise SystemExit(f"fewer than {count} reconfigure servers under {prefix} within {timeout:g} s")


def percentiles(values: list[float]) -> str:
    """p50, p95 and max in milliseconds."""
    ordered = sorted(values)
    p95 = ordered[min(len(ordered) - 1, int(round(0.95 * (len(ordered) - 1))))]
    return f"p50 {statistics.median(ordered) * 1000:.1f} ms  p95 {p95 * 1000:.1f} ms  max {ordered[-1] * 1000:.1f} ms"


async def key_to_server(env: dict[str, str], log: ServerLog | None, node: str, parameter: str) -> list[float]:
    """Press → and ← in turn on *parameter* of *node* :data:`PRESSES` times (each after the last answer); each
    press's time to the server's callback (from *log*), or without a log to the app's answer."""
    import os

    from textual import events
    from textual.pilot import Pilot

    from rostui.apps.reconfigure.app import ReconfigureApp
    from rostui.apps.reconfigure.panels import ParamTable
    from rostui.models.reconfigure import ParamRow

    os.environ.update(env)
    app = ReconfigureApp(master_uri=env["ROS_MASTER_URI"], node=node, server_period=float(os.environ.get("BENCH_PERIOD", "1.0")))
    latencies: list[float] = []

    async def until(predicate, what: str, timeout: float = 30.0) -> None:  # type: ignore[no-untyped-def]
        deadline = time.monotonic() + timeout
        while not predicate():
            if time.monotonic() > deadline:
                raise SystemExit(f"timed out waiting for {what}")
            await asyncio.sleep(0.005)

    async with app.run_test(size=(100, 40)) as pilot:
        assert isinstance(pilot, Pilot)
        table = app.query_one(ParamTable)
        await until(lambda: any(isinstance(r, ParamRow) and r.name == parameter and r.value is not None
                                for r in table.rows_shown), "the parameters")
        table.focus()
        target = [r.key for r in table.rows_shown].index("param:" + parameter)
        while table.cursor_row != target:
            await pilot.press("down")
        for index in range(PRESSES):
            before = len(log.stamps) if log is not None else 0
            answered = app.last_change
            pressed = time.time()
            # the key as the terminal driver delivers it (the pilot's press also waits for the process to idle)
            app.post_message(events.Key("right" if index % 2 == 0 else "left", None))
            await until(lambda: app.last_change is not answered, "the answer")
            latencies.append((log.wait_count(before + 1) if log is not None else time.time()) - pressed)
    return latencies


def command_latency(argv: list[str], env: dict[str, str], log: ServerLog, runs: int = 5) -> list[float]:
    """From a command's start to the server's callback, *runs* times."""
    found = []
    for index in range(runs):
        before = len(log.stamps)
        started = time.time()
        subprocess.run([*argv, str(index + 1)], env=env, capture_output=True, timeout=60, check=True)
        found.append(log.wait_count(before + 1) - started)
    return found


async def many_servers(env: dict[str, str]) -> None:
    """The app with 200 servers and 1000 topics on the master."""
    from textual import events

    from rostui.apps.reconfigure.app import ReconfigureApp
    from rostui.apps.reconfigure.panels import ParamTable
    from rostui.apps.widgets.name_list import NameList

    started = time.monotonic()
    app = ReconfigureApp(master_uri=env["ROS_MASTER_URI"], server_period=1.0)
    async with app.run_test(size=(100, 40)) as pilot:
        while len(app.query_one(NameList).names) < 200:
            await asyncio.sleep(0.01)
            if time.monotonic() - started > 60:
                raise SystemExit("the app did not list 200 servers within 60 s")
        listed = time.monotonic() - started
        while not app.query_one(ParamTable).rows_shown:
            await asyncio.sleep(0.01)
        servers = app.query_one(NameList)
        servers.focus()
        moves = []
        for _ in range(10):
            selected = app.source.selected
            t0 = time.monotonic()
            app.post_message(events.Key("down", None))
            while app.source.selected == selected or not app.query_one(ParamTable).rows_shown or \
                    app.query_one(ParamTable).rows_shown[0].key != "param:int_enum_":
                await asyncio.sleep(0.002)
            moves.append(time.monotonic() - t0)
        print(f"  200 servers listed {listed:.2f} s after the app started")
        print(f"  ↓ to the next server until its parameters show: {percentiles(moves)}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--load", action="store_true", help="a busy loop on every core while measuring")
    args = parser.parse_args()
    import os

    busy = [subprocess.Popen(["sh", "-c", "while :; do :; done"]) for _ in os.sched_getaffinity(0)] \
        if args.load else []
    port = free_port()
    with tempfile.TemporaryDirectory() as home:
        env = ros_env(port, home)
        env = {k: v for k, v in env.items() if not k.startswith("ROSTUI_PYTHON")}
        procs: list[subprocess.Popen[str]] = []
        try:
            procs.append(subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=env,
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True))
            wait_port(port)
            server = subprocess.Popen(["/usr/bin/python3", str(TESTSERVER), f"__name:={NODE[1:]}"], env=env,
                                      stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            procs.append(server)
            wait_services(env, NODE, 1)
            log = ServerLog(server)
            print(f"key to server ({'loaded' if args.load else 'quiet'} machine), Debian's rospy test server:")
            keyed = asyncio.run(key_to_server(env, log, NODE, "double_"))
            print(f"  rostui reconfigure, a key press to the callback: {percentiles(keyed)}")
            debian = command_latency(["/usr/bin/python3", DYNPARAM, "set", NODE, "int_"], env, log)
            ours = command_latency([sys.executable, "-m", "rostui", "dynparam", "set", NODE, "int_"], env, log)
            print(f"  Debian's dynparam set, start to callback: {percentiles(debian)}")
            print(f"  rostui dynparam set, start to callback:   {percentiles(ours)} "
                  f"({statistics.median(ours) / statistics.median(debian):.2f}x Debian's)")
            for code, count in ((MANY_SERVERS, 200), (MANY_TOPICS, 1000)):
                script = Path(home) / f"many_{count}.py"
                script.write_text(code)
                procs.append(subprocess.Popen([sys.executable, "-m", "rostui", "python", "--rostui", str(script),
                                               str(count)], env=env, stdout=subprocess.PIPE,
                                              stderr=subprocess.DEVNULL, text=True))
            many_log = ServerLog(procs[-2])
            wait_services(env, "/bench/s", 200)
            print("many servers: 200 reconfigure servers and 1000 topics on the master")
            asyncio.run(many_servers(env))
            far = asyncio.run(key_to_server(env, many_log, "/bench/s150", "double_"))
            print(f"  a key press to /bench/s150's callback: {percentiles(far)}")
        finally:
            for proc in [*reversed(procs), *busy]:
                proc.terminate()
            for proc in [*procs, *busy]:
                try:
                    proc.wait(10)
                except subprocess.TimeoutExpired:
                    proc.kill()


if __name__ == "__main__":
    main()
