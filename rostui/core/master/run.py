"""Run a standalone master under uvloop until SIGINT/SIGTERM or a ``shutdown`` call."""

from __future__ import annotations

import asyncio
import signal
import sys

from ..network import resolve_addressing
from .master import Master


async def _serve(port: int) -> int:
    addressing = resolve_addressing()
    master = Master(addressing.bind_host, port, advertise_host=addressing.advertise_host)
    try:
        await master.start()
    except OSError as exc:
        print(f"ERROR: cannot start the master on port {port}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    print(f"ROS_MASTER_URI={master.uri}", flush=True)
    print(f"setting /run_id to {master.run_id}", flush=True)
    loop = asyncio.get_running_loop()
    stop: asyncio.Future[str] = loop.create_future()

    def on_signal(sig: signal.Signals) -> None:
        if not stop.done():
            stop.set_result(f"signal {sig}")

    for sig in (signal.SIGINT, signal.SIGTERM):
        try:
            loop.add_signal_handler(sig, on_signal, sig)
        except (NotImplementedError, RuntimeError):  # pragma: no cover - non-Unix
            pass
    shutdown_call = asyncio.ensure_future(master.wait_for_shutdown_request())
    done, _ = await asyncio.wait({stop, shutdown_call}, return_when=asyncio.FIRST_COMPLETED)
    if shutdown_call in done:
        print(f"shutdown request: {shutdown_call.result()}", flush=True)
        await asyncio.sleep(0.05)  # let the shutdown reply reach the caller
    else:
        shutdown_call.cancel()
    await master.stop()
    return 0


def run_master_forever(port: int) -> int:
    """Serve a master on ``port`` (uvloop if available) until Ctrl-C; return the exit code.

    Bind and advertised addresses come from ROS_IP / ROS_HOSTNAME /
    ROS_MASTER_URI (see :func:`rostui.core.network.resolve_addressing`).
    Prints ``ROS_MASTER_URI=...`` and ``setting /run_id to <uuid>``.
    """
    try:
        import uvloop
    except ImportError:  # pragma: no cover - uvloop is a dependency on Unix
        return asyncio.run(_serve(port))
    try:
        return uvloop.run(_serve(port))
    except AttributeError:  # pragma: no cover - old uvloop without run()
        uvloop.install()
        return asyncio.run(_serve(port))
    except KeyboardInterrupt:  # pragma: no cover - signal raced the handler
        return 0
