"""How `rostui python` and `rostui run` start a ROS 1 Python script: the argv, environment and notice.

Both commands go through :func:`plan`: the script runs in rostui's own Python
with :func:`rostui.compat.choice.child_env`, so its interpreter's
``sitecustomize`` makes the choice of :mod:`rostui.compat.choice` and says so.
One case more for `rostui run`: a script whose ``#!`` line names another Python
that can import a real ROS, where rostui's Python cannot, runs with that Python,
as rosrun would run it; the notice line is then printed here.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path

from rostui.core.records import FrozenRecord

from . import PYLIB
from .choice import REAL_ROS_MODULES, Choice, Mode, child_env, find_real_ros

__all__ = ["Plan", "plan", "real_ros_of"]

_PROBE_TIMEOUT = 30.0
_PROBE = (
    "import importlib.util, os\n"
    f"for name in {REAL_ROS_MODULES!r}:\n"
    "    spec = importlib.util.find_spec(name)\n"
    "    if spec is not None and spec.origin not in (None, 'namespace'):\n"
    "        print(os.path.dirname(spec.origin))\n"
    "        break\n"
)


class Plan(FrozenRecord):
    """What to ``exec``: ``argv`` with ``env``, after printing ``notice`` (if any) on stderr (immutable).

    A record rather than a dataclass: :mod:`rostui.core.records` says why.
    """

    __slots__ = _fields = ("argv", "env", "notice")

    argv: list[str]
    env: dict[str, str]
    notice: str | None

    def __init__(self, argv: list[str], env: dict[str, str], notice: str | None = None) -> None:
        self._set(argv, env, notice)


def _without_pylib(env: Mapping[str, str]) -> dict[str, str]:
    out = {k: v for k, v in env.items() if not k.startswith("ROSTUI_PYTHON")}
    entries = [e for e in env.get("PYTHONPATH", "").split(os.pathsep) if e and Path(e).resolve() != PYLIB]
    if entries:
        out["PYTHONPATH"] = os.pathsep.join(entries)
    else:
        out.pop("PYTHONPATH", None)
    return out


def real_ros_of(interpreter: str, env: Mapping[str, str]) -> Path | None:
    """The directory of the real ``rospy`` (or ``genpy``, ``rosbag``) *interpreter* imports, if any."""
    import subprocess  # here: `rostui python SCRIPT` itself starts no process (asyncio's stand-in, compat/deferred.py)

    try:
        out = subprocess.run([interpreter, "-c", _PROBE], env=_without_pylib(env), capture_output=True,
                             text=True, timeout=_PROBE_TIMEOUT, stdin=subprocess.DEVNULL)
    except (OSError, subprocess.TimeoutExpired):
        return None
    found = out.stdout.strip()
    return Path(found) if out.returncode == 0 and found else None


def plan(mode: Mode, script: str, args: Sequence[str], env: Mapping[str, str], *,
         interpreter: str | None = None) -> Plan:
    """How to run *script* with *args* in *mode*.

    *interpreter* is the Python the script's ``#!`` line names (`rostui run`):
    in :attr:`Mode.AUTO`, when rostui's Python finds no real ROS and that one
    does, the script runs as ``script ARGS`` with *env* unchanged and the notice
    says it gets the real ROS; in :attr:`Mode.REAL` it always runs so. Otherwise
    it runs as ``rostui python`` runs it, and in :attr:`Mode.ROSTUI` the notice
    names the real ROS that *interpreter* would have given it.
    """
    if mode is Mode.REAL and interpreter is not None:
        return Plan([script, *args], _without_pylib(env))
    ours = Plan([sys.executable, script, *args], child_env(mode, env))
    if interpreter is None or os.path.abspath(interpreter) == os.path.abspath(sys.executable):
        return ours
    if find_real_ros(sys.path) is not None:
        return ours
    real = real_ros_of(interpreter, env)
    if real is None:
        return ours
    if mode is Mode.ROSTUI:
        return Plan(ours.argv, ours.env, Choice(True, real).describe())
    return Plan([script, *args], _without_pylib(env), Choice(False, real).describe())
