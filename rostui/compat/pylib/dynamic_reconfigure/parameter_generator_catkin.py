"""The ``.cfg`` generator's Python API (``ParameterGenerator``), as a package's ``cfg/<Name>.cfg`` file calls it.

A ``.cfg`` file is a Python script: it makes a ``ParameterGenerator``, adds parameters, constants,
enums and groups, and ends with ``exit(gen.generate(PACKAGE, NODE, NAME))``. dynamic_reconfigure runs it
at build time to write ``<Name>Config.py``; rostui runs it when ``<pkg>.cfg.<Name>Config`` is imported
(:mod:`dynamic_reconfigure.cfg_modules`) and builds the same module in memory: ``config_description``,
``min``, ``max``, ``defaults``, ``level``, ``type``, ``all_level`` and one ``<Name>_<const>`` per
constant. Run by hand with catkin's four arguments (the generator's directory, the build, C++ and Python
output directories), a ``.cfg`` writes ``<py dir>/cfg/<Name>Config.py``; the C++ header and the
documentation files are not written.

The rules are dynamic_reconfigure's: names as ROS conventions want them, min and max only for numbers,
values type-checked (an int given for a double becomes a float; a missing default stays the int 0), the
int range of a 32-bit int, no quotes in descriptions, one type per enum (an enum is the ``repr`` of its
constants, used as the parameter's ``edit_method``). Each generator numbers its own groups.
"""

from __future__ import annotations

import inspect
import os
import re
import sys
import textwrap
from collections.abc import Callable
from string import Template
from types import FrameType
from typing import Any

__all__ = [
    "Template", "ParameterGenerator", "bool_t", "check_description", "check_name", "double_t", "inspect", "int_t",
    "os", "re", "str_t", "sys", "textwrap",
]

str_t = "str"
bool_t = "bool"
int_t = "int"
double_t = "double"

_PYTYPES: dict[str, type] = {"str": str, "int": int, "double": float, "bool": bool}
_CTYPES = {"str": "std::string", "int": "int", "double": "double", "bool": "bool"}
_CCONSTTYPES = {"str": "const char * const", "int": "const int", "double": "const double", "bool": "const bool"}
_NAME = re.compile(r"^[a-zA-Z][a-zA-Z0-9_]*$")
USAGE = textwrap.dedent("""\
    ahhhh! Unexpected command line syntax!

    Are you trying to call a dynamic_reconfigure configuration generation script
    directly? When you are using dynamic_reconfigure with python, you don't ever
    need to invoke the configuration generator script yourself; it loads
    automatically. If you are using dynamic_reconfigure from C++, you need to
    add a call to generate_dynamic_reconfigure_options() in your CMakeLists.txt

    For an example, see http://wiki.ros.org/dynamic_reconfigure/Tutorials

    Have a nice day
    """)
"""What a ``.cfg`` run by hand without catkin's arguments says (dynamic_reconfigure's own words, kept for users
who search for them)."""

_capture: list[ParameterGenerator] | None = None
"""While :mod:`dynamic_reconfigure.cfg_modules` runs a ``.cfg`` file: the generators that called ``generate``."""


def check_description(description: str) -> None:
    """Refuse a description holding a quote (the C++ header could not hold it)."""
    for quote in ('"', "'"):
        if quote in description:
            raise Exception(f"quotes not allowed in description string `{description}`")


def check_name(name: str) -> None:
    """Refuse a parameter name that does not follow the ROS naming conventions."""
    if not _NAME.match(name):
        raise Exception(f"The name of field '{name}' does not follow the ROS naming conventions, "
                        "see http://wiki.ros.org/ROS/Patterns/Conventions")


def _caller_frame() -> FrameType:
    """The frame that called the function calling this one."""
    frame = inspect.currentframe()
    assert frame is not None and frame.f_back is not None and frame.f_back.f_back is not None
    return frame.f_back.f_back


def _source_of(frame: FrameType, name_of: Callable[[str], str]) -> tuple[int, str]:
    path = inspect.getsourcefile(frame.f_code) or frame.f_code.co_filename
    return frame.f_lineno, name_of(path)


def _basename(path: str) -> str:
    return os.path.basename(path)


