"""rospkg.environment: the ROS directories a program uses, from the environment.

``get_ros_paths`` lists where rostui looks for packages: ``ROS_ROOT``, ``ROS_PACKAGE_PATH``'s entries, rostui's
built-in packages, then ``/usr/share`` (where Debian installs ROS packages; Debian's rospkg adds it too).
"""

from __future__ import annotations

import os
from collections.abc import Mapping

from rostui.core.packages import BUILTIN_SHARE, SYSTEM_SHARE

__all__ = [
    "ROS_ETC_DIR", "ROS_HOME", "ROS_LOG_DIR", "ROS_PACKAGE_PATH", "ROS_ROOT", "ROS_TEST_RESULTS_DIR", "get_etc_ros_dir",
    "get_log_dir", "get_ros_home", "get_ros_package_path", "get_ros_paths", "get_ros_root", "get_test_results_dir",
    "on_ros_path",
]

ROS_ROOT = "ROS_ROOT"
ROS_PACKAGE_PATH = "ROS_PACKAGE_PATH"
ROS_HOME = "ROS_HOME"
ROS_ETC_DIR = "ROS_ETC_DIR"
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


def _compute_package_paths(ros_root: str | None, ros_package_path: str | None) -> list[str]:
    """ROS_ROOT (when set) followed by the non-empty entries of a ROS_PACKAGE_PATH value."""
    paths = [ros_root] if ros_root else []
    return paths + [p for p in (ros_package_path or "").split(os.pathsep) if p.strip()]


def get_ros_paths(env: Mapping[str, str] | None = None) -> list[str]:
    """The directories searched for packages, in order."""
    return _compute_package_paths(get_ros_root(env), get_ros_package_path(env))


def _resolve_path(path: str) -> str:
    """*path* absolute and normalised, ``~`` expanded."""
    return os.path.abspath(os.path.normpath(os.path.expanduser(path)))


def _resolve_paths(paths: str) -> str:
    """Each entry of a path list (``os.pathsep``-separated) resolved as :func:`_resolve_path` does."""
    return os.pathsep.join(_resolve_path(p) for p in paths.split(os.pathsep) if p.strip())


def on_ros_path(path: str, env: Mapping[str, str] | None = None) -> bool:
    """True when *path* is inside one of the ROS paths (ROS_ROOT or a ROS_PACKAGE_PATH entry)."""
    target = _resolve_path(path)
    for root in get_ros_paths(env):
        root = _resolve_path(root)
        if target == root or target.startswith(root.rstrip(os.sep) + os.sep):
            return True
    return False


def get_etc_ros_dir(env: Mapping[str, str] | None = None) -> str:
    """``ROS_ETC_DIR``, else ``/etc/ros``."""
    return _env(env).get(ROS_ETC_DIR) or "/etc/ros"


def get_ros_home(env: Mapping[str, str] | None = None) -> str:
    """``ROS_HOME``, else ``~/.ros``."""
    return _env(env).get(ROS_HOME) or os.path.join(os.path.expanduser("~"), ".ros")


def get_log_dir(env: Mapping[str, str] | None = None) -> str:
    """``ROS_LOG_DIR``, else ``<ROS_HOME>/log``."""
    return _env(env).get(ROS_LOG_DIR) or os.path.join(get_ros_home(env), "log")


def get_test_results_dir(env: Mapping[str, str] | None = None) -> str:
    """``ROS_TEST_RESULTS_DIR``, else ``<ROS_HOME>/test_results``."""
    return _env(env).get(ROS_TEST_RESULTS_DIR) or os.path.join(get_ros_home(env), "test_results")
