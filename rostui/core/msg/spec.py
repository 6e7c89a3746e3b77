"""Parsing ``.msg`` and ``.srv`` text into field and constant lists.

The grammar follows the ROS 1 msg format: one declaration per line, ``#`` starts
a comment, ``TYPE NAME`` declares a field, ``TYPE NAME=VALUE`` a constant.
``Header`` means ``std_msgs/Header`` (an array ``Header[]`` does not: like
any other bare non-builtin type name it refers to the declaring package).
String constants keep everything right of ``=`` (including ``#``), stripped,
as genmsg does.  Constant names are stripped and, as in genmsg, not checked
here: the md5 of a type whose constants no class can hold is still genmsg's,
and :mod:`.codegen` refuses to build a class for it.  Field names must be
unique; constants may repeat a name (genmsg and genpy allow it).
"""

from __future__ import annotations

import re

from rostui.core.records import FrozenRecord, Record

from .errors import MessageSpecError

__all__ = [
    "PRIMITIVE_TYPES",
    "BUILTIN_TYPES",
    "HEADER_TYPE",
    "Field",
    "Constant",
    "MsgSpec",
    "SrvSpec",
    "parse_msg_text",
    "parse_srv_text",
    "split_type_name",
    "is_valid_name",
    "shown",
    "is_valid_type_name",
]

PRIMITIVE_TYPES: tuple[str, ...] = (
    "bool", "int8", "uint8", "int16", "uint16", "int32", "uint32",
    "int64", "uint64", "float32", "float64", "string", "byte", "char",
)
"""Types allowed for constants (``byte`` = int8 and ``char`` = uint8 are deprecated aliases)."""

BUILTIN_TYPES: tuple[str, ...] = PRIMITIVE_TYPES + ("time", "duration")
"""Every type that is not a message: primitives plus ``time`` and ``duration``."""

HEADER_TYPE = "std_msgs/Header"
"""The full name of the type a bare ``Header`` refers to."""

_INT_BOUNDS: dict[str, tuple[int, int]] = {
    "int8": (-(2**7), 2**7 - 1), "uint8": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1), "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1), "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1), "uint64": (0, 2**64 - 1),
    "byte": (-(2**7), 2**7 - 1), "char": (0, 2**8 - 1),
}

# ``\Z``, not ``$``: ``$`` also matches before a trailing newline, and these names reach generated code.
_NAME_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")
_TYPE_RE = re.compile(r"([A-Za-z][A-Za-z0-9_]*(?:/[A-Za-z][A-Za-z0-9_]*)?)(?:\[([0-9]*)\])?\Z")


def shown(text: str, limit: int = 80) -> str:
    """*text* as an error message may show it: quoted when it holds control characters, cut at *limit*."""
    if len(text) > limit:
        text = text[:limit] + "..."
    return text if text.isprintable() else repr(text)


def split_type_name(type_name: str) -> tuple[str, str]:
    """Split ``pkg/Name`` into ``(pkg, Name)``; raises ValueError without exactly one ``/``."""
    pkg, sep, name = type_name.partition("/")
    if not sep or not pkg or not name or "/" in name:
        raise ValueError(f"not a package-qualified type name: {type_name!r}")
    return pkg, name


def is_valid_name(name: str) -> bool:
    """True for a legal ROS base name (package, message, field or constant): ``[A-Za-z][A-Za-z0-9_]*``."""
    return isinstance(name, str) and _NAME_RE.match(name) is not None


def is_valid_type_name(type_name: str) -> bool:
    """True for a syntactically legal ``pkg/Name`` (no array suffix)."""
    if not isinstance(type_name, str):
        return False
    m = _TYPE_RE.match(type_name)
    return m is not None and m.group(2) is None and "/" in type_name


class Field(FrozenRecord):
    """One field of a message: its name and resolved type (immutable)."""

    __slots__ = _fields = ("name", "type", "base_type", "is_array", "array_len")

    name: str
    """The field name."""
    type: str
    """The resolved type with array suffix, e.g. ``std_msgs/Header``, ``float64[9]``, ``uint8[]``."""
    base_type: str
    """The element type without array suffix (``pkg/Name`` for messages)."""
    is_array: bool
    """True for ``T[]`` and ``T[N]``."""
    array_len: int | None
    """N for fixed arrays ``T[N]``, None otherwise."""

    def __init__(self, name: str, type: str, base_type: str, is_array: bool, array_len: int | None) -> None:
        self._set(name, type, base_type, is_array, array_len)

    @property
    def is_builtin(self) -> bool:
        """True when the element type is a primitive, ``time`` or ``duration``."""
        return self.base_type in BUILTIN_TYPES


