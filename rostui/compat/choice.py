"""Which ROS a script gets: rostui's modules or a real ROS install that its interpreter can import.

The choice travels to the script's interpreter in ``ROSTUI_PYTHON``: ``rostui``,
``real``, or ``auto`` (unset): the real ROS when ``rospy``, ``genpy`` or ``rosbag`` is
importable from anywhere but :data:`rostui.compat.PYLIB`, rostui's otherwise.
rostui's modules never hide a real ROS silently: whenever one is found, one
line on stderr says which the script gets.
"""

from __future__ import annotations

import enum
import os
from collections.abc import Iterable, Mapping
from importlib.machinery import PathFinder
from pathlib import Path

from rostui.core.records import FrozenRecord

from . import PYLIB, ROSTUI_ROOT

__all__ = ["ENV_MODE", "ENV_NOTICE_SHOWN", "REAL_ROS_MODULES", "Mode", "Choice", "find_real_ros", "choose",
           "pythonpath_for", "child_env"]

ENV_MODE = "ROSTUI_PYTHON"
"""The environment variable carrying the :class:`Mode` to a script's interpreter."""
ENV_NOTICE_SHOWN = "ROSTUI_PYTHON_NOTICE_SHOWN"
"""Set once the notice is printed, so the script's own Python children do not repeat it."""
REAL_ROS_MODULES = ("rospy", "genpy", "rosbag")
"""Top-level modules whose presence means a real ROS 1 install is importable."""


class Mode(enum.Enum):
    """What the user asked for."""

    AUTO = "auto"
    ROSTUI = "rostui"
    REAL = "real"

    @classmethod
    def from_env(cls, env: Mapping[str, str]) -> Mode:
        """The mode *env* names; an unknown or missing value is :attr:`AUTO`."""
        try:
            return cls(env.get(ENV_MODE, "auto").strip().lower() or "auto")
        except ValueError:
            return cls.AUTO


class Choice(FrozenRecord):
    """The outcome: whether the script gets rostui's modules, and the real ROS found, if any (immutable).

    A record rather than a dataclass: :mod:`rostui.core.records` says why.
    """

    __slots__ = _fields = ("use_rostui", "real_ros")

    use_rostui: bool
    real_ros: Path | None

    def __init__(self, use_rostui: bool, real_ros: Path | None) -> None:
        self._set(use_rostui, real_ros)

    def describe(self) -> str:
        """One line saying which ROS the script gets and where it comes from."""
        if self.use_rostui:
            shown = f"rostui's rospy, genpy, roslib, rosbag and message modules ({PYLIB})"
            if self.real_ros is not None:
                return f"rostui python: the script gets {shown}, not the real ROS at {self.real_ros}"
            return f"rostui python: the script gets {shown}"
        if self.real_ros is None:
            return "rostui python: the script gets no ROS modules (--real-ros, but no real ROS is importable)"
        return (f"rostui python: the script gets the real ROS at {self.real_ros} "
                f"(`rostui python --rostui` gives it rostui's)")

    @property
    def notice(self) -> bool:
        """Whether the script's stderr gets :meth:`describe`: only when a real ROS is found."""
        return self.real_ros is not None


def _same_dir(a: str, b: Path) -> bool:
    try:
        return Path(a or ".").resolve() == b
    except OSError:
        return False


def find_real_ros(paths: Iterable[str]) -> Path | None:
    """The directory of the first of :data:`REAL_ROS_MODULES` importable from *paths* (rostui's own left out)."""
    search = [p for p in paths if not _same_dir(p, PYLIB)]
    for name in REAL_ROS_MODULES:
        spec = PathFinder.find_spec(name, search)
        if spec is not None and spec.origin is not None and spec.origin != "namespace":
            return Path(spec.origin).parent
    return None


def choose(mode: Mode, paths: Iterable[str]) -> Choice:
    """Decide for *mode*, looking for a real ROS on *paths* (a ``sys.path``)."""
    real = find_real_ros(paths)
    if mode is Mode.ROSTUI:
        return Choice(True, real)
    if mode is Mode.REAL:
        return Choice(False, real)
    return Choice(real is None, real)


def pythonpath_for(existing: str | None) -> str:
    """``PYTHONPATH`` with rostui's modules (and the ``rostui`` package itself) in front of *existing*."""
    entries = [str(PYLIB), str(ROSTUI_ROOT)]
    if existing:
        entries += [e for e in existing.split(os.pathsep) if e not in entries]
    return os.pathsep.join(entries)


def child_env(mode: Mode, env: Mapping[str, str]) -> dict[str, str]:
    """The environment of a script run by ``rostui python`` in *mode*."""
    out = dict(env)
    out["PYTHONPATH"] = pythonpath_for(env.get("PYTHONPATH"))
    out[ENV_MODE] = mode.value
    out.pop(ENV_NOTICE_SHOWN, None)
    return out
