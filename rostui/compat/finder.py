"""The import hook: ``<pkg>``, ``<pkg>.msg``, ``<pkg>.srv`` (and genpy's ``<pkg>.msg._Name``) from rostui's types.

Every ROS package rostui knows (``ROS_PACKAGE_PATH``, then the built-in ones)
that defines messages or services becomes importable. The classes are
rostui's own generated ones (:func:`rostui.core.msg.get_message_class`), built
on first use; a module's ``__getattr__`` builds them, so ``import std_msgs.msg``
costs nothing until a class is named. A package's other Python modules that
rostui writes (``sensor_msgs.point_cloud2``) live in :data:`~rostui.compat.PKGPY`,
found through the package's ``__path__``. The finder sits last on
``sys.meta_path``: a package that is really installed is found first, unless
the user chose rostui's modules over a real ROS (then it sits first).
"""

from __future__ import annotations

import importlib
import importlib.machinery
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any

from rostui.compat import PKGPY, PYLIB
from rostui.core import packages
from rostui.core.msg.action import split_action_type
from rostui.core.msg import (
    MessageError,
    get_message_class,
    get_service_class,
    list_message_types,
    list_service_types,
)

__all__ = ["MessageModuleFinder", "install", "message_names", "service_names"]

_KINDS = ("msg", "srv")
CFG = "cfg"
"""The subpackage of a ROS package that holds its dynamic_reconfigure modules (``<pkg>.cfg.<Name>Config``)."""


def message_names(package: str) -> list[str]:
    """The short names of *package*'s message types (empty when the package is unknown)."""
    try:
        return [t.rpartition("/")[2] for t in list_message_types(package)]
    except packages.PackageNotFoundError:
        return []


def service_names(package: str) -> list[str]:
    """The short names of *package*'s service types (empty when the package is unknown)."""
    try:
        return [t.rpartition("/")[2] for t in list_service_types(package)]
    except packages.PackageNotFoundError:
        return []


ROS_PYTHON_NOT_PROVIDED = frozenset({
    "PyKDL", "angles", "image_geometry",
    "interactive_markers", "kdl_parser_py", "laser_geometry", "moveit_commander", "roslaunch",
    "rosmsg", "rosnode", "rosparam", "smach", "smach_ros", "sound_play",
    "tf_conversions", "topic_tools", "urdf_parser_py", "xacro",
})
"""ROS 1 Python modules scripts import that rostui python does not provide (yet): importing one says so and
where to read which modules there are, unless a real one is installed."""

DEBIAN_PYTHON = Path("/usr/lib/python3/dist-packages")
"""Where Debian installs ROS packages' Python modules."""
_MESSAGE_ONLY = {"msg", "srv", "__init__.py", "__pycache__"}


def own_python(package: str) -> Path | None:
    """The package's own Python package in its source tree (``<pkg>/src/<pkg>/__init__.py``, as catkin builds it)."""
    try:
        root = packages.find_package(package)
    except OSError:
        return None
    if root is None:
        return None
    candidate = root / "src" / package
    return candidate if (candidate / "__init__.py").is_file() else None


def _python_module_name(entry: Path) -> str | None:
    """The top-level module *entry* is (``name.py`` or a folder with ``__init__.py``), or None."""
    if entry.suffix == ".py" and entry.is_file():
        return entry.stem
    return entry.name if (entry / "__init__.py").is_file() else None


_workspace_modules: tuple[str, dict[str, Path]] | None = None


def workspace_python(module: str) -> Path | None:
    """The ``src`` folder of a package that holds the top-level Python module *module* under another name
    (navigation's ``base_local_planner/src/local_planner_limits``), as a catkin workspace puts every package's
    ``src`` Python on the path; None when no package has it. The map is made once per ROS_PACKAGE_PATH."""
    global _workspace_modules
    key = os.environ.get("ROS_PACKAGE_PATH", "")
    if _workspace_modules is None or _workspace_modules[0] != key:
        found: dict[str, Path] = {}
        for root in packages.list_packages().values():
            src = root / "src"
            try:
                entries = sorted(src.iterdir())
            except OSError:
                continue
            for entry in entries:
                name = _python_module_name(entry)
                if name is not None:
                    found.setdefault(name, src)
        _workspace_modules = (key, found)
    return _workspace_modules[1].get(module)