class Constant(FrozenRecord):
    """A constant declaration ``TYPE NAME=VALUE`` (immutable)."""

    __slots__ = _fields = ("type", "name", "value", "val_text")

    type: str
    """The constant's primitive type."""
    name: str
    """The constant's name."""
    value: bool | int | float | str
    """The value converted to Python."""
    val_text: str
    """The value exactly as written (stripped); used for the md5 text."""

    def __init__(self, type: str, name: str, value: bool | int | float | str, val_text: str) -> None:
        self._set(type, name, value, val_text)


class MsgSpec(Record):
    """A parsed message definition."""

    _fields = ("type_name", "fields", "constants", "text", "source", "md5sum")
    _compared = ("type_name", "fields", "constants", "text", "source")

    type_name: str
    """Full type name ``pkg/Name``."""
    fields: tuple[Field, ...]
    """Fields in declaration order."""
    constants: tuple[Constant, ...]
    """Constants in declaration order."""
    text: str
    """The definition text as given (used for ``message_definition``)."""
    source: str | None
    """The file the text came from, if any."""
    md5sum: str
    """Filled in by the registry once dependencies are known (not compared)."""

    def __init__(self, type_name: str, fields: tuple[Field, ...], constants: tuple[Constant, ...], text: str,
                 source: str | None = None, md5sum: str = "") -> None:
        self.type_name = type_name
        self.fields = fields
        self.constants = constants
        self.text = text
        self.source = source
        self.md5sum = md5sum


    @property
    def package(self) -> str:
        """The package part of the type name."""
        return self.type_name.partition("/")[0]

    @property
    def short_name(self) -> str:
        """The type name without package."""
        return self.type_name.rpartition("/")[2]

    @property
    def has_header(self) -> bool:
        """True when the first field is ``std_msgs/Header header``."""
        return bool(self.fields) and self.fields[0].type == HEADER_TYPE and self.fields[0].name == "header"

    def dependencies(self) -> list[str]:
        """Message types used by fields, in field order (duplicates kept)."""
        return [f.base_type for f in self.fields if not f.is_builtin]


class SrvSpec(Record):
    """A parsed service definition: request and response message specs."""

    _fields = ("type_name", "request", "response", "text", "source")

    type_name: str
    """Full service type name ``pkg/Name``."""
    request: MsgSpec
    """The request half, typed ``pkg/NameRequest``."""
    response: MsgSpec
    """The response half, typed ``pkg/NameResponse``."""
    text: str
    """The whole .srv text."""
    source: str | None
    """The file the text came from, if any."""

    def __init__(self, type_name: str, request: MsgSpec, response: MsgSpec, text: str,
                 source: str | None = None) -> None:
        self.type_name = type_name
        self.request = request
        self.response = response
        self.text = text
        self.source = source



def _strip_comment(line: str) -> str:
    return line.split("#", 1)[0].strip()


def _convert_constant(ctype: str, val: str) -> bool | int | float | str:
    if ctype in ("float32", "float64"):
        return float(val)
    if ctype == "string":
        return val.strip()
    if ctype in _INT_BOUNDS:
        lo, hi = _INT_BOUNDS[ctype]
        iv = int(val)
        if iv < lo or iv > hi:
            raise ValueError(f"cannot coerce [{val}] to {ctype} (out of bounds)")
        return iv
    if ctype == "bool":
        import ast  # here: bool constants are rare, and ast is 3 ms of every node's start

        return bool(ast.literal_eval(val))
    raise ValueError(f"invalid constant type: [{ctype}]")


