"""rospkg.rospack: ``RosPack``, the packages on the ROS paths, their folders, manifests and dependencies."""

from __future__ import annotations

import builtins
import os
from collections.abc import Sequence
from typing import Any

from rostui.core import packages

from .common import MANIFEST_FILE, PACKAGE_FILE, ResourceNotFound
from .environment import get_ros_paths
from .manifest import InvalidManifest, Manifest, parse_manifest_file

__all__ = ["RosPack", "get_package_name"]


class RosPack:
    """The packages rostui finds (``ROS_PACKAGE_PATH``, then its built-in ones, then Debian's), as rospack lists
    them: ``list``, ``get_path``, ``get_manifest``, ``get_depends``, ``get_depends_on``."""

    def __init__(self, ros_paths: Sequence[str] | None = None) -> None:
        self._ros_paths = list(ros_paths) if ros_paths is not None else get_ros_paths()
        self._manifests: dict[str, Manifest] = {}
        self._depends_cache: dict[str, list[str]] = {}
        self._custom_cache: dict[str, Any] = {}

    @classmethod
    def get_instance(cls, ros_paths: Sequence[str] | None = None) -> RosPack:
        """A RosPack (rospkg shares one per set of paths; a new one costs little here)."""
        return cls(ros_paths)

    def get_ros_paths(self) -> list[str]:
        """The directories searched."""
        return list(self._ros_paths)

    def list(self) -> builtins.list[str]:
        """Every package name."""
        return builtins.list(packages.list_packages())

    def get_path(self, name: str) -> str:
        """The folder of package *name*; ResourceNotFound when there is none."""
        folder = packages.find_package(name)
        if folder is None:
            raise ResourceNotFound(name, ros_paths=self._ros_paths)
        return str(folder)

    def get_manifest(self, name: str) -> Manifest:
        """The manifest of package *name*."""
        if name not in self._manifests:
            self._manifests[name] = parse_manifest_file(self.get_path(name), MANIFEST_FILE,
                                                        frozenset(packages.list_packages()))
        return self._manifests[name]

    def get_depends(self, name: str, implicit: bool = True) -> builtins.list[str]:
        """The packages *name* depends on: directly, or (*implicit*) through its dependencies too."""
        direct = [d.name for d in self.get_manifest(name).depends]
        if not implicit:
            return direct
        if name not in self._depends_cache:
            self._depends_cache[name] = []  # a cycle ends here
            found = set(direct)
            for dependency in direct:
                found.update(self.get_depends(dependency, implicit=True))
            self._depends_cache[name] = builtins.list(found)
        return self._depends_cache[name]

    def get_depends_on(self, name: str, implicit: bool = True) -> builtins.list[str]:
        """The packages that depend on *name* (directly, or through others when *implicit*)."""
        users = []
        for other in self.list():
            if other == name:
                continue
            try:
                if name in self.get_depends(other, implicit=implicit):
                    users.append(other)
            except (InvalidManifest, ResourceNotFound, OSError):
                pass
        return users

    def get_rosdeps(self, package: str, implicit: bool = True) -> builtins.list[str]:
        """The system dependencies (rosdep keys) of *package*: none here (rostui has no rosdep database)."""
        self.get_manifest(package)
        return []

    def get_custom_cache(self, key: str, default: Any = None) -> Any:
        """A value a caller kept here."""
        return self._custom_cache.get(key, default)

    def set_custom_cache(self, key: str, value: Any) -> None:
        """Keep a value here."""
        self._custom_cache[key] = value


def get_package_name(path: str) -> str | None:
    """The name of the package holding *path* (the nearest folder up with a manifest); None when none does."""
    folder = os.path.abspath(path)
    while True:
        if os.path.exists(os.path.join(folder, MANIFEST_FILE)):
            return os.path.basename(folder)
        if os.path.exists(os.path.join(folder, PACKAGE_FILE)):
            return packages.package_of(os.path.join(folder, PACKAGE_FILE))
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent
