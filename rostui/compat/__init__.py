"""What unmodified ROS 1 Python scripts import, served by rostui (`rostui python`, `rostui shell-env`).

:data:`PYLIB` is a directory of importable top-level packages (``rospy``,
``genpy``, ``rosbag``, ``roslib``) and a ``sitecustomize`` that, at a child interpreter's start,
chooses between rostui's modules and a real ROS install (:mod:`.choice`) and
installs the import hook of :mod:`.finder` that makes ``<pkg>.msg`` and
``<pkg>.srv`` modules from rostui's message classes.
"""

from __future__ import annotations

from rostui.compat.deferred import import_urllib_parse_lean

import_urllib_parse_lean()  # before pathlib imports it: without ipaddress until a bracketed host needs it

from pathlib import Path  # noqa: E402

__all__ = ["PKGPY", "PYLIB", "ROSTUI_ROOT"]

PYLIB: Path = Path(__file__).resolve().parent / "pylib"
"""The directory put first on a script's ``sys.path`` (its ``PYTHONPATH``)."""

PKGPY: Path = Path(__file__).resolve().parent / "pkgpy"
"""Python modules ROS message packages ship besides ``msg``/``srv`` (``sensor_msgs.point_cloud2``), one
directory per package: the finder makes it the package's ``__path__``."""

ROSTUI_ROOT: Path = Path(__file__).resolve().parent.parent.parent
"""The directory holding the ``rostui`` package, so an interpreter without rostui installed finds it."""
