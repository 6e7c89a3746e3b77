"""rospkg.environment: the ROS directories a program uses, from the environment.

``get_ros_paths`` lists where rostui looks for packages: ``ROS_ROOT``, ``ROS_PACKAGE_PATH``'s entries, rostui's
built-in packages, then ``/usr/share`` (where Debian installs ROS packages; Debian's rospkg adds it too).
"""

from __future__ import annotations

import os
from collections.abc import Mapping

from rostui.core.packages import BUILTIN_SHARE, SYSTEM_SHARE

__all__ = [
    "ROS_HOME", "ROS_LOG_DIR", "ROS_PACKAGE_PATH", "ROS_ROOT", "ROS_TEST_RESULTS_DIR", "get_log_dir", "get_ros_home",
    "get_ros_package_path", "get_ros_paths", "get_ros_root", "get_test_results_dir",
]

ROS_ROOT = "ROS_ROOT"
ROS_PACKAGE_PATH = "ROS_PACKAGE_PATH"
ROS_HOME = "ROS_HOME"
ROS_LOG_DIR = "ROS_LOG_DIR"
ROS_TEST_RESULTS_DIR = "ROS_TEST_RESULTS_DIR"


def _env(env: Mapping[str, str] | None) -> Mapping[str, str]:
    return os.environ if env is None else env


def get_ros_root(env: Mapping[str, str] | None = None) -> str | None:
    """``ROS_ROOT``, normalised; None when unset."""
    root = _env(env).get(ROS_ROOT)
    return os.path.normpath(root) if root else None


def get_ros_package_path(env: Mapping[str, str] | None = None) -> str:
    """``ROS_PACKAGE_PATH`` with rostui's built-in packages and ``/usr/share`` after it."""
    return os.pathsep.join(filter(None, [_env(env).get(ROS_PACKAGE_PATH, ""), str(BUILTIN_SHARE), str(SYSTEM_SHARE)]))


def get_ros_paths(env: Mapping[str, str] | None = None) -> list[str]:
    """The directories searched for packages, in order."""
    root = get_ros_root(env)
    paths = [root] if root else []
    return paths + [p for p in get_ros_package_path(env).split(os.pathsep) if p.strip()]


def get_ros_home(env: Mapping[str, str] | None = None) -> str:
    """``ROS_HOME``, else ``~/.ros``."""
    return _env(env).get(ROS_HOME) or os.path.join(os.path.expanduser("~"), ".ros")


def get_log_dir(env: Mapping[str, str] | None = None) -> str:
    """``ROS_LOG_DIR``, else ``<ROS_HOME>/log``."""
    return _env(env).get(ROS_LOG_DIR) or os.path.join(get_ros_home(env), "log")


def get_test_results_dir(env: Mapping[str, str] | None = None) -> str:
    """``ROS_TEST_RESULTS_DIR``, else ``<ROS_HOME>/test_results``."""
    return _env(env).get(ROS_TEST_RESULTS_DIR) or os.path.join(get_ros_home(env), "test_results")
