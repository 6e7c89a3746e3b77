"""The collector while a command starts (rostui/core/startup_gc.py): rare collections until the command's node has
started, then what start-up made is frozen and the thresholds are back; a script's own node is left alone.

Thresholds and the frozen generation belong to a process, so each case runs in a Python of its own."""

from __future__ import annotations

import subprocess
import sys

import pytest

PROBE = r"""
import asyncio, gc, sys
from rostui.core.startup_gc import START_THRESHOLD, collect_rarely
default = gc.get_threshold()
if sys.argv[1] == "cli":
    collect_rarely()
    print("starting", gc.get_threshold()[0] == START_THRESHOLD)
from rostui.core.node import AsyncNode

async def main():
    node = AsyncNode("gc_probe", anonymous=True)
    await node.start()
    print("started", gc.get_threshold() == default, gc.get_freeze_count() > 0)
    await node.shutdown("probed")

asyncio.run(main())
"""


def _probe(mode: str, env: dict[str, str]) -> list[str]:
    done = subprocess.run([sys.executable, "-c", PROBE, mode], env=env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


@pytest.mark.usefixtures("rostui_core")
def test_a_command_collects_rarely_until_its_node_has_started(ros_env: dict[str, str]) -> None:
    assert _probe("cli", ros_env) == ["starting True", "started True True"]


@pytest.mark.usefixtures("rostui_core")
def test_a_scripts_node_leaves_the_collector_as_it_was(ros_env: dict[str, str]) -> None:
    assert _probe("script", ros_env) == ["started True False"]


def test_the_cli_raises_the_threshold_before_a_command_loads() -> None:
    """The entry point's full path (not the quick answers before it) starts with rare collections."""
    code = ("import gc, sys; from rostui.cli import fast, tree; "
            "sys.argv = ['rostui', 'msg', 'list']; "
            "seen = []; tree.main = lambda: seen.append(gc.get_threshold()[0]); "
            "fast.main(); print(seen)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    from rostui.core.startup_gc import START_THRESHOLD

    assert done.stdout.strip() == f"[{START_THRESHOLD}]"
