"""`rostui core` as a user runs it: start-up lines, a busy port, Ctrl-C."""

from __future__ import annotations

import re
import subprocess
from typing import Any

from rostui.core.xmlrpc import call_sync

from conftest import master_port, rostui_cmd, stop_process


def test_core_prints_run_id_and_sets_core_params(rostui_core: subprocess.Popen, ros_env: dict[str, str]) -> None:
    uri = ros_env["ROS_MASTER_URI"]
    run_id = call_sync(uri, "getParam", "/test", "/run_id")[2]
    assert re.fullmatch(r"[0-9a-f-]{36}", run_id)
    assert call_sync(uri, "getParam", "/test", "/rosdistro")[0] == 1
    assert call_sync(uri, "getParam", "/test", "/rosversion")[0] == 1
    pubs, subs, _ = call_sync(uri, "getSystemState", "/test")[2]
    assert ["/rosout_agg", ["/rosout"]] in pubs and ["/rosout", ["/rosout"]] in subs
    stop_process(rostui_core)
    out = rostui_core.stdout.read() if rostui_core.stdout else ""
    assert rostui_core.returncode == 0
    assert f"setting /run_id to {run_id}" in out


def test_second_core_on_same_port_is_one_clear_error(rostui_core: Any, ros_env: dict[str, str]) -> None:
    second = subprocess.run(rostui_cmd("core", "-p", str(master_port(ros_env))), env=ros_env,
                            capture_output=True, text=True, timeout=30)
    assert second.returncode == 1
    assert second.stderr.strip().splitlines() == [
        f"ERROR: rostui core cannot run: another master is already running on port {master_port(ros_env)}."]
