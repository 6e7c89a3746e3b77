"""``rostui tf echo``: tf_echo's text for a lookup, and the loop that prints it at a rate."""

from __future__ import annotations

import asyncio
import math
import time
from typing import Callable, TextIO

from rostui.tools.tf.buffer import StampedTransform, TfBuffer, TfError
from rostui.models.tf.source import TfSource

__all__ = ["format_echo", "format_failure", "run_echo"]

FIRST_WAIT = 1.0
"""Seconds to wait for the first transform before the first print (tf_echo's waitForTransform)."""


def format_echo(st: StampedTransform, precision: int = 3) -> str:
    """tf_echo's block for one transform: time, translation, quaternion, RPY in radians and degrees."""
    def nums(values: tuple[float, ...] | list[float]) -> str:
        return ", ".join(f"{float(v):.{precision}f}" for v in values)

    tr = st.transform
    roll, pitch, yaw = tr.rpy()
    degrees = tuple(math.degrees(a) for a in (roll, pitch, yaw))
    return (f"At time {st.stamp:.{precision}f}\n"
            f"- Translation: [{nums(tr.translation.tolist())}]\n"
            f"- Rotation: in Quaternion [{nums(tr.rotation.tolist())}]\n"
            f"            in RPY (radian) [{nums((roll, pitch, yaw))}]\n"
            f"            in RPY (degree) [{nums(degrees)}]\n")


def format_failure(now: float, error: TfError, buffer: TfBuffer) -> str:
    """tf_echo's block when the lookup fails: when, why, and every frame known."""
    return (f"Failure at {now:.9f}\nException thrown:{error}\nThe current list of frames is:\n"
            f"{buffer.all_frames_as_string()}\n")


async def run_echo(master_uri: str, source: str, target: str, out: TextIO, *, rate: float = 1.0,
                   precision: int = 3, clock: Callable[[], float] = time.time) -> None:
    """Print the transform from ``target`` into ``source`` (tf_echo's argument order) every ``1/rate`` seconds.

    Runs until cancelled. As tf_echo, "SOURCE TARGET" prints ``lookup_transform(SOURCE, TARGET)``:
    the pose of TARGET in SOURCE.
    """
    tf = TfSource(master_uri, node_name="tf_echo", clock=clock)
    task = asyncio.create_task(tf.run())
    try:
        deadline = time.monotonic() + FIRST_WAIT
        while time.monotonic() < deadline and not tf.buffer.can_transform(source, target):
            await asyncio.sleep(0.02)
        period = 1.0 / rate
        next_at = time.monotonic()
        while True:
            try:
                text = format_echo(tf.buffer.lookup_transform(source, target), precision)
            except TfError as exc:
                text = format_failure(clock(), exc, tf.buffer)
            out.write(text)
            out.flush()
            next_at += period
            await asyncio.sleep(max(0.0, next_at - time.monotonic()))
    finally:
        await tf.stop()
        task.cancel()
        try:
            await task
        except (asyncio.CancelledError, Exception):
            pass
