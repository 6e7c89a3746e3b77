"""`rostui top`: rqt_top in the terminal: every node's process, its CPU, memory, threads and connections."""

from __future__ import annotations

import typer

from rostui.cli.common import examples

SORT_HELP = "Order: cpu (the busiest first), memory or name."


def top_command(
    once: bool = typer.Option(False, "--once", help="Print the table once and exit (for scripts)."),
    sort: str = typer.Option("cpu", "--sort", "-s", metavar="KEY", help=SORT_HELP),
    interval: float = typer.Option(1.0, "--interval", "-i", metavar="SECONDS",
                                   help="Seconds between two measures (with --once: the CPU is measured over it)."),
) -> None:
    """Show every node on the master with its process (like rqt_top).

    Each node's pid comes from the node itself (its slave API); nodes on this
    host show their CPU, memory, threads and TCP connections, nodes elsewhere
    are listed as remote. In the app, s changes the order and k stops the
    node under the cursor (SIGINT, then SIGTERM, then SIGKILL, after you
    confirm). `--once` prints the table once.
    """
    from rostui.cli.common import fail
    from rostui.models.top import SORTS

    if sort not in SORTS:
        fail(f"unknown sort {sort!r}: choose cpu, memory or name")
    if not interval > 0:
        fail("--interval must be more than 0 seconds")
    if once:
        raise typer.Exit(_print_once(sort, interval))
    from rostui.apps.top.app import run_app

    raise typer.Exit(run_app(sort=sort, interval=interval))


def _print_once(sort: str, interval: float) -> int:
    """Measure twice, ``interval`` apart, and print the table; the exit status."""
    import asyncio

    from rostui.cli.common import fail, master_call, master_uri
    from rostui.core.master_errors import MasterUnreachableError
    from rostui.models.top import TopSource, format_rows, sort_rows

    master_call("/rostui_top", "getPid")

    async def measure() -> str:
        source = await TopSource(master_uri()).start()
        try:
            await source.poll()
            await asyncio.sleep(interval)
            return format_rows(sort_rows(await source.poll(), sort))
        finally:
            await source.close()

    try:
        print(asyncio.run(measure()))
    except MasterUnreachableError as exc:
        fail(str(exc))
    except KeyboardInterrupt:
        return 130
    return 0


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("top", context_settings={"help_option_names": ["-h", "--help"]}, epilog=examples(
        ("every node's CPU and memory, live", "rostui top"),
        ("the biggest first", "rostui top --sort memory"),
        ("print it once, for a script", "rostui top --once"),
    ))(top_command)
