"""Type registry: loads .msg/.srv specs from packages, computes md5 and full text, builds classes.

The default store loads lazily from rostui's built-in ``share/`` packages and
ROS_PACKAGE_PATH (see :mod:`rostui.core.packages`), and holds nothing else:
classes for a connection header's or a bag's ``message_definition`` come from
:func:`rostui.core.msg.received.connection_class`, in stores of their own.
"""

from __future__ import annotations

import threading
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .. import packages
from .action import ACTION_SUFFIXES, action_message_texts, split_action_type
from .codegen import build_message_class
from .errors import MessageSpecError, UnknownMessageTypeError
from .message import Message, Service
from .spec import HEADER_TYPE, MsgSpec, SrvSpec, is_valid_type_name, parse_msg_text, parse_srv_text, shown

try:
    from _md5 import md5  # type: ignore[import-not-found]  # CPython's own: hashlib's loads OpenSSL (3 MB)
except ImportError:  # a Python built without it
    from hashlib import md5

__all__ = [
    "DEFINITION_SEPARATOR",
    "TypeStore",
    "default_store",
    "get_message_class",
    "get_service_class",
    "get_message_spec",
    "get_service_spec",
    "md5sum",
    "full_text",
    "split_definition",
    "list_message_types",
    "list_service_types",
    "normalize_type_name",
    "clear_cache",
]

DEFINITION_SEPARATOR = "=" * 80
"""The line between types in a ``message_definition`` / ``_full_text``."""

MAX_NESTING = 64
"""Deepest nesting of message types accepted (ROS types cannot contain themselves)."""


def normalize_type_name(type_name: str) -> str:
    """Map ``Header`` to ``std_msgs/Header`` and validate ``pkg/Name``."""
    if type_name == "Header":
        return HEADER_TYPE
    if not is_valid_type_name(type_name):
        raise UnknownMessageTypeError(type_name, "not a valid pkg/Type name")
    return type_name


