"""`rostui core` as a user runs it: start-up lines, a busy port, Ctrl-C."""

from __future__ import annotations

import re
import subprocess
from typing import Any

from rostui.core.xmlrpc import call_sync

from conftest import free_port, master_port, rostui_cmd, stop_process, wait_for_port, wait_until


def test_core_prints_run_id_and_sets_core_params(rostui_core: subprocess.Popen, ros_env: dict[str, str]) -> None:
    uri = ros_env["ROS_MASTER_URI"]
    run_id = call_sync(uri, "getParam", "/test", "/run_id")[2]
    assert re.fullmatch(r"[0-9a-f-]{36}", run_id)
    assert call_sync(uri, "getParam", "/test", "/rosdistro")[0] == 1
    assert call_sync(uri, "getParam", "/test", "/rosversion")[0] == 1

    def rosout_registered() -> bool:
        pubs, subs, _ = call_sync(uri, "getSystemState", "/test")[2]
        return ["/rosout_agg", ["/rosout"]] in pubs and ["/rosout", ["/rosout"]] in subs

    wait_until(rosout_registered, "rosout to publish /rosout_agg and subscribe /rosout")
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


def test_core_warns_when_ros_master_uri_names_another_port(ros_env: dict[str, str]) -> None:
    """Like roscore: a core on a port other than ROS_MASTER_URI's says so on stderr, and still runs there."""
    port = free_port()
    proc = subprocess.Popen(rostui_cmd("core", "-p", str(port)), env=ros_env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    try:
        wait_for_port(port, proc=proc)
    finally:
        stop_process(proc)
    err = proc.stderr.read() if proc.stderr else ""
    assert (f"WARNING: ROS_MASTER_URI port [{master_port(ros_env)}] does not match this roscore [{port}]"
            in err.splitlines())


def test_core_on_ros_master_uri_port_has_no_port_warning(rostui_core: Any, ros_env: dict[str, str]) -> None:
    stop_process(rostui_core)
    out = rostui_core.stdout.read() if rostui_core.stdout else ""
    assert "does not match this roscore" not in out
