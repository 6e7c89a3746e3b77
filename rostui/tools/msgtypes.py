"""`rostui msg` / `rostui srv`: message and service types as rosmsg and rossrv print them.

``show`` prints constants then fields of each type, nested message types
indented by two spaces, and a blank line after each type; ``-r`` prints the
definition text as written.  A name without package is searched in every
package, each match headed ``[pkg/Type]:``.  Types come from the package roots
(ROS_PACKAGE_PATH, then rostui's built-in packages).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Literal

from rostui.core import packages
from rostui.core.msg import MessageSpecError, UnknownMessageTypeError
from rostui.core.msg.registry import default_store
from rostui.core.msg.spec import MsgSpec

__all__ = [
    "Kind", "TypeLookupError", "show", "show_json", "md5", "list_types", "package_types",
    "packages_with_types", "find_by_short_name", "spec_text",
]

Kind = Literal["msg", "srv"]
"""``msg`` for message types, ``srv`` for service types."""

EXIT_INVALID_PACKAGE = 64
"""rosmsg's exit status for ``package`` of an unknown package."""


class TypeLookupError(Exception):
    """A type or package could not be found or read; ``code`` is the exit status."""

    def __init__(self, message: str, code: int = 1) -> None:
        """Keep the (possibly multi-line) message and exit status."""
        super().__init__(message)
        self.message = message
        self.code = code


# -- finding types ---------------------------------------------------------------

def _type_dir(pkg_dir: Path, kind: Kind) -> Path:
    return pkg_dir / kind


def _type_files(kind: Kind, package: str) -> dict[str, Path]:
    """The .msg/.srv files of *package* by type name, from every directory of it on the path (the first wins):
    a package found without its type files (Debian's /usr/share layout) does not hide rostui's built-in copy."""
    files: dict[str, Path] = {}
    for pkg_dir in reversed(packages.find_package_dirs(package)):
        files.update((p.stem, p) for p in _type_dir(pkg_dir, kind).glob(f"*.{kind}") if p.is_file())
    return files


def package_types(kind: Kind, package: str) -> list[str]:
    """Types of *kind* in *package*, sorted; unknown package: rosmsg's ``Invalid package`` (exit 64)."""
    if packages.find_package(package) is None:
        lines = [f"Invalid package: {package}"]
        lines += [f"ROS path [{i}]={root}" for i, root in enumerate(packages.package_roots())]
        raise TypeLookupError("\n".join(lines), EXIT_INVALID_PACKAGE)
    return sorted(f"{package}/{name}" for name in _type_files(kind, package))


def list_types(kind: Kind) -> list[str]:
    """Every type of *kind* in every package, sorted by package then name."""
    out: list[str] = []
    for name in sorted(packages.list_packages()):
        out.extend(package_types(kind, name))
    return out


def packages_with_types(kind: Kind) -> list[str]:
    """Packages that define at least one type of *kind*, sorted."""
    return [name for name in sorted(packages.list_packages()) if _type_files(kind, name)]


def find_by_short_name(kind: Kind, name: str) -> list[str]:
    """Full names ``pkg/Name`` of the types called *name* in any package, sorted by package."""
    return [f"{pkg}/{name}" for pkg in sorted(packages.list_packages()) if name in _type_files(kind, pkg)]


def _load_error(kind: Kind, type_name: str, detail: str) -> TypeLookupError:
    head = "Unable to load msg" if kind == "msg" else "Unknown srv type"
    return TypeLookupError(f"{head} [{type_name}]: {detail}")


def _locate(kind: Kind, type_name: str) -> Path:
    """The .msg/.srv file of *type_name*; rosmsg's wording when it is missing."""
    pkg, _, name = type_name.partition("/")
    pkg_dir = packages.find_package(pkg)
    if pkg_dir is None:
        raise _load_error(kind, type_name, f"Cannot locate message [{name}]: unknown package [{pkg}]")
    path = _type_files(kind, pkg).get(name) if name and "/" not in name else None
    if path is None:
        where = [str(_type_dir(pkg_dir, kind))]
        raise _load_error(kind, type_name, f"Cannot locate message [{name}] in package [{pkg}] with paths {[where]}")
    return path


def _expand(kind: Kind, arg: str) -> tuple[list[str], bool]:
    """The full names *arg* stands for, and whether it was a bare name (which gets headers)."""
    if "/" in arg:
        return [arg], False
    if kind == "msg" and arg == "Header":
        return ["std_msgs/Header"], True
    return find_by_short_name(kind, arg), True


# -- show ---------------------------------------------------------------------------

def _spec_lines(spec: MsgSpec, indent: str, out: list[str], depth: int = 0) -> None:
    if depth > 64:
        raise MessageSpecError(f"{spec.type_name}: nesting too deep or recursive")
    store = default_store()
    for c in spec.constants:
        out.append(f"{indent}{c.type} {c.name}={c.val_text}")
    for f in spec.fields:
        out.append(f"{indent}{f.type} {f.name}")
        if not f.is_builtin:
            _spec_lines(store.get_spec(f.base_type), indent + "  ", out, depth + 1)


