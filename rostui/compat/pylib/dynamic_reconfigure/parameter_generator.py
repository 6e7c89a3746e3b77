"""The rosbuild form of the ``.cfg`` generator (``from dynamic_reconfigure.parameter_generator import *``).

The same API as :mod:`dynamic_reconfigure.parameter_generator_catkin`; as in rosbuild, the generator takes
no command-line arguments, source files are named by their full path, and a ``.cfg`` run by hand writes
``<package>/src/<package>/cfg/<Name>Config.py``.
"""

from __future__ import annotations

from rostui.core.packages import get_package_path

from .parameter_generator_catkin import (
    ParameterGenerator as _CatkinGenerator, Template, bool_t, check_description, check_name, double_t, inspect,
    int_t, os, re, str_t, sys, textwrap,
)

__all__ = [
    "Template", "ParameterGenerator", "bool_t", "check_description", "check_name", "double_t", "inspect", "int_t",
    "os", "re", "str_t", "sys", "textwrap",
]


def _absolute(path: str) -> str:
    return os.path.abspath(path)


class ParameterGenerator(_CatkinGenerator):
    """The catkin generator with rosbuild's conventions (full source paths, output in the package's ``src``)."""

    _srcfile = staticmethod(_absolute)

    def _take_arguments(self) -> None:
        self.dynconfpath = str(get_package_path("dynamic_reconfigure"))

    def _output_dir(self) -> str:
        return str(get_package_path(self.pkgname) / "src" / self.pkgname / "cfg")
