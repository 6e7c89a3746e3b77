"""`rostui run PKG EXE [args...]`: find an executable in a package and replace this process with it.

Behaves like rosrun: the executable is any file named EXE with an execute bit
below the package directory (``build/`` excluded; catkin's ``<prefix>/lib/<pkg>``
searched too); ``EXE`` containing ``/`` is a path relative to the package.
Arguments are passed through untouched.  Differences, by design: a ``.py`` file
without execute bit is run with this Python, Python scripts of rostui's built-in
packages and Python scripts that import rostui always run with this Python, and
rosrun's error lines go to stderr.  Other Python scripts are found here
(:func:`ros_python_script`) and started by the command line the way ``rostui
python`` starts a script (:mod:`rostui.compat.launcher`), which this layer cannot import.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Mapping, Sequence, TextIO

from rostui.core import packages

__all__ = ["RunError", "resolve", "locate", "argv_for", "runs_with_this_python", "RosPythonScript", "ros_python_script", "choose_interactively", "exec_argv"]

#: rosrun's exit codes.
EXIT_BAD_NAME = 1
EXIT_NO_PACKAGE = 2
EXIT_NO_EXECUTABLE = 3


class RunError(Exception):
    """The executable cannot be run; ``lines`` are the message, ``code`` the exit status."""

    def __init__(self, lines: list[str], code: int) -> None:
        """Keep the message lines and the exit code."""
        super().__init__("\n".join(lines))
        self.lines = lines
        self.code = code


def argv_for(path: Path, args: Sequence[str], prefix: str | None) -> list[str]:
    """The argv that starts *path*: Python files of built-in packages and non-executable .py use this Python."""
    argv: list[str]
    if runs_with_this_python(path):
        argv = [sys.executable, str(path), *args]
    else:
        argv = [str(path), *args]
    if prefix:
        argv = shlex.split(prefix) + argv
    return argv


_SCRIPT_HEAD = 64 * 1024
"""Bytes of a script read to find its ``#!`` line and whether it imports rostui."""
_IMPORTS_ROSTUI = re.compile(rb"^\s*(?:from\s+rostui[\s.]|import\s+rostui\b)", re.MULTILINE)


def _head(path: Path) -> bytes | None:
    try:
        with path.open("rb") as fh:
            return fh.read(_SCRIPT_HEAD)
    except OSError:
        return None


def _names_python(head: bytes) -> bool:
    return head.startswith(b"#!") and b"python" in head.split(b"\n", 1)[0]


def _is_rostui_program(path: Path, head: bytes) -> bool:
    """A built-in package's program, or a script importing rostui: it needs rostui's own Python as it is."""
    try:
        inside_share = path.resolve().is_relative_to(packages.BUILTIN_SHARE)
    except OSError:
        return False
    return inside_share or _IMPORTS_ROSTUI.search(head) is not None


def runs_with_this_python(path: Path) -> bool:
    """True for Python programs that need rostui's Python: built-in packages' scripts, non-executable .py files,
    and scripts that import rostui (whatever their ``#!`` line names, it may not have rostui installed)."""
    if not packages.is_executable_file(path):
        return True  # only .py files get here
    head = _head(path)
    if head is None or (not _names_python(head) and path.suffix != ".py"):
        return False
    return _is_rostui_program(path, head)


@dataclass(frozen=True)
class RosPythonScript:
    """A package's Python script written for ROS 1's rospy (not one of rostui's own programs).

    ``interpreter`` is what its ``#!`` line names, found on ``PATH``; None when
    it has none (a ``.py`` file without execute bit) or that program is not found.
    """

    path: Path
    interpreter: str | None


def ros_python_script(path: Path, search_path: str | None = None) -> RosPythonScript | None:
    """*path* as a :class:`RosPythonScript` when it is a Python script that is not rostui's own, else None.

    Python scripts are ``.py`` files without execute bit and executables whose
    ``#!`` line names python; *search_path* is the ``PATH`` its interpreter is looked up on.
    """
    executable = packages.is_executable_file(path)
    if not executable and path.suffix != ".py":
        return None
    head = _head(path)
    if head is None or _is_rostui_program(path, head):
        return None
    if not executable:
        return RosPythonScript(path, None)
    if not _names_python(head):
        return None
    return RosPythonScript(path, _interpreter(head.split(b"\n", 1)[0][2:], search_path))