class TypeStore:
    """Specs, md5 sums, full texts and generated classes for a set of types.

    With ``load_from_packages=True`` unknown names are looked up as
    ``<pkg>/msg/<Name>.msg`` / ``<pkg>/srv/<Name>.srv`` in the package roots.
    """

    def __init__(self, load_from_packages: bool = True) -> None:
        """Create an empty store."""
        self.load_from_packages = load_from_packages
        self._specs: dict[str, MsgSpec] = {}
        self._srv_specs: dict[str, SrvSpec] = {}
        self._md5: dict[str, str] = {}
        self._md5_text: dict[str, str] = {}
        self._full: dict[str, str] = {}
        self._classes: dict[str, type[Message]] = {}
        self._srv_classes: dict[str, type[Service]] = {}
        self._building: set[str] = set()
        self._lock = threading.RLock()

    # -- specs -------------------------------------------------------------
    def add_spec(self, spec: MsgSpec) -> None:
        """Register a message spec (replacing nothing already present); MessageSpecError for an illegal name."""
        _check_type_name(spec.type_name, spec.source)
        with self._lock:
            self._specs.setdefault(spec.type_name, spec)

    def has_type(self, type_name: str) -> bool:
        """True when *type_name* is known or loadable."""
        try:
            self.get_spec(type_name)
        except UnknownMessageTypeError:
            return False
        return True

    def get_spec(self, type_name: str) -> MsgSpec:
        """The spec of message type *type_name*; raises UnknownMessageTypeError/MessageSpecError."""
        spec = self._specs.get(type_name)
        if spec is not None:
            return spec
        type_name = normalize_type_name(type_name)
        with self._lock:
            spec = self._specs.get(type_name)
            if spec is not None:
                return spec
            pkg, _, name = type_name.partition("/")
            if self.load_from_packages:
                path = _first_file(packages.iter_package_dirs(pkg), "msg", f"{name}.msg")
                if path is not None:  # without listing every directory of the package (Debian's too)
                    spec = parse_msg_text(_read(path), type_name, str(path))
                    self._specs[type_name] = spec
                    return spec
                pkg_dirs = packages.find_package_dirs(pkg)
                if pkg_dirs:
                    spec = self._action_spec(pkg, name, pkg_dirs)
                    if spec is not None:
                        return spec
                    for suffix in ("Request", "Response"):
                        if name.endswith(suffix) and len(name) > len(suffix):
                            srv_name = f"{pkg}/{name[: -len(suffix)]}"
                            try:
                                self.get_srv_spec(srv_name)
                            except UnknownMessageTypeError:
                                break
                            return self._specs[type_name]
                    raise UnknownMessageTypeError(type_name, f"no {name}.msg in package {pkg} ({_dirs_text(pkg_dirs)})")
                raise UnknownMessageTypeError(type_name, f"package {pkg} not found")
            raise UnknownMessageTypeError(type_name)

    def _action_spec(self, pkg: str, name: str, pkg_dirs: list[Path]) -> MsgSpec | None:
        """The spec of ``pkg/name`` when it is one of the messages of an ``.action`` file of ``pkg`` (all seven of
        that action's are registered then); None when no action makes it."""
        for action in split_action_type(name):
            path = _first_file(pkg_dirs, "action", f"{action}.action")
            if path is None:
                continue
            for message, text in action_message_texts(action, _read(path), str(path)).items():
                self._specs.setdefault(f"{pkg}/{message}", parse_msg_text(text, f"{pkg}/{message}", str(path)))
            spec = self._specs.get(f"{pkg}/{name}")
            if spec is not None:
                return spec
        return None

    def get_srv_spec(self, type_name: str) -> SrvSpec:
        """The spec of service type *type_name*."""
        spec = self._srv_specs.get(type_name)
        if spec is not None:
            return spec
        if not is_valid_type_name(type_name):
            raise UnknownMessageTypeError(type_name, "not a valid pkg/Type name")
        with self._lock:
            spec = self._srv_specs.get(type_name)
            if spec is not None:
                return spec
            pkg, _, name = type_name.partition("/")
            path = _first_file(packages.iter_package_dirs(pkg), "srv", f"{name}.srv") if self.load_from_packages \
                else None
            if path is None:
                pkg_dirs = packages.find_package_dirs(pkg) if self.load_from_packages else []
                if not pkg_dirs:
                    raise UnknownMessageTypeError(type_name, f"package {pkg} not found")
                raise UnknownMessageTypeError(type_name, f"no {name}.srv in package {pkg} ({_dirs_text(pkg_dirs)})")
            spec = parse_srv_text(_read(path), type_name, str(path))
            self._srv_specs[type_name] = spec
            self._specs.setdefault(spec.request.type_name, spec.request)
            self._specs.setdefault(spec.response.type_name, spec.response)
            return spec

    def add_srv_spec(self, spec: SrvSpec) -> None:
        """Register a service spec and its request/response halves; MessageSpecError for an illegal name."""
        for name in (spec.type_name, spec.request.type_name, spec.response.type_name):
            _check_type_name(name, spec.source)
        with self._lock:
            self._srv_specs.setdefault(spec.type_name, spec)
            self._specs.setdefault(spec.request.type_name, spec.request)
            self._specs.setdefault(spec.response.type_name, spec.response)

    # -- md5 and full text ---------------------------------------------------
    def md5_text(self, type_name: str) -> str:
        """The text hashed for *type_name*'s md5 (constants, then fields; nested types by md5)."""
        cached = self._md5_text.get(type_name)
        if cached is not None:
            return cached
        spec = self.get_spec(type_name)
        type_name = spec.type_name
        if type_name in self._building:
            raise MessageSpecError(f"{type_name} contains itself", spec.source)
        if len(self._building) >= MAX_NESTING:
            raise MessageSpecError(f"{type_name}: nesting too deep (more than {MAX_NESTING} levels)", spec.source)
        self._building.add(type_name)
        try:
            lines = [f"{c.type} {c.name}={c.val_text}" for c in spec.constants]
            for f in spec.fields:
                if f.is_builtin:
                    lines.append(f"{f.type} {f.name}")
                else:
                    try:
                        sub = self.md5sum(f.base_type)
                    except UnknownMessageTypeError as e:
                        raise UnknownMessageTypeError(f.base_type, f"needed by {type_name}: {e}") from None
                    lines.append(f"{sub} {f.name}")
        finally:
            self._building.discard(type_name)
        text = "\n".join(lines).strip()
        self._md5_text[type_name] = text
        return text

    def md5sum(self, type_name: str) -> str:
        """The md5sum of message type *type_name*, as genmsg computes it."""
        cached = self._md5.get(type_name)
        if cached is None:
            cached = md5(self.md5_text(type_name).encode()).hexdigest()
            self._md5[type_name] = cached
        return cached

    def srv_md5sum(self, type_name: str) -> str:
        """The md5sum of service type *type_name* (request text + response text)."""
        spec = self.get_srv_spec(type_name)
        h = md5()
        h.update(self.md5_text(spec.request.type_name).encode())
        h.update(self.md5_text(spec.response.type_name).encode())
        return str(h.hexdigest())

    def all_depends(self, type_name: str) -> list[str]:
        """Nested message types of *type_name*, depth first, each once."""
        out: list[str] = []

        seen: set[str] = set()

        def walk(t: str, depth: int) -> None:
            if depth > MAX_NESTING:
                raise MessageSpecError(f"{type_name}: nesting too deep or recursive")
            for d in self.get_spec(t).dependencies():
                if d in seen:  # its own dependencies are in already: walking it again adds nothing
                    continue
                seen.add(d)
                out.append(d)
                walk(d, depth + 1)

        walk(type_name, 0)
        return out

    def full_text(self, type_name: str) -> str:
        """The ``message_definition`` of *type_name*: own text, then each nested type once."""
        cached = self._full.get(type_name)
        if cached is not None:
            return cached
        spec = self.get_spec(type_name)
        parts = [spec.text, "\n"]
        for d in self.all_depends(spec.type_name):
            parts += [DEFINITION_SEPARATOR, "\n", f"MSG: {d}\n", self.get_spec(d).text, "\n"]
        text = "".join(parts)[:-1]
        self._full[type_name] = text
        return text

    # -- classes -------------------------------------------------------------
    def get_class(self, type_name: str) -> type[Message]:
        """The generated class of message type *type_name* (built once, cached)."""
        cls = self._classes.get(type_name)
        if cls is not None:
            return cls
        with self._lock:
            spec = self.get_spec(type_name)
            cls = self._classes.get(spec.type_name)
            if cls is None:
                md5 = self.md5sum(spec.type_name)  # also rejects recursive types
                cls = build_message_class(spec, md5, self.full_text(spec.type_name), self.get_spec, self.get_class)
                self._classes[spec.type_name] = cls
            self._classes[type_name] = cls
            return cls

    def use_class(self, cls: type[Message]) -> None:
        """Let *cls* stand for its type here (a class of another store whose md5sum this store's type has)."""
        with self._lock:
            if self.md5sum(cls._type) != cls._md5sum:
                raise MessageSpecError(f"{cls._type}: md5sum {cls._md5sum} is not this store's {self.md5sum(cls._type)}")
            self._classes[cls._type] = cls

    def get_service_class(self, type_name: str) -> type[Service]:
        """The generated service class of *type_name* (``_request_class``/``_response_class``)."""
        cls = self._srv_classes.get(type_name)
        if cls is not None:
            return cls
        with self._lock:
            spec = self.get_srv_spec(type_name)
            attrs: dict[str, Any] = {
                "__doc__": f"ROS service {type_name} (generated by rostui).",
                "__module__": "rostui.core.msg.generated",
                "__slots__": (),
                "_type": type_name,
                "_md5sum": self.srv_md5sum(type_name),
                "_request_class": self.get_class(spec.request.type_name),
                "_response_class": self.get_class(spec.response.type_name),
                "_spec": spec,
            }
            cls = type(spec.type_name.rpartition("/")[2], (Service,), attrs)
            self._srv_classes[type_name] = cls
            return cls


