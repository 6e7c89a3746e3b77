"""rospkg for unmodified ROS 1 scripts: ``RosPack`` and ``RosStack`` (packages and stacks, their folders,
manifests and dependencies), manifest parsing, ``ResourceNotFound`` and the ROS directories (``get_ros_home``,
``get_log_dir``, ``get_ros_paths``...).

A ``RosPack()`` finds the packages rostui finds, as rospack finds them: ``ROS_PACKAGE_PATH``, rostui's built-in
packages, then Debian's in ``/usr/share``. ``rospkg.distro``, ``rospkg.os_detect`` and rosdep's database are not
here: a catkin package.xml's system dependencies are not told apart.
"""

from __future__ import annotations

from .common import MANIFEST_FILE, PACKAGE_FILE, ROS_STACK, STACK_FILE, ResourceNotFound
from .environment import (
    ROS_ETC_DIR, ROS_HOME, ROS_LOG_DIR, ROS_PACKAGE_PATH, ROS_ROOT, get_etc_ros_dir, get_log_dir, get_ros_home,
    get_ros_package_path, get_ros_paths, get_ros_root, get_test_results_dir, on_ros_path,
)
from .manifest import InvalidManifest, Manifest, parse_manifest_file
from .rospack import (
    ManifestManager, RosPack, RosStack, expand_to_packages, get_package_name, get_stack_version_by_dir, list_by_path,
)

#: The rospkg release whose API this follows (Debian's python3-rospkg).
__version__ = "1.4.0"

__all__ = [
    "InvalidManifest", "MANIFEST_FILE", "Manifest", "ManifestManager", "PACKAGE_FILE", "ROS_ETC_DIR", "ROS_HOME",
    "ROS_LOG_DIR", "ROS_PACKAGE_PATH", "ROS_ROOT", "ROS_STACK", "ResourceNotFound", "RosPack", "RosStack",
    "STACK_FILE", "expand_to_packages", "get_etc_ros_dir", "get_log_dir", "get_package_name", "get_ros_home",
    "get_ros_package_path", "get_ros_paths", "get_ros_root", "get_stack_version_by_dir", "get_test_results_dir",
    "list_by_path", "on_ros_path", "parse_manifest_file",
]
