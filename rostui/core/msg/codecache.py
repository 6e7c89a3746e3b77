"""A cache on disk of the compiled code of generated message classes, so a node's start skips ``compile()``.

Building a message class is generating its Python source (cheap) and compiling
it (three quarters of the cost: 6-8 ms for the classes every rospy node builds
at start, rosgraph_msgs/Log and roscpp's logger services). This cache keeps the
compiled code, marshalled, under a key that hashes the source itself with its
file name and the interpreter's bytecode version: the source is generated
afresh from the current definitions each time, so a changed definition (or a
changed code generator) makes another key and never meets a stale class.

The cache is off until :func:`use_directory` names a folder (a script's
interpreter does, :mod:`rostui.compat.bootstrap`: ``$ROS_HOME/rostui/msg_code``,
see :func:`default_directory`). It never breaks a build: a folder that cannot
be read or written means compiling as before; an entry that is short, too big,
fails its checksum or is not code is ignored (and replaced). Entries are written
to a temporary file and renamed into place, and the folder holds at most
:data:`MAX_ENTRIES` of them (the oldest go first).
"""

from __future__ import annotations

import marshal
import os
import sys
import types
from collections.abc import Mapping
from pathlib import Path

try:
    from _md5 import md5  # type: ignore[import-not-found]  # CPython's own: hashlib's loads OpenSSL
except ImportError:  # a Python built without it
    from hashlib import md5

__all__ = ["ENV_CACHE", "MAX_ENTRIES", "MAX_ENTRY_BYTES", "compile_source", "default_directory", "directory",
           "use_directory"]

ENV_CACHE = "ROSTUI_MSG_CACHE"
"""Environment variable: a folder for the cache, or ``off`` (also ``0`` or ``no``) for none."""

MAX_ENTRIES = 512
"""Entries the folder keeps at most; a write past it removes the oldest quarter."""

MAX_ENTRY_BYTES = 1 << 20
"""Largest entry written or read (a message's code is a few to a few hundred kilobytes)."""

_MAGIC = b"rostui-msg-code-1\n"
_SUFFIX = ".code"
_DIGEST = 16

_directory: Path | None = None


def _bytecode_tag() -> str:
    from importlib.util import MAGIC_NUMBER

    return f"{sys.implementation.cache_tag}-{MAGIC_NUMBER.hex()}"


def default_directory(env: Mapping[str, str] | None = None) -> Path | None:
    """The folder :data:`ENV_CACHE` names, else ``$ROS_HOME/rostui/msg_code`` (``~/.ros`` without ROS_HOME);
    None when the variable turns the cache off."""
    env = os.environ if env is None else env
    chosen = env.get(ENV_CACHE, "")
    if chosen.strip().lower() in ("off", "0", "no", "false"):
        return None
    if chosen:
        return Path(chosen).expanduser()
    home = env.get("ROS_HOME")
    root = Path(home) if home else Path(os.path.expanduser("~")) / ".ros"
    return root / "rostui" / "msg_code"


def use_directory(folder: Path | None) -> None:
    """Keep compiled message code in *folder* (made when first written), or nowhere (None, the default)."""
    global _directory
    _directory = None if folder is None else Path(folder) / _bytecode_tag()


def directory() -> Path | None:
    """The folder entries are read from and written to now (under the one :func:`use_directory` named), or None."""
    return _directory


def compile_source(source: str, filename: str) -> types.CodeType:
    """``compile(source, filename, "exec")``, taken from the cache when it holds this very source's code."""
    folder = _directory
    if folder is None:
        return compile(source, filename, "exec")
    key = md5(f"{filename}\0{source}".encode("utf-8", "surrogatepass")).hexdigest()
    path = folder / (key + _SUFFIX)
    code = _read(path)
    if code is None:
        code = compile(source, filename, "exec")
        _write(folder, path, code)
    return code


def _read(path: Path) -> types.CodeType | None:
    """The code in entry *path*, or None when there is none or it is not whole."""
    try:
        with open(path, "rb") as file:
            data = file.read(MAX_ENTRY_BYTES + 1)
    except (OSError, ValueError):
        return None
    head = len(_MAGIC) + _DIGEST
    if len(data) > MAX_ENTRY_BYTES or len(data) <= head or not data.startswith(_MAGIC):
        return None
    payload = data[head:]
    if md5(payload).digest() != data[len(_MAGIC):head]:
        return None
    try:
        code = marshal.loads(payload)
    except Exception:  # EOFError, ValueError, TypeError...: whatever it is, the entry is not usable
        return None
    return code if isinstance(code, types.CodeType) else None


def _write(folder: Path, path: Path, code: types.CodeType) -> None:
    """Store *code* at *path*, atomically; any failure leaves the cache as it was."""
    try:
        payload = marshal.dumps(code)
    except ValueError:
        return
    data = _MAGIC + md5(payload).digest() + payload
    if len(data) > MAX_ENTRY_BYTES:
        return
    temporary = folder / f".{path.stem}.{os.getpid()}.{os.urandom(4).hex()}.tmp"
    try:
        folder.mkdir(parents=True, exist_ok=True)
        fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
        try:
            with os.fdopen(fd, "wb") as file:
                file.write(data)
            os.replace(temporary, path)
        except BaseException:
            try:
                os.unlink(temporary)
            except OSError:
                pass
            raise
    except OSError:
        return
    _prune(folder)


def _prune(folder: Path) -> None:
    """Remove the oldest quarter of the entries when the folder holds more than :data:`MAX_ENTRIES`."""
    entries: list[tuple[int, str]] = []
    try:
        with os.scandir(folder) as it:
            for entry in it:
                if entry.name.endswith((_SUFFIX, ".tmp")):
                    try:
                        entries.append((entry.stat().st_mtime_ns, entry.path))
                    except OSError:
                        continue
    except OSError:
        return
    if len(entries) <= MAX_ENTRIES:
        return
    entries.sort()
    for _, old in entries[: len(entries) - MAX_ENTRIES * 3 // 4]:
        try:
            os.unlink(old)
        except OSError:
            pass
