"""``<pkg>.cfg.<Name>Config`` from a package's ``cfg/<Name>.cfg``, made when it is imported (rostui's own).

catkin runs each ``.cfg`` file at build time and installs the module it writes. rostui has no build: the
import hook (:mod:`rostui.compat.finder`) asks here, and the ``.cfg`` file is run with the generator in
capture mode, which hands over the module's text instead of writing files. The module belongs to the
package whose ``cfg`` folder holds the file, whatever ``PACKAGE`` the file names, as with catkin.
An error in the file is an ImportError naming the file and line.
"""

from __future__ import annotations

import builtins
import threading
import traceback
from pathlib import Path

from rostui.core import packages

from . import parameter_generator_catkin as generator

__all__ = ["CfgError", "cfg_files", "config_module", "config_names"]

SUFFIX = "Config"
"""What the generator appends to a ``.cfg`` file's name to name its module."""
_running = threading.Lock()


class CfgError(ImportError):
    """A ``.cfg`` file that could not be run, or that does not make the module asked for."""


def cfg_files(package: str) -> list[Path]:
    """The ``.cfg`` files of *package* (``<dir>/cfg/*.cfg`` of each of its directories), sorted by name."""
    return packages.package_files(package, "cfg", "*.cfg")


def config_names(package: str) -> list[str]:
    """The module names *package*'s ``.cfg`` files give by their file names (``Test.cfg`` gives ``TestConfig``)."""
    return [path.stem + SUFFIX for path in cfg_files(package)]


def _where(exc: BaseException, path: Path) -> str:
    """``file:line`` of the deepest frame of *exc*'s traceback inside *path* (the file alone if none)."""
    line = None
    for frame in traceback.extract_tb(exc.__traceback__):
        if frame.filename == str(path):
            line = frame.lineno
    return f"{path}:{line}" if line is not None else str(path)


def run_cfg(path: Path) -> list[generator.ParameterGenerator]:
    """Run the ``.cfg`` file at *path* and return the generators that called ``generate``, in order."""
    try:
        code = compile(path.read_bytes(), str(path), "exec")
    except (OSError, SyntaxError, ValueError) as exc:
        raise CfgError(f"cannot read {_where(exc, path)}: {exc}") from exc
    namespace = {"__name__": "__main__", "__file__": str(path), "__builtins__": builtins}
    with _running:
        made: list[generator.ParameterGenerator] = []
        generator._capture = made
        try:
            exec(code, namespace)  # noqa: S102 (the package's own .cfg script, as catkin runs it)
        except SystemExit:
            pass
        except Exception as exc:
            raise CfgError(f"{_where(exc, path)}: {type(exc).__name__}: {exc}") from exc
        finally:
            generator._capture = None
    return made


def config_module(package: str, module: str) -> tuple[str, Path]:
    """The source of ``<package>.cfg.<module>`` and the ``.cfg`` file it comes from; CfgError when none makes it."""
    if not module.endswith(SUFFIX):
        raise CfgError(f"{package}.cfg.{module}: generated modules are named <Name>{SUFFIX}")
    wanted = module[: -len(SUFFIX)]
    # Name.cfg first: it makes NameConfig as a rule, and its errors are the user's to see; a file named
    # otherwise may generate it too, and its errors are not the point.
    for path in sorted(cfg_files(package), key=lambda p: p.stem != wanted):
        try:
            made = run_cfg(path)
        except CfgError:
            if path.stem == wanted:
                raise
            continue
        for gen in made:
            if gen.name == wanted:
                return generator.module_source(gen), path
    raise CfgError(f"no .cfg file of package {package} generates {module}")