def _interpreter(line: bytes, search_path: str | None) -> str | None:
    """The program a ``#!`` line runs the script with (``env``'s argument looked up on *search_path*)."""
    try:
        words = shlex.split(line.decode("utf-8", "replace"))
    except ValueError:
        return None
    if words and os.path.basename(words[0]) == "env":
        words = [w for w in words[1:] if not w.startswith("-") and "=" not in w]
    if not words:
        return None
    found = shutil.which(words[0], path=search_path) if os.sep not in words[0] else words[0]
    return found if found and os.access(found, os.X_OK) else None


def resolve(package: str, executable: str, args: Sequence[str] = (), *, prefix: str | None = None,
            choose: Callable[[list[Path]], Path | None] | None = None) -> list[str]:
    """The argv that runs *executable* of *package* with *args*; raises :class:`RunError`.

    *choose* picks one of several matches (rosrun's numbered prompt); without
    it several matches are an error listing them, and so is a None answer.
    """
    return argv_for(locate(package, executable, choose=choose), args, prefix)


def locate(package: str, executable: str, *,
           choose: Callable[[list[Path]], Path | None] | None = None) -> Path:
    """The file that is *executable* of *package*, found as :func:`resolve` finds it; raises :class:`RunError`."""
    if executable.endswith("/"):
        raise RunError([f"Invalid filename:  {executable}"], EXIT_BAD_NAME)
    try:
        pkg_dir = packages.get_package_path(package)
    except packages.PackageNotFoundError:
        raise RunError([f"[rospack] Error: package '{package}' not found"], EXIT_NO_PACKAGE) from None
    if "/" in executable:
        path = pkg_dir / executable
        if path.is_file() and (packages.is_executable_file(path) or path.suffix == ".py"):
            return path
        raise RunError([f"[rosrun] Couldn't find executable named {path}"], EXIT_NO_EXECUTABLE)
    found, others = packages.find_executables(package, executable)
    if not found:
        scripts = [p for p in others if p.suffix == ".py" and p.is_file()]
        if scripts:
            found = scripts
    if not found:
        lines = [f"[rosrun] Couldn't find executable named {executable} below {pkg_dir}"]
        if others:
            lines += ["[rosrun] Found the following, but they're either not files,",
                      "[rosrun] or not executable:"]
            lines += [f"[rosrun]   {p}" for p in others]
        raise RunError(lines, EXIT_NO_EXECUTABLE)
    if len(found) == 1:
        return found[0]
    if choose is None:
        raise RunError(["[rosrun] You have chosen a non-unique executable, please pick one of the following:",
                        *(f"[rosrun]   {p}" for p in found)], EXIT_NO_EXECUTABLE)
    picked = choose(found)
    if picked is None:
        raise RunError(["[rosrun] No executable chosen"], EXIT_NO_EXECUTABLE)
    return picked


def choose_interactively(candidates: list[Path], stdin: TextIO | None = None,
                         stderr: TextIO | None = None) -> Path | None:
    """rosrun's prompt: the header, a numbered list and ``#? ``; None on EOF or a bad answer."""
    stdin = stdin or sys.stdin
    stderr = stderr or sys.stderr
    print("[rosrun] You have chosen a non-unique executable, please pick one of the following:",
          file=stderr)
    for i, p in enumerate(candidates, 1):
        print(f"{i}) {p}", file=stderr)
    stderr.write("#? ")
    stderr.flush()
    line = stdin.readline()
    if not line:
        stderr.write("\n")
    answer = line.strip()
    if answer.isdigit() and 1 <= int(answer) <= len(candidates):
        return candidates[int(answer) - 1]
    return None


def exec_argv(argv: list[str], env: Mapping[str, str] | None = None) -> None:
    """Replace this process with *argv* (signals and exit status become the child's), in *env* if given.

    A script without ``#!`` line is run by ``/bin/sh``, as a shell's ``exec`` does.
    Returns only by raising OSError.
    """
    sys.stdout.flush()
    sys.stderr.flush()
    environ = os.environ if env is None else env
    try:
        os.execvpe(argv[0], argv, environ)
    except OSError as exc:
        import errno

        if exc.errno == errno.ENOEXEC:
            os.execve("/bin/sh", ["/bin/sh", *argv], environ)
        raise