def _resolve_field_type(ftype: str, package: str) -> tuple[str, str, bool, int | None]:
    m = _TYPE_RE.match(ftype)
    if not m:
        raise ValueError(f"{shown(ftype)} is not a legal message field type")
    base, arr = m.group(1), m.group(2)
    suffix = "" if arr is None else f"[{arr}]"
    if "/" not in base:
        if ftype == "Header":  # genmsg maps the bare word only: ``Header[]`` is the package's own Header
            base = HEADER_TYPE
        elif base not in BUILTIN_TYPES:
            if not package:
                raise ValueError(f"cannot resolve bare type {base} without a package")
            base = f"{package}/{base}"
    return base + suffix, base, arr is not None, (int(arr) if arr else None)


def parse_msg_text(text: str, type_name: str, source: str | None = None, first_line: int = 1) -> MsgSpec:
    """Parse .msg *text* for type *type_name* (``pkg/Name``).

    *source* and *first_line* are used only for error locations.
    Raises :class:`MessageSpecError`, also when *type_name* is not a legal ``pkg/Name``
    (it may come from a peer's ``message_definition``).
    """
    if not is_valid_type_name(type_name):
        raise MessageSpecError(f"{shown(type_name)} is not a valid pkg/Type name", source)
    package = type_name.partition("/")[0]
    fields: list[Field] = []
    constants: list[Constant] = []
    names: set[str] = set()
    for lineno, orig in enumerate(text.split("\n"), start=first_line):
        clean = _strip_comment(orig)
        if not clean:
            continue
        try:
            if "=" in clean:
                constants.append(_parse_constant(orig, clean))
                continue
            parts = clean.split()
            if len(parts) != 2:
                raise ValueError(f"invalid declaration: {shown(orig.strip())}")
            ftype, fname = parts
            if not _NAME_RE.match(fname):
                raise ValueError(f"{shown(fname)} is not a legal message field name")
            full, base, is_arr, alen = _resolve_field_type(ftype, package)
            if fname in names:
                raise ValueError(f"duplicate field name {fname}")
            names.add(fname)
            fields.append(Field(fname, full, base, is_arr, alen))
        except ValueError as e:
            raise MessageSpecError(f"{type_name}: {e}", source, lineno) from None
    return MsgSpec(type_name, tuple(fields), tuple(constants), text, source)


def _parse_constant(orig: str, clean: str) -> Constant:
    # genmsg splits on spaces only: ``int32\tX=1`` has no legal type, as there
    parts = [x.strip() for x in clean.split(" ") if x.strip()]
    ctype = parts[0]
    if ctype not in PRIMITIVE_TYPES:
        raise ValueError(f"{shown(ctype)} is not a legal constant type")
    if ctype == "string":
        # everything right of the first "=" is the value, "#" included; the name is what lies
        # between the line's first space and that "=" (genmsg's reading, odd lines too)
        idx = orig.find("=")
        name = orig[orig.find(" ") + 1 : idx].strip()
        val = orig[idx + 1 :]
    else:
        halves = [x.strip() for x in " ".join(parts[1:]).split("=")]
        if len(halves) != 2:
            raise ValueError(f"invalid constant declaration: {shown(orig.strip())}")
        name, val = halves
    try:
        value = _convert_constant(ctype, val)
    except (ValueError, SyntaxError, TypeError, RecursionError, MemoryError) as e:
        raise ValueError(f"invalid constant value: {shown(str(e))}") from None
    return Constant(ctype, name, value, val.strip())


def parse_srv_text(text: str, type_name: str, source: str | None = None) -> SrvSpec:
    """Parse .srv *text*: the request, a line starting with ``---``, the response.

    The halves are typed ``<type_name>Request`` and ``<type_name>Response``.
    """
    req_lines: list[str] = []
    resp_lines: list[str] = []
    acc = req_lines
    split_line = None
    for i, line in enumerate(text.split("\n"), start=1):
        if line.startswith("---"):
            acc = resp_lines
            if split_line is None:
                split_line = i
            continue
        acc.append(line + "\n")
    if split_line is None:
        # genmsg accepts a missing separator (empty response); keep that leniency
        split_line = len(req_lines) + 1
    request = parse_msg_text("".join(req_lines), type_name + "Request", source, 1)
    response = parse_msg_text("".join(resp_lines), type_name + "Response", source, split_line + 1)
    return SrvSpec(type_name, request, response, text, source)