class ParameterGenerator:
    """Collects a ``.cfg`` file's parameters, constants and groups, and makes its ``<Name>Config`` module."""

    minval: dict[str, Any] = {"int": -0x80000000, "double": -float("inf"), "str": "", "bool": False}
    maxval: dict[str, Any] = {"int": 0x7FFFFFFF, "double": float("inf"), "str": "", "bool": True}
    defval: dict[str, Any] = {"int": 0, "double": 0, "str": "", "bool": False}
    _srcfile: Callable[[str], str] = staticmethod(_basename)

    class Group:
        """A group of parameters (the top one is "Default", id 0); groups nest."""

        def __init__(self, gen: ParameterGenerator, name: str, type: str, state: bool, id: int, parent: int,
                     where: FrameType | None = None) -> None:
            self.name = name.replace(" ", "_")
            self.type = type
            self.groups: list[ParameterGenerator.Group] = []
            self.parameters: list[dict[str, Any]] = []
            self.gen = gen
            self.id = id
            self.parent = parent
            self.state = state
            self.srcline, self.srcfile = _source_of(where or _caller_frame(), gen._srcfile)
            gen.groups_by_id[id] = self

        def get_group(self, id: int) -> ParameterGenerator.Group:
            """The group of this generator with *id*."""
            return self.gen.groups_by_id[id]

        def add_group(self, name: str, type: str = "", state: bool = True) -> ParameterGenerator.Group:
            """A new subgroup (ids count up from 1 in the order groups are made)."""
            group = ParameterGenerator.Group(self.gen, name, type, state, self.gen.next_group_id, self.id,
                                             where=inspect.currentframe())
            self.gen.next_group_id += 1
            self.groups.append(group)
            return group

        def add(self, name: str, paramtype: str, level: int, description: str, default: Any = None,
                min: Any = None, max: Any = None, edit_method: str = "") -> None:
            """Add a parameter to this group (its type one of ``int_t``, ``double_t``, ``str_t``, ``bool_t``)."""
            srcline, srcfile = _source_of(_caller_frame(), self.gen._srcfile)
            param = {
                "name": name, "type": paramtype, "default": default, "level": level, "description": description,
                "min": min, "max": max, "srcline": srcline, "srcfile": srcfile, "edit_method": edit_method,
            }
            if paramtype in (str_t, bool_t) and (max is not None or min is not None):
                raise Exception(f"Max or min specified for {name}, which is of '{paramtype}' type")
            check_name(name)
            self.gen.fill_type(param)
            self.gen.check_type_fill_default(param, "default", self.gen.defval[paramtype])
            self.gen.check_type_fill_default(param, "max", self.gen.maxval[paramtype])
            self.gen.check_type_fill_default(param, "min", self.gen.minval[paramtype])
            self.parameters.append(param)

        def get_parameters(self) -> list[dict[str, Any]]:
            """This group's parameters, then its subgroups', depth first."""
            params = list(self.parameters)
            for group in self.groups:
                params.extend(group.get_parameters())
            return params

        def get_parents(self) -> list[str]:
            """The names from the top group down to this one."""
            if self.id == 0:
                return [self.name]
            return [*self.get_group(self.parent).get_parents(), self.name]

        def get_field(self) -> str:
            """The C++ member path of this group (ancestors upper case, itself lower case)."""
            return "::".join(x.lower() if x == self.name else x.upper() for x in self.get_parents())

        def get_class(self, parent: bool = False) -> str:
            """The C++ class path of this group (or of its parent)."""
            names = [x.upper() for x in self.get_parents()]
            return "::".join(names[:-1] if parent else names)

        def to_dict(self) -> dict[str, Any]:
            """This group as the generated module's ``config_description`` holds it."""
            return {
                "name": self.name,
                "type": self.type,
                "state": self.state,
                "cstate": "true" if self.state else "false",
                "id": self.id,
                "parent": self.parent,
                "parameters": self.parameters,
                "groups": [group.to_dict() for group in self.groups],
                "srcline": self.srcline,
                "srcfile": self.srcfile,
                "class": self.get_class(),
                "parentclass": self.get_class(parent=True),
                "parentname": self.get_group(self.parent).name,
                "field": self.get_field(),
                "upper": self.name.upper(),
                "lower": ("groups" if self.id == 0 else self.name).lower(),
            }

    def __init__(self) -> None:
        self.groups_by_id: dict[int, ParameterGenerator.Group] = {}
        self.group = self.Group(self, "Default", "", True, 0, 0, where=inspect.currentframe())
        self.next_group_id = 1
        self.constants: list[dict[str, Any]] = []
        self.pkgname = self.name = self.nodename = self.msgname = ""
        if _capture is None:
            self._take_arguments()

    def _take_arguments(self) -> None:
        if len(sys.argv) < 5:
            raise SystemExit(USAGE)
        self.dynconfpath, self.binary_dir, self.cpp_gen_dir, self.py_gen_dir = sys.argv[1:5]

    @staticmethod
    def pytype(drtype: str) -> type:
        """The Python type of a parameter type name."""
        return _PYTYPES[drtype]

    def check_type(self, param: dict[str, Any], field: str) -> None:
        """Refuse a value of the wrong type in ``param[field]``; an int for a double becomes a float."""
        pytype: Any = self.pytype(param["type"])
        value = param[field]
        if pytype is not type(value) and not (pytype is float and type(value) is int):
            raise TypeError(f"'{param['name']}' has type {param['type']}, but {field} is {value!r}")
        param[field] = pytype(value)

    @staticmethod
    def fill_type(param: dict[str, Any]) -> None:
        """Add the C++ types of a parameter or constant."""
        param["ctype"] = _CTYPES[param["type"]]
        param["cconsttype"] = _CCONSTTYPES[param["type"]]

    def check_type_fill_default(self, param: dict[str, Any], field: str, default: Any) -> None:
        """Give ``param[field]`` its default when missing, else check its type."""
        if param[field] is None:
            param[field] = default
        else:
            self.check_type(param, field)

    def const(self, name: str, type: str, value: Any, descr: str) -> dict[str, Any]:
        """A named constant (for enums and for the module's ``<Name>_<const>``)."""
        srcline, srcfile = _source_of(_caller_frame(), self._srcfile)
        constant = {"name": name, "type": type, "value": value, "srcline": srcline, "srcfile": srcfile,
                    "description": descr}
        check_description(descr)
        self.fill_type(constant)
        self.check_type(constant, "value")
        self.constants.append(constant)
        return constant

    @staticmethod
    def enum(constants: list[dict[str, Any]], description: str) -> str:
        """An enum of constants of one type, as the ``edit_method`` string of a parameter."""
        if len({c["type"] for c in constants}) != 1:
            raise Exception("Inconsistent types in enum!")
        check_description(description)
        return repr({"enum": constants, "enum_description": description})

    def add(self, name: str, paramtype: str, level: int, description: str, default: Any = None,
            min: Any = None, max: Any = None, edit_method: str = "") -> None:
        """Add a parameter to the top group."""
        self.group.add(name, paramtype, level, description, default, min, max, edit_method)

    def add_group(self, name: str, type: str = "", state: bool = True) -> ParameterGenerator.Group:
        """A new group under the top group."""
        return self.group.add_group(name, type=type, state=state)

    def generate(self, pkgname: str, nodename: str, name: str) -> None:
        """Make the ``<name>Config`` module: kept in memory while rostui imports it, else written to disk."""
        self.pkgname, self.nodename, self.name, self.msgname = pkgname, nodename, name, name + "Config"
        if _capture is not None:
            _capture.append(self)
            return
        print(f"Generating reconfiguration files for {name} in {pkgname}")
        try:
            self._write(self._output_dir())
        except Exception:
            print(f"Error building srv {name}.srv")
            import traceback

            traceback.print_exc()
            sys.exit(1)

    def _output_dir(self) -> str:
        return os.path.join(self.py_gen_dir, "cfg")

    def _write(self, folder: str) -> None:
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, self.msgname + ".py"), "w", encoding="utf-8") as f:
            f.write(module_source(self))
        with open(os.path.join(folder, "__init__.py"), "a", encoding="utf-8"):
            pass


def module_source(gen: ParameterGenerator) -> str:
    """The text of the ``<Name>Config`` module of a generator that has run ``generate``."""
    lines = [
        "## " + "*" * 57,
        "##",
        f"## File autogenerated for the {gen.pkgname} package",
        "## by the dynamic_reconfigure package.",
        "## Please do not edit.",
        "##",
        "## " + "*" * 56 + "/",
        "",
        "from dynamic_reconfigure.encoding import extract_params",
        "",
        "inf = float('inf')",
        "",
        f"config_description = {gen.group.to_dict()!r}",
        "",
        "min = {}",
        "max = {}",
        "defaults = {}",
        "level = {}",
        "type = {}",
        "all_level = 0",
        "",
        "for param in extract_params(config_description):",
        "    min[param['name']] = param['min']",
        "    max[param['name']] = param['max']",
        "    defaults[param['name']] = param['default']",
        "    level[param['name']] = param['level']",
        "    type[param['name']] = param['type']",
        "    all_level = all_level | param['level']",
        "",
    ]
    lines += [f"{gen.name}_{c['name']} = {c['value']!r}" for c in gen.constants]
    return "\n".join(lines) + "\n"

