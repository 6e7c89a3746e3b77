"""genpy.rostime: ROS ``time`` and ``duration`` (rostui's, printing ``genpy.Time[...]`` as genpy does)."""

from __future__ import annotations

from rostui.core.rostime import Duration, Time, TVal

__all__ = ["Time", "Duration", "TVal"]

TVal.repr_prefix = "genpy"
