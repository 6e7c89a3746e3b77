"""The supervisor's side of `rostui launch --tui`, without Textual: captured output, states, one-node control.

The monitor drives the launch only through the supervisor's public methods
(start_node, stop_node, restart_node, request_stop) and reads node states and
output rings; these tests do the same on a plain event loop.
"""

from __future__ import annotations

import asyncio
import os
from pathlib import Path

import pytest

from rostui.launch.errors import LaunchError
from rostui.launch.files import LaunchRequest
from rostui.launch.output import OutputBuffer
from rostui.launch.process import NodeState
from rostui.launch.supervisor import Supervisor, SupervisorOptions, keep_quiet, load_supervisor

from conftest import until
from launch_tui_helpers import on_loop, still_alive, tui_env, write_launch  # noqa: F401  (tui_env is a fixture)


def captured(launch: Path) -> Supervisor:
    """A supervisor for ``launch`` with the monitor's options."""
    options = SupervisorOptions(capture=True, handle_signals=False, stay_when_all_ended=True, sigint_timeout=5)
    return load_supervisor(LaunchRequest([str(launch)]), options, reporter=keep_quiet)


def lines(buffer: OutputBuffer) -> list[str]:
    """The texts of every kept line."""
    return [line.text for line in buffer.since(0)]


def test_output_buffer_keeps_the_newest_lines() -> None:
    """A full ring drops its oldest lines, counts them, and ``since`` skips what was already read."""
    buffer = OutputBuffer(max_lines=3)
    for n in range(5):
        buffer.append("stdout", f"l{n}")
    assert lines(buffer) == ["l2", "l3", "l4"]
    assert buffer.dropped == 2
    assert [line.text for line in buffer.since(4)] == ["l4"]
    assert [line.text for line in buffer.since(0)] == ["l2", "l3", "l4"]


@on_loop
async def test_start_stop_restart_without_textual(tui_env: dict[str, str], tmp_path: Path) -> None:
    """stop_node stops (no respawn), start_node starts, restart_node gives a new pid; output is captured."""
    launch = write_launch(tmp_path / "plain.launch", """
  <node pkg="tuitest" type="chatty" name="talker" args="2"/>
  <node pkg="tuitest" type="quiet" name="keeper" respawn="true"/>""")
    supervisor = captured(launch)
    run = asyncio.get_running_loop().create_task(supervisor.run())
    try:
        await until(lambda: len(supervisor.processes) == 2
                    and all(p.state is NodeState.RUNNING for p in supervisor.processes), "both nodes running")
        talker = supervisor.process_named("/talker")
        await until(lambda: "a warning from chatty" in lines(talker.output), "the talker's captured stderr")
        assert [(line.stream, line.text) for line in talker.output.since(0)][1:] == [
            ("stdout", "line 1 of 2"), ("stdout", "line 2 of 2"), ("stderr", "a warning from chatty")]
        assert talker.plan.stdout_log is not None
        assert talker.plan.stdout_log.read_text() == "line 1 of 2\nline 2 of 2\n"  # stdout is still logged

        keeper = supervisor.process_named("keeper-2")  # by roslaunch's label too
        first = keeper.pid
        await supervisor.stop_node("/keeper")
        assert keeper.state is NodeState.STOPPED and not keeper.running and not still_alive({first or 0})
        await asyncio.sleep(1.5)
        assert keeper.state is NodeState.STOPPED  # respawn does not bring a stopped node back
        assert await supervisor.start_node("/keeper")
        second = keeper.pid
        assert keeper.state is NodeState.RUNNING and second != first
        assert await supervisor.restart_node("/keeper")
        assert keeper.pid not in (first, second) and keeper.restarts == 2
        assert not still_alive({second or 0})
        with pytest.raises(LaunchError, match=r"no node \[/nobody\] in this launch"):
            await supervisor.stop_node("/nobody")
        pids = {p.pid for process in supervisor.processes for p in process.alive_tree()}
    finally:
        supervisor.request_stop()
        assert await run == 0
    assert supervisor.finished.is_set()
    assert all(p.state is NodeState.STOPPED for p in supervisor.processes)
    assert not still_alive(pids)
    with pytest.raises(LaunchError, match="shutting down"):
        await supervisor.start_node("/talker")


def test_usage_counts_the_whole_process_tree(tmp_path: Path) -> None:
    """A node whose shell runs a busy child: the tree holds both, CPU shows the child's work, memory is summed."""
    import subprocess
    import sys
    import time

    from rostui.tools.usage import UsageSampler, children_map, tree_of

    busy = subprocess.Popen(["/bin/sh", "-c", f"{sys.executable} -c 'while True: pass' & wait"])
    try:
        until_child = time.monotonic() + 30
        while len(tree_of(busy.pid, children_map())) < 2:
            assert time.monotonic() < until_child, "the busy child never started"
            time.sleep(0.05)
        tree = tree_of(busy.pid, children_map())
        import psutil

        child = psutil.Process(max(set(tree) - {busy.pid}))

        def cpu_seconds() -> float:
            times = child.cpu_times()
            return times.user + times.system

        sampler = UsageSampler()
        start = (time.monotonic(), cpu_seconds())
        first = sampler.measure(tree)
        assert first is not None and first.cpu_percent == 0.0  # nothing to compare with yet
        # on a loaded machine the child gets what the scheduler gives it: wait for its work, not a fixed time
        while cpu_seconds() - start[1] < 0.3:
            assert time.monotonic() - start[0] < 60, "the busy child got no CPU"
            time.sleep(0.05)
        second = sampler.measure(tree)
        end = (time.monotonic(), cpu_seconds())
        child_share = 100 * (end[1] - start[1]) / (end[0] - start[0])
        assert second is not None and child_share * 0.7 <= second.cpu_percent <= child_share * 1.3 + 5, \
            (second, child_share)
        assert second.rss_bytes >= sum(psutil.Process(pid).memory_info().rss for pid in tree) // 2
        assert sampler.measure([busy.pid]).rss_bytes < second.rss_bytes  # type: ignore[union-attr]
    finally:
        for pid in tree_of(busy.pid, children_map()):
            try:
                os.kill(pid, 9)
            except ProcessLookupError:
                pass
        busy.wait()
    deadline = time.monotonic() + 30
    while sampler.measure(tree) is not None:  # killed: gone, or a zombie until it is reaped
        assert time.monotonic() < deadline, "killed processes still measured"
        time.sleep(0.05)
