"""The app processes of `rostui serve`: each started in a process group of its own, and ended for sure.

An app is started without a shell, as the leader of a new process group (and session), so that the
server can signal it and whatever it started in one call, and a Ctrl-C typed in serve's terminal reaches
only serve.  On Linux it also gets SIGHUP if serve dies without ending it (killed outright): the
browser was its terminal, and a rostui app ends when its terminal hangs up.

Ending an app (:func:`end_app`) asks first (the caller has sent textual-serve's ``quit``), then after a
grace sends SIGTERM to its group, then SIGKILL to its group and to every process it started, wherever
they went (a launch's nodes lead groups of their own).
"""

from __future__ import annotations

import asyncio
import os
import signal
import sys
from typing import Callable, Mapping, Optional, Sequence

import psutil

from rostui.core.libc import libc_function

#: Seconds an app has after SIGTERM before SIGKILL.
TERM_GRACE = 1.5

#: ``prctl(PR_SET_PDEATHSIG, ...)``: the signal a process gets when its parent dies.
_PR_SET_PDEATHSIG = 1


def _parent_death_hangup() -> Optional[Callable[[], None]]:
    """A function for the child, between fork and exec: SIGHUP when the server dies (Linux); None elsewhere."""
    prctl = libc_function("prctl")
    if prctl is None:
        return None
    server = os.getpid()

    def hang_up_with_server() -> None:
        prctl(_PR_SET_PDEATHSIG, int(signal.SIGHUP))
        if os.getppid() != server:  # the server died before prctl took effect
            os.kill(os.getpid(), signal.SIGHUP)

    return hang_up_with_server


async def start_app(argv: Sequence[str], env: Mapping[str, str]) -> asyncio.subprocess.Process:
    """``argv`` with pipes for stdin, stdout and stderr, leading a new process group."""
    return await asyncio.create_subprocess_exec(
        *argv, stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
        env=dict(env), start_new_session=True, preexec_fn=_parent_death_hangup())


def _descendants(pid: int) -> list[psutil.Process]:
    """Every process ``pid`` started (and they started), as far as they can still be found."""
    try:
        return psutil.Process(pid).children(recursive=True)
    except psutil.Error:
        return []


def _signal_group(pgid: int, signum: signal.Signals) -> None:
    try:
        os.killpg(pgid, signum)
    except (ProcessLookupError, PermissionError):
        pass


def _signal_each(processes: list[psutil.Process], signum: signal.Signals) -> None:
    for process in processes:
        try:
            process.send_signal(signum)
        except psutil.Error:
            pass


async def _exited(process: asyncio.subprocess.Process, timeout: float) -> bool:
    """True once ``process`` has exited, False if it is still there after ``timeout`` seconds."""
    try:
        await asyncio.wait_for(asyncio.shield(process.wait()), timeout)
    except asyncio.TimeoutError:
        return False
    return True


async def end_app(process: asyncio.subprocess.Process, quit_grace: float, term_grace: float = TERM_GRACE) -> None:
    """Wait ``quit_grace`` seconds for an app that was asked to quit; then SIGTERM its group, and after
    ``term_grace`` SIGKILL its group and everything it started.  Returns once the app has exited."""
    pid = process.pid
    started = _descendants(pid)  # before the app goes: its children are then reparented out of reach
    if await _exited(process, quit_grace):
        _signal_group(pid, signal.SIGKILL)  # anything left in its group that outlived it
        return
    started += _descendants(pid)
    _signal_group(pid, signal.SIGTERM)
    if await _exited(process, term_grace):
        _signal_group(pid, signal.SIGKILL)
        return
    started += _descendants(pid)
    _signal_group(pid, signal.SIGKILL)
    _signal_each(started, signal.SIGKILL)
    await process.wait()
