"""rospkg.rospack: ``RosPack`` and ``RosStack``, the packages and stacks on the ROS paths, their folders,
manifests and dependencies.

An instance made without ``ros_paths`` lists the packages rostui's own tools find (``ROS_PACKAGE_PATH``, the
built-in packages, Debian's in ``/usr/share``, one level deep as Debian's rospack looks there). One made with
``ros_paths`` crawls exactly those folders as rospkg does: a folder holding the manifest is a resource and is
not entered, ``CATKIN_IGNORE`` and ``rospack_nosubdirs`` stop the walk, hidden folders are skipped, and an
earlier path wins over a later one.
"""

from __future__ import annotations

import builtins
import os
import re
import threading
import xml.etree.ElementTree as ElementTree
from collections.abc import Sequence
from typing import Any, ClassVar

from rostui.core import packages

from .common import MANIFEST_FILE, PACKAGE_FILE, STACK_FILE, ResourceNotFound
from .environment import get_ros_paths
from .manifest import InvalidManifest, Manifest, parse_manifest_file

__all__ = [
    "ManifestManager", "RosPack", "RosStack", "expand_to_packages", "get_package_name", "get_stack_version_by_dir",
    "list_by_path",
]

_IGNORE_MARKERS = ("CATKIN_IGNORE", "rospack_nosubdirs")


def _package_xml_facts(path: str) -> tuple[str, bool] | None:
    """The name in a package.xml and whether it declares a metapackage; None when it cannot be read."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError):
        return None
    name = (root.findtext("name") or "").strip()
    return (name, root.find("./export/metapackage") is not None) if name else None


def _resource_in(folder: str, files: Sequence[str], manifest_name: str) -> str | None:
    """The resource *folder* is for *manifest_name* (MANIFEST_FILE: a package, STACK_FILE: a stack,
    PACKAGE_FILE: any catkin package), or None."""
    if PACKAGE_FILE in files:
        facts = _package_xml_facts(os.path.join(folder, PACKAGE_FILE))
        if facts is not None:
            name, is_metapackage = facts
            wanted = {MANIFEST_FILE: not is_metapackage, STACK_FILE: is_metapackage}.get(manifest_name, True)
            if wanted:
                return name
    if manifest_name in files:
        return os.path.basename(folder)
    return None


def list_by_path(manifest_name: str, path: str, cache: dict[str, str] | None) -> builtins.list[str]:
    """The resources (packages or stacks, by *manifest_name*) below *path*; each one's folder goes into *cache*."""
    found: builtins.list[str] = []
    for folder, dirs, files in os.walk(os.path.abspath(path), topdown=True, followlinks=True):
        if "CATKIN_IGNORE" in files:
            dirs.clear()
            continue
        name = _resource_in(folder, files, manifest_name)
        if name is not None:
            if name not in found:
                found.append(name)
                if cache is not None:
                    cache[name] = folder
            dirs.clear()
        elif MANIFEST_FILE in files or PACKAGE_FILE in files or any(m in files for m in _IGNORE_MARKERS):
            dirs.clear()
        else:
            dirs[:] = [d for d in dirs if not d.startswith(".")]
    return found


class ManifestManager:
    """The resources whose folders hold *manifest_name* on *ros_paths* (default: the ROS paths), with their
    manifests and dependencies. Answers are cached: a change on disk needs a new instance."""

    _instances: ClassVar[dict[tuple[type, tuple[str, ...]], ManifestManager]] = {}
    _instances_lock: ClassVar[threading.Lock] = threading.Lock()

    def __init__(self, manifest_name: str, ros_paths: Sequence[str] | None = None) -> None:
        self._manifest_name = manifest_name
        self._rostui_packages = ros_paths is None and manifest_name == MANIFEST_FILE
        self._ros_paths = builtins.list(ros_paths) if ros_paths is not None else get_ros_paths()
        self._manifests: dict[str, Manifest] = {}
        self._depends_cache: dict[str, builtins.list[str]] = {}
        self._location_cache: dict[str, str] | None = None
        self._custom_cache: dict[str, Any] = {}
        self._lock = threading.Lock()

    @classmethod
    def get_instance(cls, ros_paths: Sequence[str] | None = None) -> Any:
        """One shared instance of this class per list of paths."""
        paths = tuple(ros_paths if ros_paths is not None else get_ros_paths())
        with cls._instances_lock:
            key = (cls, paths)
            if key not in cls._instances:
                given = None if ros_paths is None else builtins.list(paths)
                cls._instances[key] = cls(given)  # type: ignore[arg-type]  # RosPack and RosStack take (ros_paths)
            return cls._instances[key]

    def get_ros_paths(self) -> builtins.list[str]:
        """The folders searched, in order (a copy)."""
        return builtins.list(self._ros_paths)

    ros_paths = property(get_ros_paths, doc="The folders searched, in order (a copy).")

    def _locations(self) -> dict[str, str]:
        with self._lock:
            if self._location_cache is None:
                cache: dict[str, str] = {}
                if self._rostui_packages:
                    cache = {name: str(folder) for name, folder in packages.list_packages().items()}
                else:
                    for path in reversed(self._ros_paths):  # an earlier path overwrites a later one
                        list_by_path(self._manifest_name, path, cache)
                self._location_cache = cache
            return self._location_cache

    def list(self) -> builtins.list[str]:
        """Every resource's name."""
        return builtins.list(self._locations())

    def get_path(self, name: str) -> str:
        """The folder of *name*; ResourceNotFound when there is none."""
        folder = self._locations().get(name)
        if folder is None:
            raise ResourceNotFound(name, ros_paths=self._ros_paths)
        return folder

    def get_manifest(self, name: str) -> Manifest:
        """The manifest of *name* (InvalidManifest when it cannot be read)."""
        if name not in self._manifests:
            self._manifests[name] = parse_manifest_file(self.get_path(name), self._manifest_name, rospack=self)
        return self._manifests[name]

    def get_depends(self, name: str, implicit: bool = True) -> builtins.list[str]:
        """What *name* depends on: directly, or (*implicit*) through its dependencies too."""
        direct = [d.name for d in self.get_manifest(name).depends]
        if not implicit:
            return direct
        if name not in self._depends_cache:
            self._depends_cache[name] = []  # a dependency cycle ends here
            found = set(direct)
            for dependency in direct:
                found.update(self.get_depends(dependency, implicit=True))
            self._depends_cache[name] = builtins.list(found)
        return self._depends_cache[name]

    def get_depends_on(self, name: str, implicit: bool = True) -> builtins.list[str]:
        """What depends on *name* (directly, or through others when *implicit*); unreadable manifests are passed."""
        users = []
        for other in self.list():
            if other == name:
                continue
            try:
                if name in self.get_depends(other, implicit=implicit):
                    users.append(other)
            except (InvalidManifest, ResourceNotFound):
                pass
        return users

    def get_custom_cache(self, key: str, default: Any = None) -> Any:
        """A value a caller kept here."""
        return self._custom_cache.get(key, default)

    def set_custom_cache(self, key: str, value: Any) -> None:
        """Keep a value here."""
        self._custom_cache[key] = value


