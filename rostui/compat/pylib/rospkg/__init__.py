"""rospkg for unmodified ROS 1 scripts: ``RosPack`` (packages, their folders, manifests and dependencies),
``ResourceNotFound`` and the ROS directories (``get_ros_home``, ``get_log_dir``, ``get_ros_paths``).

The packages are those rostui finds, as rospack finds them: ``ROS_PACKAGE_PATH``, rostui's built-in
packages, then Debian's in ``/usr/share``. ``RosStack``, rosdep keys and ``rospkg.distro``/``os_detect`` are
not here.
"""

from __future__ import annotations

from .common import MANIFEST_FILE, PACKAGE_FILE, STACK_FILE, ResourceNotFound
from .environment import (
    ROS_HOME, ROS_LOG_DIR, ROS_PACKAGE_PATH, ROS_ROOT, get_log_dir, get_ros_home, get_ros_package_path, get_ros_paths,
    get_ros_root, get_test_results_dir,
)
from .manifest import InvalidManifest, Manifest, parse_manifest_file
from .rospack import RosPack, get_package_name

__all__ = [
    "InvalidManifest", "MANIFEST_FILE", "Manifest", "PACKAGE_FILE", "ROS_HOME", "ROS_LOG_DIR", "ROS_PACKAGE_PATH",
    "ROS_ROOT", "ResourceNotFound", "RosPack", "STACK_FILE", "get_log_dir", "get_package_name", "get_ros_home",
    "get_ros_package_path", "get_ros_paths", "get_ros_root", "get_test_results_dir", "parse_manifest_file",
]