def python_elsewhere(package: str) -> bool:
    """Whether Debian's install of ``package`` has Python modules besides its messages that rostui lacks
    (``sensor_msgs.point_cloud2`` is rostui's, in :data:`~rostui.compat.PKGPY`)."""
    try:
        ours = {entry.name for entry in (PKGPY / package).iterdir()} if (PKGPY / package).is_dir() else set()
        return any(entry.name not in _MESSAGE_ONLY and entry.name not in ours
                   for entry in (DEBIAN_PYTHON / package).iterdir())
    except OSError:
        return False


def _lacks_python(package: str) -> bool:
    """Whether ``package`` has a Python API in ROS that rostui python does not give (its messages aside)."""
    if (PYLIB / package).is_dir() or own_python(package) is not None:
        return False
    return package in ROS_PYTHON_NOT_PROVIDED or python_elsewhere(package)


def _not_provided(name: str, what: str) -> ModuleNotFoundError:
    return ModuleNotFoundError(f"No module named '{name}': rostui python {what}; docs/rospy.md lists the modules "
                               "rostui provides", name=name)


def _names(package: str, kind: str) -> list[str]:
    return message_names(package) if kind == "msg" else service_names(package)


def _has_types(package: str, kind: str) -> bool:
    """Whether ``_names(package, kind)`` is not empty, asking no more directories of *package* than it must
    (the built-in copy of a package answers without Debian's 200 folders of /usr/share being listed)."""
    suffixes = (".msg", ".action") if kind == "msg" else (".srv",)
    for root in packages.iter_package_dirs(package):
        for folder, suffix in zip((kind, "action"), suffixes):
            try:
                if any(entry.endswith(suffix) and not entry.startswith(".") for entry in os.listdir(root / folder)):
                    return True
            except OSError:
                continue
    return False


def _has_name(package: str, kind: str, name: str) -> bool:
    """Whether *name* is in ``_names(package, kind)``, asking no more directories of *package* than it must."""
    if not name.isidentifier():
        return False
    actions = split_action_type(name) if kind == "msg" else []
    for root in packages.iter_package_dirs(package):
        if (root / kind / f"{name}.{kind}").exists():
            return True
        if any((root / "action" / f"{action}.action").exists() for action in actions):
            return True
    return False


def _expose(cls: type, package: str, kind: str, name: str) -> type:
    """Give *cls* the module genpy's class of the same type has (``std_msgs.msg._String``), and import the message
    modules of the packages its fields use, as genpy's module does (so ``std_msgs.msg`` is an attribute of
    ``std_msgs`` once ``diagnostic_msgs.msg.DiagnosticArray`` is loaded, which scripts rely on)."""
    cls.__module__ = f"{package}.{kind}._{name}"
    for half in (cls, getattr(cls, "_request_class", None), getattr(cls, "_response_class", None)):
        for field_type in getattr(half, "_slot_types", ()):
            used = field_type.split("[", 1)[0].partition("/")[0] if "/" in field_type else ""
            if used and used != package and used.isidentifier():
                try:
                    importlib.import_module(f"{used}.msg")
                except ImportError:
                    pass  # the class was built, so the type is known; its module is only a convenience
    return cls