def spec_text(kind: Kind, type_name: str, raw: bool = False) -> str:
    """One type as rosmsg/rossrv show prints it, ending with the blank line."""
    path = _locate(kind, type_name)
    store = default_store()
    try:
        if kind == "srv":
            srv = store.get_srv_spec(type_name)
            if raw:
                return srv.text + "\n"
            lines: list[str] = []
            _spec_lines(srv.request, "", lines)
            lines.append("---")
            _spec_lines(srv.response, "", lines)
        else:
            spec = store.get_spec(type_name)
            if raw:
                return spec.text + "\n"
            lines = []
            _spec_lines(spec, "", lines)
    except (UnknownMessageTypeError, MessageSpecError) as exc:
        raise _load_error(kind, type_name, str(exc)) from None
    except OSError as exc:
        raise _load_error(kind, type_name, f"{path}: {exc.strerror or exc}") from None
    return "".join(line + "\n" for line in lines) + "\n"


def message_lines(type_name: str) -> list[str]:
    """A message type's fields as rosmsg show lists them (nested types indented), for any type rostui can load:
    a .msg file's, or one an .action generates. :class:`TypeLookupError` otherwise."""
    lines: list[str] = []
    try:
        _spec_lines(default_store().get_spec(type_name), "", lines)
    except (UnknownMessageTypeError, MessageSpecError, OSError) as exc:
        raise _load_error("msg", type_name, str(exc)) from None
    return lines


def _not_found(kind: Kind, arg: str) -> TypeLookupError:
    # rossrv says "msg" here too
    return TypeLookupError(f"Could not find msg '{arg}'")


def show(kind: Kind, arg: str, raw: bool = False) -> str:
    """``rosmsg show [-r] ARG`` / ``rossrv show [-r] ARG`` output; raises :class:`TypeLookupError`."""
    names, bare = _expand(kind, arg)
    if not names:
        raise _not_found(kind, arg)
    if not bare:
        return spec_text(kind, names[0], raw)
    return "".join(f"[{n}]:\n" + spec_text(kind, n, raw) for n in names)


def md5(kind: Kind, arg: str) -> tuple[str, str | None]:
    """``rosmsg md5 ARG`` output and, for a bare name without match, rosmsg's notice (exit 0)."""
    names, bare = _expand(kind, arg)
    if not names:
        what = "messages" if kind == "msg" else "services"
        return "", f"No {what} matching the name [{arg}]"
    store = default_store()
    out: list[str] = []
    for n in names:
        _locate(kind, n)
        try:
            value = store.srv_md5sum(n) if kind == "srv" else store.md5sum(n)
        except (UnknownMessageTypeError, MessageSpecError) as exc:
            raise _load_error(kind, n, str(exc)) from None
        out.append(f"[{n}]: {value}" if bare else value)
    return "".join(line + "\n" for line in out), None


# -- JSON --------------------------------------------------------------------------

def _spec_json(spec: MsgSpec, depth: int = 0) -> dict[str, Any]:
    if depth > 64:
        raise MessageSpecError(f"{spec.type_name}: nesting too deep or recursive")
    store = default_store()
    fields: list[dict[str, Any]] = []
    for f in spec.fields:
        entry: dict[str, Any] = {"name": f.name, "type": f.type}
        if f.is_array:
            entry["array_length"] = f.array_len
        if not f.is_builtin:
            entry["message"] = _spec_json(store.get_spec(f.base_type), depth + 1)
        fields.append(entry)
    return {
        "type": spec.type_name,
        "md5sum": store.md5sum(spec.type_name),
        "constants": [{"name": c.name, "type": c.type, "value": c.value} for c in spec.constants],
        "fields": fields,
    }


def show_json(kind: Kind, arg: str) -> list[dict[str, Any]]:
    """The types *arg* names as JSON-ready dicts (nested types inline); raises :class:`TypeLookupError`."""
    names, _ = _expand(kind, arg)
    if not names:
        raise _not_found(kind, arg)
    store = default_store()
    out: list[dict[str, Any]] = []
    for n in names:
        path = _locate(kind, n)
        try:
            if kind == "srv":
                srv = store.get_srv_spec(n)
                out.append({"type": n, "md5sum": store.srv_md5sum(n), "file": os.fspath(path),
                            "request": _spec_json(srv.request), "response": _spec_json(srv.response)})
            else:
                item = _spec_json(store.get_spec(n))
                item["file"] = os.fspath(path)
                out.append(item)
        except (UnknownMessageTypeError, MessageSpecError) as exc:
            raise _load_error(kind, n, str(exc)) from None
    return out