def _check_type_name(type_name: str, source: str | None) -> None:
    if not is_valid_type_name(type_name):
        raise MessageSpecError(f"{shown(type_name)} is not a valid pkg/Type name", source)


def _first_file(pkg_dirs: Iterable[Path], folder: str, file_name: str) -> Path | None:
    """The first ``<dir>/<folder>/<file_name>`` that exists: a package dir without it does not hide later ones."""
    for pkg_dir in pkg_dirs:
        path = pkg_dir / folder / file_name
        if path.is_file():
            return path
    return None


def _dirs_text(pkg_dirs: list[Path]) -> str:
    return ", ".join(str(d) for d in pkg_dirs)


def _read(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError as e:
        raise MessageSpecError(f"not UTF-8 text: {e}", str(path)) from None


_default = TypeStore(load_from_packages=True)


def default_store() -> TypeStore:
    """The process-wide store used by the module-level functions."""
    return _default


def clear_cache() -> None:
    """Forget every loaded type (for example after editing .msg files)."""
    global _default
    _default = TypeStore(load_from_packages=True)
    packages.clear_cache()


def get_message_class(type_name: str) -> type[Message]:
    """The class of message type *type_name* (``pkg/Name``; ``Header`` is accepted)."""
    return _default.get_class(type_name)


def get_service_class(type_name: str) -> type[Service]:
    """The class of service type *type_name*."""
    return _default.get_service_class(type_name)


def get_message_spec(type_name: str) -> MsgSpec:
    """The parsed spec of message type *type_name*."""
    return _default.get_spec(type_name)


def get_service_spec(type_name: str) -> SrvSpec:
    """The parsed spec of service type *type_name*."""
    return _default.get_srv_spec(type_name)


def md5sum(type_name: str) -> str:
    """The md5sum of message type *type_name*."""
    return _default.md5sum(type_name)


def full_text(type_name: str) -> str:
    """The ``message_definition`` text of message type *type_name*."""
    return _default.full_text(type_name)


def split_definition(type_name: str, definition: str) -> list[MsgSpec]:
    """Parse a ``message_definition`` into specs: the main type first, then each ``MSG:`` section.

    Every type name is checked against ROS's grammar before use (the text may
    come from any peer or bag): a bad one raises MessageSpecError.
    """
    if not isinstance(definition, str):
        raise MessageSpecError("message_definition is not text", "<message_definition>")
    type_name = normalize_type_name(type_name)
    where = f"<message_definition of {type_name}>"
    sections = definition.split("\n" + DEFINITION_SEPARATOR + "\n")
    specs = [parse_msg_text(sections[0], type_name, where)]
    for sec in sections[1:]:
        head, _, text = sec.partition("\n")
        if not head.startswith("MSG: "):
            raise MessageSpecError(f"expected 'MSG: pkg/Type' after separator, got {shown(head)}", where)
        sub = head[5:].strip()
        if sub == "Header":
            sub = HEADER_TYPE
        if not is_valid_type_name(sub):
            raise MessageSpecError(f"{shown(sub)} after 'MSG:' is not a valid pkg/Type name", where)
        specs.append(parse_msg_text(text, sub, f"<message_definition of {type_name}: {sub}>"))
    return specs


def list_message_types(package: str) -> list[str]:
    """The message types (``pkg/Name``) defined by *package*, sorted: its .msg files and what its .action files
    make (:mod:`rostui.core.msg.action`)."""
    dirs = packages.find_package_dirs(package)
    if not dirs:
        raise packages.PackageNotFoundError(package)
    actions = {p.stem for d in dirs for p in (d / "action").glob("*.action")}
    generated = {f"{name}{suffix}" for name in actions for suffix in ACTION_SUFFIXES}
    return sorted({f"{package}/{p.stem}" for d in dirs for p in (d / "msg").glob("*.msg")}
                  | {f"{package}/{name}" for name in generated})


def list_service_types(package: str) -> list[str]:
    """The service types (``pkg/Name``) defined by *package*, sorted."""
    dirs = packages.find_package_dirs(package)
    if not dirs:
        raise packages.PackageNotFoundError(package)
    return sorted({f"{package}/{p.stem}" for d in dirs for p in (d / "srv").glob("*.srv")})
