"""`rostui python SCRIPT ARGS...` without Typer: the form test suites and launch files start by the hundred.

Loading Typer and the full CLI costs more CPU than the script's own start (0.18 s of the 0.28 s a
``rostui python`` took before its script ran). The plain form runs here: optionally ``--rostui`` or
``--real-ros``, then a script path (or Python's own ``-c CODE`` / ``-m MODULE``, as the full CLI takes
them), then the script's arguments untouched. A script file runs in this very interpreter
(:mod:`rostui.compat.inplace`); ``-c`` and ``-m`` replace it with a new one. Anything else (``--which``,
``--help``, both modes asked for, no script) goes to the full CLI, which says what it said before.
"""

from __future__ import annotations

import os
import sys

TYPE_CHECKING = False
if TYPE_CHECKING:
    from collections.abc import Sequence

    from rostui.compat.launcher import Plan

__all__ = ["exec_plan", "run_plain"]

MODE_FLAGS = {"--rostui": "rostui", "--real-ros": "real"}


def exec_plan(how: Plan, who: str) -> int:
    """Print *how*'s notice, then replace this process with its command; on failure, say so and return 126."""
    from rostui.tools.run import exec_argv

    if how.notice:
        print(how.notice, file=sys.stderr)
    try:
        exec_argv(how.argv, how.env)
    except OSError as exc:
        print(f"{who}: cannot run {how.argv[0]}: {exc.strerror or exc}", file=sys.stderr)
    return 126


def run_plain(args: Sequence[str]) -> int | None:
    """Run ``rostui python ARGS`` when ARGS are the plain form (see the module's docstring); else None."""
    modes = []
    at = 0
    while at < len(args) and args[at] in MODE_FLAGS:
        modes.append(MODE_FLAGS[args[at]])
        at += 1
    if at >= len(args) or (args[at].startswith("-") and args[at] not in ("-c", "-m")) or len(set(modes)) > 1:
        return None
    from rostui.compat.deferred import pause_gc, resume_gc

    collecting = pause_gc()  # until the script's first line: rostui's start makes no garbage
    from rostui.compat.choice import Mode
    from rostui.compat.launcher import plan

    mode = Mode(modes[0] if modes else "auto")
    how = plan(mode, args[at], list(args[at + 1:]), os.environ)
    from rostui.compat.inplace import can_run_here, run_here

    if can_run_here(how):  # a script file: run in this interpreter rather than start a second one
        return run_here(how, collecting=collecting)
    resume_gc(collecting)
    return exec_plan(how, "rostui python")
