"""rospkg.common: the manifest file names and ``ResourceNotFound``."""

from __future__ import annotations

from collections.abc import Sequence

__all__ = ["MANIFEST_FILE", "PACKAGE_FILE", "ROS_STACK", "STACK_FILE", "ResourceNotFound"]

MANIFEST_FILE = "manifest.xml"
PACKAGE_FILE = "package.xml"
STACK_FILE = "stack.xml"
ROS_STACK = "ros"


class ResourceNotFound(Exception):
    """A package (or other resource) that is not on the ROS paths; its text lists the paths searched."""

    def __init__(self, msg: str, ros_paths: Sequence[str] | None = None) -> None:
        super().__init__(msg)
        self.ros_paths = ros_paths

    def __str__(self) -> str:
        lines = [str(self.args[0])]
        lines += [f"ROS path [{i}]={path}" for i, path in enumerate(self.ros_paths or ())]
        return "\n".join(lines)
