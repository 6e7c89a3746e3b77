"""roslib.packages: where a ROS package lives (rostui's package search: ROS_PACKAGE_PATH, then built-ins)."""

from __future__ import annotations

from rostui.core.packages import PackageNotFoundError, get_package_path

__all__ = ["InvalidROSPkgException", "get_pkg_dir"]


class InvalidROSPkgException(Exception):
    """A package name that no package root holds."""


def get_pkg_dir(package: str, required: bool = True, ros_root: str | None = None) -> str:
    """The directory of *package*; raises :class:`InvalidROSPkgException` if there is none."""
    try:
        return str(get_package_path(package))
    except PackageNotFoundError:
        raise InvalidROSPkgException(f"Cannot locate installation of package {package}: [rospack] Error: "
                                     f"package '{package}' not found") from None
