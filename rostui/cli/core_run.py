"""`rostui core`: the master, the parameter server and rosout in one process."""

from __future__ import annotations

import asyncio
import errno
import os
import signal
import sys
from urllib.parse import urlparse

from rostui.core.log import DISK_CHECK_NOTICE, DISK_OK_NOTICE, disk_usage_warning, log_root
from rostui.core.master import DEFAULT_ROSDISTRO, DEFAULT_ROSVERSION, Master
from rostui.core.msg import MessageError
from rostui.core.network import resolve_addressing
from rostui.core.node.engine import new_event_loop
from rostui.core.rosout import RosoutNode


def check_log_disk_usage() -> None:
    """Warn, as roscore does, when the log directory holds more than 1 GB."""
    print(DISK_CHECK_NOTICE, flush=True)
    warning = disk_usage_warning(log_root(), tool="rostui clean")
    if warning:
        print(warning, file=sys.stderr, flush=True)
    else:
        print(DISK_OK_NOTICE, flush=True)


def master_port_mismatch(port: int, master_uri: str | None) -> str | None:
    """roscore's warning when ROS_MASTER_URI names another port than the one this core listens on."""
    if not master_uri:
        return None
    try:
        uri_port = urlparse(master_uri).port
    except ValueError:
        return None
    if uri_port is None or uri_port == port:
        return None
    return f"WARNING: ROS_MASTER_URI port [{uri_port}] does not match this roscore [{port}]"


async def serve_core(port: int, stop: asyncio.Event) -> int:
    """Run master and rosout until ``stop`` is set; return the exit status."""
    addressing = resolve_addressing(None)
    master = Master(addressing.bind_host, port, advertise_host=addressing.advertise_host)
    try:
        await master.start()
    except OSError as exc:
        if exc.errno == errno.EADDRINUSE:
            print(f"ERROR: rostui core cannot run: another master is already running on port {port}.",
                  file=sys.stderr)
        else:
            print(f"ERROR: rostui core cannot listen on port {port}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    print("SUMMARY\n========\n\nPARAMETERS")
    print(f" * /rosdistro: {DEFAULT_ROSDISTRO.strip()}")
    print(f" * /rosversion: {DEFAULT_ROSVERSION.strip()}\n")
    print(f"started master on port {port}")
    print(f"ROS_MASTER_URI={master.uri}\n")
    print(f"setting /run_id to {master.run_id}")
    try:
        rosout = RosoutNode(master.uri, master.run_id)
        await rosout.start()
    except (MessageError, OSError) as exc:  # e.g. no rosgraph_msgs/Log definition on ROS_PACKAGE_PATH
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        print(f"ERROR: rostui core cannot start /rosout: {reason}", file=sys.stderr, flush=True)
        await master.stop()
        return 1
    print("started core service [/rosout]", flush=True)
    stopped = asyncio.ensure_future(stop.wait())
    shutdown = asyncio.ensure_future(master.wait_for_shutdown_request())
    await asyncio.wait({stopped, shutdown}, return_when=asyncio.FIRST_COMPLETED)
    if shutdown.done():
        print(f"shutdown request: {shutdown.result()}", flush=True)
    for waiter in (stopped, shutdown):
        waiter.cancel()
    await rosout.stop()
    await master.stop()
    return 0


def run_core(port: int) -> int:
    """Blocking entry point; Ctrl-C or SIGTERM stops everything cleanly."""
    mismatch = master_port_mismatch(port, os.environ.get("ROS_MASTER_URI"))
    if mismatch:
        print(mismatch, file=sys.stderr, flush=True)
    check_log_disk_usage()
    loop = new_event_loop()
    asyncio.set_event_loop(loop)
    stop = asyncio.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    try:
        return loop.run_until_complete(serve_core(port, stop))
    finally:
        loop.close()