class RosPack(ManifestManager):
    """The packages on the ROS paths: ``list``, ``get_path``, ``get_manifest``, ``get_depends``,
    ``get_depends_on``, ``get_rosdeps`` and ``stack_of``."""

    def __init__(self, ros_paths: Sequence[str] | None = None) -> None:
        super().__init__(MANIFEST_FILE, ros_paths)
        self._rosdeps_cache: dict[str, builtins.list[str]] = {}

    def get_rosdeps(self, package: str, implicit: bool = True) -> builtins.list[str]:
        """The system dependencies (rosdep keys) a rosbuild manifest names: *package*'s own, or (*implicit*)
        its dependencies' too. A catkin package.xml gives none (that needs rosdep's database)."""
        own = [d.name for d in self.get_manifest(package).rosdeps]
        if not implicit:
            return own
        if package not in self._rosdeps_cache:
            found = set(own)
            for dependency in self.get_depends(package, implicit=True):
                found.update(self.get_rosdeps(dependency, implicit=False))
            self._rosdeps_cache[package] = builtins.list(found)
        return self._rosdeps_cache[package]

    def stack_of(self, package: str) -> str | None:
        """The rosbuild stack holding *package* (the nearest folder up with a stack.xml), or None."""
        folder = self.get_path(package)
        while folder and os.path.dirname(folder) != folder:
            if os.path.exists(os.path.join(folder, STACK_FILE)):
                return os.path.basename(folder)
            folder = os.path.dirname(folder)
        return None


class RosStack(ManifestManager):
    """The rosbuild stacks (folders with a stack.xml) and catkin metapackages on the ROS paths."""

    def __init__(self, ros_paths: Sequence[str] | None = None) -> None:
        super().__init__(STACK_FILE, ros_paths)

    def packages_of(self, stack: str) -> builtins.list[str]:
        """The packages inside *stack*'s folder."""
        return list_by_path(MANIFEST_FILE, self.get_path(stack), {})

    def get_stack_version(self, stack: str) -> str | None:
        """*stack*'s version (see :func:`get_stack_version_by_dir`)."""
        return get_stack_version_by_dir(self.get_path(stack))


def expand_to_packages(names: Sequence[str], rospack: RosPack, rosstack: RosStack) \
        -> tuple[builtins.list[str], builtins.list[str]]:
    """*names* of packages and stacks as package names: (packages, names that are neither)."""
    if not isinstance(names, (list, tuple)):
        raise ValueError("names must be a list of strings")
    known = set(rospack.list())
    valid: builtins.list[str] = []
    invalid: builtins.list[str] = []
    for name in names:
        if name in known:
            valid.append(name)
            continue
        try:
            valid.extend(rosstack.packages_of(name))
        except ResourceNotFound:
            invalid.append(name)
    return valid, invalid


def get_stack_version_by_dir(stack_dir: str) -> str | None:
    """The version of the stack in *stack_dir*: its stack.xml's ``<version>``, else the one in its
    CMakeLists.txt's ``rosbuild_make_distribution(...)``; None when neither gives one."""
    try:
        version = (ElementTree.parse(os.path.join(stack_dir, STACK_FILE)).getroot().findtext("version") or "").strip()
    except (ElementTree.ParseError, OSError):
        version = ""
    if version:
        return version
    try:
        with open(os.path.join(stack_dir, "CMakeLists.txt"), encoding="utf-8", errors="replace") as cmake:
            return _get_cmake_version(cmake.read())
    except OSError:
        return None
    except ValueError:
        return None


_DISTRIBUTION_CALL = re.compile(r"[()]")


def _get_cmake_version(text: str) -> str | None:
    """The version in CMakeLists text's ``rosbuild_make_distribution(VERSION)``; ValueError when that line has
    none; None when there is no such line."""
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("rosbuild_make_distribution"):
            parts = _DISTRIBUTION_CALL.split(line)
            if len(parts) < 2 or not parts[1]:
                raise ValueError(f"cannot parse the version number in CMakeLists.txt:\n\n{line}")
            return parts[1]
    return None


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
