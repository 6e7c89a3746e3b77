"""What a script's interpreter does at start (called from ``PYLIB/sitecustomize.py``).

It decides (:func:`rostui.compat.choice.choose`) between rostui's modules and a
real ROS, says so on stderr when a real ROS is found, and then either installs
the import hook or takes :data:`PYLIB` off ``sys.path`` so the real ROS's
``genpy`` and ``roslib`` are the ones imported. Last it runs the
``sitecustomize`` that ours hides (Debian's, for one), as Python would have.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from importlib.machinery import PathFinder
from pathlib import Path

from . import PYLIB
from .choice import ENV_MODE, ENV_NOTICE_SHOWN, Choice, Mode, choose

__all__ = ["start", "run_hidden_sitecustomize", "hidden_ran"]

hidden_ran = False
"""True when the ``sitecustomize`` ours hides already ran in this interpreter (a script run in the
interpreter of `rostui python` itself, :mod:`rostui.compat.inplace`): it is not run twice."""


def _is_pylib(entry: str) -> bool:
    try:
        return Path(entry or ".").resolve() == PYLIB
    except OSError:
        return False


def start() -> Choice:
    """Choose, tell, and set up this interpreter's imports; returns the choice."""
    mode = Mode.from_env(os.environ)
    choice = choose(mode, sys.path)
    if choice.notice and not os.environ.get(ENV_NOTICE_SHOWN):
        print(choice.describe(), file=sys.stderr)
        os.environ[ENV_NOTICE_SHOWN] = "1"
    if choice.use_rostui:
        from rostui.core.msg import codecache
        from rostui.core.rostime import TVal

        from .finder import install

        codecache.use_directory(codecache.default_directory())  # a node's start skips compiling its classes
        TVal.repr_prefix = "genpy"  # times print as genpy's do, whether or not the script imports genpy
        install(first=choice.real_ros is not None)
        os.environ[ENV_MODE] = Mode.ROSTUI.value
    else:
        sys.path[:] = [p for p in sys.path if not _is_pylib(p)]
        os.environ[ENV_MODE] = Mode.REAL.value
    return choice


def run_hidden_sitecustomize() -> None:
    """Import the next ``sitecustomize`` on ``sys.path`` after ours, under its own name (unless :data:`hidden_ran`)."""
    if hidden_ran:
        return
    search = [p for p in sys.path if not _is_pylib(p)]
    spec = PathFinder.find_spec("sitecustomize", search)
    if spec is None or spec.loader is None or spec.origin is None:
        return
    if Path(spec.origin).resolve().parent == PYLIB:
        return
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