def _lookup(package: str, kind: str, attr: str) -> type | None:
    """The class *attr* of ``<package>.<kind>``, or None when there is none."""
    try:
        if kind == "msg":
            return _expose(get_message_class(f"{package}/{attr}"), package, kind, attr) \
                if _has_name(package, kind, attr) else None
        if _has_name(package, kind, attr):
            return _expose(get_service_class(f"{package}/{attr}"), package, kind, attr)
        for suffix, half in (("Request", "_request_class"), ("Response", "_response_class")):
            base = attr[: -len(suffix)]
            if attr.endswith(suffix) and _has_name(package, kind, base):
                cls: type = getattr(get_service_class(f"{package}/{base}"), half)
                return _expose(cls, package, kind, base)
    except MessageError as exc:
        raise ImportError(f"cannot build {package}/{attr}: {exc}") from exc
    return None


def _srv_attrs(names: Sequence[str]) -> list[str]:
    return [n + s for n in names for s in ("", "Request", "Response")]


def _module_getattr(module: ModuleType, package: str, kind: str, only: str | None,
                    public: Callable[[], list[str]]) -> Callable[[str], Any]:
    def __getattr__(attr: str) -> Any:
        if attr == "__all__":  # listed when first asked (``import *``): a class import lists no directory
            names = public()
            module.__all__ = names  # type: ignore[attr-defined]
            return names
        if not attr.startswith("__") and (only is None or attr in (only, only + "Request", only + "Response")):
            cls = _lookup(package, kind, attr)
            if cls is not None:
                setattr(module, attr, cls)
                return cls
        raise AttributeError(f"module {module.__name__!r} has no attribute {attr!r}")

    return __getattr__


if TYPE_CHECKING:
    from importlib.abc import Loader as _LoaderBase
else:
    _LoaderBase = object


class _BareLoader(_LoaderBase):
    """The loader protocol's default module creation (importlib.abc.Loader's, whose import loads
    importlib.resources, tempfile and shutil: a megabyte of a small node's memory)."""

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType | None:
        """None: the import system makes the module."""
        return None


class _Loader(_BareLoader):
    """Fills the module a :class:`MessageModuleFinder` spec names."""

    def __init__(self, package: str, kind: str | None, only: str | None, own: Path | None = None) -> None:
        self.package, self.kind, self.only, self.own = package, kind, only, own

    def exec_module(self, module: ModuleType) -> None:
        """Give the package module its kinds (or run the package's own ``__init__.py``), and a kind module its
        (lazily built) classes."""
        module.__file__ = None
        if self.kind is None:
            module.__doc__ = f"ROS package {self.package} (message and service modules served by rostui)."
            if self.own is not None:
                init = self.own / "__init__.py"
                module.__file__ = str(init)
                exec(compile(init.read_bytes(), str(init), "exec"), module.__dict__)  # noqa: S102 (the package's own code)
            return
        package, kind, only = self.package, self.kind, self.only

        def public() -> list[str]:
            names = _names(package, kind) if only is None else [only]
            return _srv_attrs(names) if kind == "srv" else list(names)

        module.__doc__ = f"{package}.{kind}: ROS {kind} types of {package} (generated by rostui)."
        module.__getattr__ = _module_getattr(module, package, kind, only, public)  # type: ignore[method-assign]
        module.__dir__ = lambda: sorted(set(public()) | set(module.__dict__))  # type: ignore[method-assign]


class _CfgLoader(_BareLoader):
    """Fills ``<pkg>.cfg`` (a package listing its ``.cfg`` modules) or ``<pkg>.cfg.<Name>Config`` (from the file)."""

    def __init__(self, package: str, module: str | None) -> None:
        self.package, self.module = package, module

    def exec_module(self, module: ModuleType) -> None:
        """Run the generated source of a ``<Name>Config`` module into *module*, or list the package's names.

        The generator is rostui's ``dynamic_reconfigure``; with a real one imported instead (whose packages'
        modules come from their catkin build) this fails with ModuleNotFoundError."""
        cfg = importlib.import_module("dynamic_reconfigure.cfg_modules")
        if self.module is None:
            module.__doc__ = f"{self.package}.cfg: dynamic_reconfigure modules of {self.package}'s .cfg files."
            module.__all__ = cfg.config_names(self.package)  # type: ignore[attr-defined]
            return
        source, path = cfg.config_module(self.package, self.module)
        module.__file__ = str(path)
        exec(compile(source, f"<{self.module} generated from {path}>", "exec"), module.__dict__)  # noqa: S102


def _has_cfg(package: str) -> bool:
    """Whether *package* has ``.cfg`` files (``<dir>/cfg/*.cfg``) rostui can turn into modules."""
    return bool(packages.package_files(package, CFG, "*.cfg"))


def _cfg_spec(fullname: str, package: str, module: str | None) -> importlib.machinery.ModuleSpec | None:
    """A spec for ``<pkg>.cfg`` or ``<pkg>.cfg.<Name>Config`` when *package* has ``.cfg`` files."""
    if not _has_cfg(package):
        return None
    return importlib.machinery.ModuleSpec(fullname, _CfgLoader(package, module), is_package=module is None)


class MessageModuleFinder:
    """Finds ``<pkg>``, ``<pkg>.msg``, ``<pkg>.srv`` and ``<pkg>.<kind>._<Name>`` for rostui's packages."""

    def find_spec(self, fullname: str, path: Sequence[str] | None,
                  target: ModuleType | None = None) -> importlib.machinery.ModuleSpec | None:
        """A spec when *fullname* names message or service modules rostui can serve; None otherwise."""
        parts = fullname.split(".")
        package = parts[0]
        if len(parts) > 3 or not package.isidentifier():
            return None
        if len(parts) == 1:
            if (PYLIB / package).is_dir():
                return None  # rostui writes this package's Python (tf, actionlib...): its own __init__ is the module
            own = own_python(package)
            if not (_has_types(package, "msg") or _has_types(package, "srv") or own is not None
                    or _has_cfg(package)):
                elsewhere = workspace_python(package)
                if elsewhere is not None:
                    return importlib.machinery.PathFinder.find_spec(fullname, [str(elsewhere)])
                if package in ROS_PYTHON_NOT_PROVIDED and importlib.machinery.PathFinder.find_spec(package) is None:
                    raise _not_provided(package, "does not provide this ROS module yet")
                return None
            return self._spec(fullname, package, None, None, own)
        kind = parts[1]
        if kind == CFG:
            return _cfg_spec(fullname, package, parts[2] if len(parts) == 3 else None)
        if kind not in _KINDS and len(parts) == 2 and _lacks_python(package) \
                and importlib.machinery.PathFinder.find_spec(fullname, path) is None:
            raise _not_provided(fullname, f"serves {package}'s messages ({package}.msg) but not its Python modules")
        if kind not in _KINDS or not _has_types(package, kind):
            return None
        if len(parts) == 2:
            return self._spec(fullname, package, kind, None)
        name = parts[2][1:]
        if not parts[2].startswith("_") or not _has_name(package, kind, name):
            return None
        return self._spec(fullname, package, kind, name)

    @staticmethod
    def _spec(fullname: str, package: str, kind: str | None, only: str | None,
              own: Path | None = None) -> importlib.machinery.ModuleSpec:
        spec = importlib.machinery.ModuleSpec(fullname, _Loader(package, kind, only, own), is_package=only is None)
        if only is None:
            places = [own] if own is not None else []
            if kind is None and (PKGPY / package).is_dir():
                places.append(PKGPY / package)
            spec.submodule_search_locations = [str(p) for p in places] if kind is None else []
            if own is not None:
                spec.origin = str(own / "__init__.py")
                spec.has_location = True
        return spec


def install(first: bool = False) -> MessageModuleFinder:
    """Put the finder on ``sys.meta_path`` (once) and return it.

    Last by default, so installed packages win; *first* when the user chose
    rostui's modules over a real ROS whose message packages are importable.
    """
    for finder in sys.meta_path:
        if isinstance(finder, MessageModuleFinder):
            sys.meta_path.remove(finder)
            break
    else:
        finder = MessageModuleFinder()
    if first:
        sys.meta_path.insert(0, finder)
    else:
        sys.meta_path.append(finder)
    return finder
