"""Generate fast Python source for message classes and ``exec`` it.

For each type we emit straight-line ``serialize``/``deserialize`` code in which
nested (non-array) messages are inlined and runs of consecutive fixed-size
fields share one precompiled :class:`struct.Struct`.  Strings, byte arrays and
variable arrays are length-checked before slicing, so a truncated or hostile
buffer raises :class:`DeserializationError` instead of over-allocating.

Decoding is budgeted per message, tied to the bytes received (ROS has no such
rule: genpy makes whatever a definition asks for).  An array of N elements of
a type at least k bytes long is read only when N*k bytes remain.  Each byte
then pays for one object; the objects no byte pays for (elements of a type
with no fields, or with more fields than bytes; see :func:`unpaid_objects`)
may number at most :data:`UNPAID_OBJECTS_FLOOR` (65,536: thousands of
``std_msgs/Empty`` in any message) plus :data:`UNPAID_OBJECTS_PER_BYTE` per
byte of the message, so a message decodes into about two objects per byte it
holds at most, as a ``bool[]`` does.  Past either bound the deserialiser
raises :class:`DeserializationError` (one line) before it makes the objects.

Definitions may come from any peer (a publisher's ``message_definition``, a
bag), so :func:`check_spec` refuses, before any code is written, every name
that is not ROS's grammar (or that Python cannot use as an attribute) and
every type whose generated code or default value would be unreasonably big;
the source itself holds only those checked names, generated identifiers,
numbers and ``repr()`` literals.
"""

from __future__ import annotations

import keyword
import struct
from typing import Any, Callable

from ..rostime import Duration, Time
from .codecache import compile_source
from .errors import DeserializationError, MessageSpecError, SerializationError
from .message import Message, hybridmethod
from .spec import BUILTIN_TYPES, Field, MsgSpec, is_valid_name, is_valid_type_name, shown

__all__ = ["attribute_name", "build_message_class", "check_spec", "min_size", "unpaid_objects", "PRIMITIVE_STRUCT",
           "RESERVED_NAMES", "MAX_INLINED_FIELDS", "MAX_DEFAULT_COST", "UNPAID_OBJECTS_FLOOR", "UNPAID_OBJECTS_PER_BYTE",
           "element_objects"]

PRIMITIVE_STRUCT: dict[str, tuple[str, int]] = {
    "bool": ("B", 1), "int8": ("b", 1), "uint8": ("B", 1), "byte": ("b", 1), "char": ("B", 1),
    "int16": ("h", 2), "uint16": ("H", 2), "int32": ("i", 4), "uint32": ("I", 4),
    "int64": ("q", 8), "uint64": ("Q", 8), "float32": ("f", 4), "float64": ("d", 8),
}
"""struct format char and byte size of each fixed-size primitive (serialization side)."""

_FLOATS = ("float32", "float64")

RESERVED_NAMES: frozenset[str] = frozenset({"serialize", "deserialize"})
"""Field and constant names a generated class cannot have (its methods)."""
MAX_INLINED_FIELDS = 1 << 14
"""Most fields one class's (de)serializer may hold once nested messages are inlined."""
MAX_DEFAULT_COST = 1 << 23
"""Most machine words (roughly) a default-constructed message may take (fixed arrays are built whole)."""
UNPAID_OBJECTS_FLOOR = 1 << 16
"""Objects that no byte pays for which any message may decode, however short (thousands of ``std_msgs/Empty``)."""
UNPAID_OBJECTS_PER_BYTE = 1
"""Unpaid objects a message may decode per byte it holds, beyond the floor (an array of ``std_msgs/Bool``)."""


def _deser_char(t: str) -> str:
    return "?" if t == "bool" else PRIMITIVE_STRUCT[t][0]


def min_size(spec: MsgSpec, get_spec: Callable[[str], MsgSpec], memo: dict[str, int] | None = None) -> int:
    """The fewest bytes a serialized instance of *spec* can take (*memo* keeps each nested type's size)."""
    memo = {} if memo is None else memo
    cached = memo.get(spec.type_name)
    if cached is not None:
        return cached
    total = 0
    for f in spec.fields:
        if f.is_array and f.array_len is None:
            total += 4
            continue
        n = f.array_len if f.is_array else 1
        assert n is not None
        total += n * _elem_min_size(f.base_type, get_spec, memo)
    memo[spec.type_name] = total
    return total


def _elem_min_size(t: str, get_spec: Callable[[str], MsgSpec], memo: dict[str, int] | None = None) -> int:
    if t in PRIMITIVE_STRUCT:
        return PRIMITIVE_STRUCT[t][1]
    if t == "string":
        return 4
    if t in ("time", "duration"):
        return 8
    return min_size(get_spec(t), get_spec, memo)


def element_objects(t: str, get_spec: Callable[[str], MsgSpec], memo: dict[str, int] | None = None) -> int:
    """The Python objects one decoded element of type *t* makes: itself and each field, nested messages'
    fields too; an array field counts as its list (its elements are charged when it is read)."""
    if t in BUILTIN_TYPES:
        return 1
    memo = {} if memo is None else memo
    cached = memo.get(t)
    if cached is not None:
        return cached
    total = 1
    for f in get_spec(t).fields:
        total += 1 if f.is_array or f.is_builtin else element_objects(f.base_type, get_spec, memo)
    memo[t] = total
    return total


def unpaid_objects(t: str, get_spec: Callable[[str], MsgSpec], objects: dict[str, int] | None = None,
                   sizes: dict[str, int] | None = None) -> int:
    """How many objects of one element of type *t* no byte pays for: its objects beyond its fewest bytes.

    0 for primitives, strings, times and most messages (a ``geometry_msgs/Point``: 4 objects in 24 bytes);
    1 for ``std_msgs/Empty`` and ``std_msgs/Bool`` (2 objects in 1 byte).  Arrays of a type with unpaid
    objects draw on the message's budget.
    """
    return max(0, element_objects(t, get_spec, objects) - _elem_min_size(t, get_spec, sizes))


def _lit(text: str) -> str:
    """A Python string literal for *text* (never pasted between quotes by hand)."""
    return repr(text)


def attribute_name(name: str) -> str:
    """The attribute a field or constant *name* has on a class: as in genpy, a Python keyword or ``self`` gets a ``_``."""
    return name + "_" if keyword.iskeyword(name) or name == "self" else name


def _check_names(spec: MsgSpec) -> None:
    if not is_valid_type_name(spec.type_name):
        raise MessageSpecError(f"{shown(spec.type_name)} is not a valid pkg/Type name", spec.source)
    for f in spec.fields:
        if not is_valid_name(f.name):
            raise MessageSpecError(f"{spec.type_name}: {shown(f.name)} is not a legal field name", spec.source)
        if f.name in RESERVED_NAMES:
            raise MessageSpecError(f"{spec.type_name}: field name {f.name} cannot be used (a method of messages)",
                                   spec.source)
        if f.base_type not in BUILTIN_TYPES and not is_valid_type_name(f.base_type):
            raise MessageSpecError(f"{spec.type_name}: {shown(f.base_type)} is not a valid pkg/Type name "
                                   f"(field {f.name})", spec.source)
        if f.array_len is not None and (not isinstance(f.array_len, int) or f.array_len < 0):
            raise MessageSpecError(f"{spec.type_name}: bad array length of field {f.name}", spec.source)
    field_names: set[str] = set()
    for f in spec.fields:
        if attribute_name(f.name) in field_names:
            raise MessageSpecError(f"{spec.type_name}: two fields are named {attribute_name(f.name)} in Python",
                                   spec.source)
        field_names.add(attribute_name(f.name))
    for c in spec.constants:
        if not is_valid_name(c.name) or c.name in RESERVED_NAMES:
            raise MessageSpecError(f"{spec.type_name}: {shown(c.name)} cannot be a constant's name", spec.source)
        if attribute_name(c.name) in field_names:
            raise MessageSpecError(f"{spec.type_name}: {c.name} is both a constant and a field", spec.source)


def check_spec(spec: MsgSpec, get_spec: Callable[[str], MsgSpec]) -> None:
    """Refuse (MessageSpecError) a type whose class must not be generated.

    Every name must follow ROS's grammar (type ``pkg/Name``, fields and
    constants ``[A-Za-z][A-Za-z0-9_]*``, fields not ``serialize``/``deserialize``;
    a Python keyword becomes its :func:`attribute_name`, ``lambda_``, as in genpy,
    and must then meet no other name), in the type and in every type nested in it;
    and the inlined (de)serializer (:data:`MAX_INLINED_FIELDS`) and the default
    value (:data:`MAX_DEFAULT_COST`) must stay small.
    """
    inlined: dict[str, int] = {}
    cost: dict[str, int] = {}

    def walk(s: MsgSpec, depth: int) -> tuple[int, int]:
        if s.type_name in inlined:
            return inlined[s.type_name], cost[s.type_name]
        if depth > 64:
            raise MessageSpecError(f"{spec.type_name}: nesting too deep or recursive", spec.source)
        _check_names(s)
        n_inlined, n_cost = 0, 1
        for f in s.fields:
            t = f.base_type
            sub: tuple[int, int] | None = None if t in BUILTIN_TYPES else walk(get_spec(t), depth + 1)
            if not f.is_array:
                n_inlined += 1 if sub is None else sub[0]
                n_cost += (8 if t in ("time", "duration") else 1) if sub is None else sub[1]
                continue
            n_inlined += 1 + (0 if sub is None else sub[0])
            n = f.array_len or 0
            if t in ("uint8", "char"):
                n_cost += 1 + n // 8
            elif sub is not None:
                n_cost += 1 + n * sub[1]
            else:
                n_cost += 1 + n * (8 if t in ("time", "duration") else 1)
            n_cost = min(n_cost, MAX_DEFAULT_COST + 1)
        inlined[s.type_name], cost[s.type_name] = n_inlined, n_cost
        if n_inlined > MAX_INLINED_FIELDS:
            raise MessageSpecError(f"{s.type_name}: too many fields once nested messages are inlined "
                                   f"({n_inlined} > {MAX_INLINED_FIELDS})", s.source)
        if n_cost > MAX_DEFAULT_COST:
            raise MessageSpecError(f"{s.type_name}: fixed-size arrays too large for a message", s.source)
        return n_inlined, n_cost

    walk(spec, 0)


def default_expr(f: Field, cls_var: Callable[[str], str]) -> str:
    """A Python expression building the default value of field *f*."""
    t = f.base_type
    if f.is_array:
        if t in ("uint8", "char"):
            return f"b'\\x00' * {f.array_len}" if f.array_len is not None else "b''"
        if f.array_len is None:
            return "[]"
        return f"[{_scalar_default(t, cls_var)} for _ in _range({f.array_len})]"
    return _scalar_default(t, cls_var)


def _scalar_default(t: str, cls_var: Callable[[str], str]) -> str:
    if t in _FLOATS:
        return "0.0"
    if t == "bool":
        return "False"
    if t in PRIMITIVE_STRUCT:
        return "0"
    if t == "string":
        return "''"
    if t == "time":
        return "_Time()"
    if t == "duration":
        return "_Duration()"
    return f"{cls_var(t)}()"


class _Gen:
    """Code emitter shared by the serializer and deserializer walkers."""

    def __init__(self, ns: dict[str, Any], get_spec: Callable[[str], MsgSpec], cls_var: Callable[[str], str]) -> None:
        self.ns = ns
        self.get_spec = get_spec
        self.cls_var = cls_var
        self.lines: list[str] = []
        self.counter = 0
        self.structs: dict[str, str] = {}
        self.sizes: dict[str, int] = {}

    def var(self, prefix: str) -> str:
        self.counter += 1
        return f"{prefix}{self.counter}"

    def struct(self, fmt: str) -> str:
        name = self.structs.get(fmt)
        if name is None:
            name = f"_S{len(self.structs)}"
            self.structs[fmt] = name
            self.ns[name] = struct.Struct("<" + fmt)
        return name

    def emit(self, indent: int, line: str) -> None:
        self.lines.append("    " * indent + line)


class _SerWalker(_Gen):
    """Emits the body of ``serialize`` (writes chunks with ``_w``)."""

    def __init__(self, *a: Any) -> None:
        super().__init__(*a)
        self.run: list[tuple[str, str]] = []

    def flush(self, ind: int) -> None:
        if not self.run:
            return
        fmt = "".join(c for c, _ in self.run)
        args = ", ".join(e for _, e in self.run)
        self.emit(ind, f"_w({self.struct(fmt)}.pack({args}))")
        self.run = []

    def fields(self, spec: MsgSpec, p: str, ind: int) -> None:
        for f in spec.fields:
            self.field(f, f"{p}.{attribute_name(f.name)}", ind)

    def bytes_of(self, expr: str, ind: int) -> str:
        x = self.var("_x")
        self.emit(ind, f"{x} = {expr}")
        self.emit(ind, f"if {x}.__class__ is not bytes: {x} = _as_bytes({x})")
        return x

    def field(self, f: Field, e: str, ind: int) -> None:
        t = f.base_type
        if not f.is_array:
            if t in PRIMITIVE_STRUCT:
                self.run.append((PRIMITIVE_STRUCT[t][0], e))
            elif t == "string":
                x = self.var("_x")
                self.emit(ind, f"{x} = {e}")
                self.emit(ind, f"if isinstance({x}, str): {x} = {x}.encode()")
                self.run.append(("I", f"len({x})"))
                self.flush(ind)
                self.emit(ind, f"_w({x})")
            elif t in ("time", "duration"):
                c = "I" if t == "time" else "i"
                v = self.var("_t")
                self.emit(ind, f"{v} = {e}")
                self.run += [(c, f"{v}.secs"), (c, f"{v}.nsecs")]
            else:
                v = self.var("_v")
                self.emit(ind, f"{v} = {e}")
                self.fields(self.get_spec(t), v, ind)
            return
        n = f.array_len
        if t in ("uint8", "char"):
            x = self.bytes_of(e, ind)
            if n is None:
                self.run.append(("I", f"len({x})"))
                self.flush(ind)
                self.emit(ind, f"_w({x})")
            else:
                self.emit(ind, f"if len({x}) != {n}: raise _SerErr({_lit(f'{f.name}: expected {n} bytes, got %d')} % len({x}))")
                self.run.append((f"{n}s", x))
            return
        if t in PRIMITIVE_STRUCT:
            ch = PRIMITIVE_STRUCT[t][0]
            if n is None:
                x = self.var("_x")
                self.emit(ind, f"{x} = {e}")
                self.run.append(("I", f"len({x})"))
                self.flush(ind)
                self.emit(ind, f"_w(_pack('<%d{ch}' % len({x}), *{x}))")
            else:
                x = self.var("_x")
                self.emit(ind, f"{x} = {e}")
                self.emit(ind, f"if len({x}) != {n}: raise _SerErr({_lit(f'{f.name}: expected {n} elements, got %d')} % len({x}))")
                self.run.append((f"{n}{ch}", f"*{x}"))
            return
        x = self.var("_x")
        self.emit(ind, f"{x} = {e}")
        if n is None:
            self.run.append(("I", f"len({x})"))
        else:
            self.emit(ind, f"if len({x}) != {n}: raise _SerErr({_lit(f'{f.name}: expected {n} elements, got %d')} % len({x}))")
        self.flush(ind)
        it = self.var("_i")
        self.emit(ind, f"for {it} in {x}:")
        if t == "string":
            self.emit(ind + 1, f"if isinstance({it}, str): {it} = {it}.encode()")
            self.emit(ind + 1, f"_w(_pack_I(len({it})))")
            self.emit(ind + 1, f"_w({it})")
        elif t in ("time", "duration"):
            s = self.struct("2I" if t == "time" else "2i")
            self.emit(ind + 1, f"_w({s}.pack({it}.secs, {it}.nsecs))")
        else:
            body = len(self.lines)
            self.fields(self.get_spec(t), it, ind + 1)
            self.flush(ind + 1)
            if len(self.lines) == body:  # a type with no fields writes nothing
                self.emit(ind + 1, "pass")


class _DeserWalker(_Gen):
    """Emits the body of ``_deser`` (reads ``_buf`` from offset ``_o``; ``_n`` = len)."""

    def __init__(self, *a: Any) -> None:
        super().__init__(*a)
        self.run: list[tuple[str, str]] = []
        self.post: list[str] = []
        self.objects: dict[str, int] = {}

    def flush(self, ind: int) -> None:
        if not self.run:
            return
        fmt = "".join(c for c, _ in self.run)
        targets = ", ".join(e for _, e in self.run)
        s = self.struct(fmt)
        self.emit(ind, f"{targets}, = {s}.unpack_from(_buf, _o)")
        self.emit(ind, f"_o += {struct.calcsize('<' + fmt)}")
        for line in self.post:
            self.emit(ind, line)
        self.run = []
        self.post = []

    def fields(self, spec: MsgSpec, p: str, ind: int) -> None:
        for f in spec.fields:
            self.field(f, p, ind)

    def new_obj(self, t: str) -> str:
        if t == "time":
            return "_new(_Time)"
        if t == "duration":
            return "_new(_Duration)"
        return f"_new({self.cls_var(t)})"

    def count(self, f: Field, ind: int, elem_min: int, unpaid: int = 0) -> str:
        """Emit code leaving the element count in a fresh variable, checked against the bytes left and, for
        elements with *unpaid* objects, charged to the message's budget ``_bud``."""
        n = f.array_len
        if n is not None:
            if elem_min > 0 or unpaid > 0:
                self.flush(ind)
            if elem_min > 0:
                self.emit(ind, f"if {n * elem_min} > _n - _o: raise _DeserErr({_lit(f'{f.name}: {n} elements run past the end of the buffer')})")
            if unpaid > 0:
                self.emit(ind, f"_bud -= {n * unpaid}")
                self.emit(ind, f"if _bud < 0: raise _DeserErr({_lit(f'{f.name}: {n} elements exceed the decoding budget of a %d-byte message')} % _n)")
            return str(n)
        c = self.var("_c")
        self.run.append(("I", c))
        self.flush(ind)
        if elem_min > 0:
            self.emit(ind, f"if {c} * {elem_min} > _n - _o: raise _DeserErr({_lit(f'{f.name}: array length %d exceeds buffer')} % {c})")
        if unpaid > 0:
            self.emit(ind, f"_bud -= {c} * {unpaid}")
            self.emit(ind, f"if _bud < 0: raise _DeserErr({_lit(f'{f.name}: %d elements exceed the decoding budget of a %d-byte message')} % ({c}, _n))")
        return c

    def field(self, f: Field, p: str, ind: int) -> None:
        t = f.base_type
        target = f"{p}.{attribute_name(f.name)}"
        if not f.is_array:
            if t in PRIMITIVE_STRUCT:
                self.run.append((_deser_char(t), target))
            elif t == "string":
                ln = self.var("_l")
                self.run.append(("I", ln))
                self.flush(ind)
                e = self.var("_e")
                self.emit(ind, f"{e} = _o + {ln}")
                self.emit(ind, f"if {e} > _n: raise _DeserErr({_lit(f'{f.name}: string runs past end of buffer')})")
                self.emit(ind, f"{target} = _buf[_o:{e}].decode('utf-8', 'replace') if {ln} < 65536 "
                               f"else _str(_memoryview(_buf)[_o:{e}], 'utf-8', 'replace')")
                self.emit(ind, f"_o = {e}")
            elif t in ("time", "duration"):
                v = self.var("_t")
                self.emit(ind, f"{v} = {target} = {self.new_obj(t)}")
                c = "I" if t == "time" else "i"
                self.run += [(c, f"{v}.secs"), (c, f"{v}.nsecs")]
                self.post.append(f"if not 0 <= {v}.nsecs < 1000000000: {v}.canon()")
            else:
                v = self.var("_v")
                self.emit(ind, f"{v} = {target} = {self.new_obj(t)}")
                self.fields(self.get_spec(t), v, ind)
            return
        n = f.array_len
        if t in ("uint8", "char"):
            if n is not None:
                self.run.append((f"{n}s", target))
                return
            c = self.count(f, ind, 1)
            e = self.var("_e")
            self.emit(ind, f"{e} = _o + {c}")
            self.emit(ind, f"{target} = _buf[_o:{e}]")
            self.emit(ind, f"_o = {e}")
            return
        if t in PRIMITIVE_STRUCT:
            ch = _deser_char(t)
            size = PRIMITIVE_STRUCT[t][1]
            if n is not None:
                self.flush(ind)
                s = self.struct(f"{n}{ch}")
                self.emit(ind, f"{target} = list({s}.unpack_from(_buf, _o))")
                self.emit(ind, f"_o += {n * size}")
            else:
                c = self.count(f, ind, size)
                self.emit(ind, f"{target} = list(_unpack_from('<%d{ch}' % {c}, _buf, _o))")
                self.emit(ind, f"_o += {c} * {size}")
            return
        elem_min = _elem_min_size(t, self.get_spec, self.sizes)
        if n is not None:
            self.flush(ind)
        c = self.count(f, ind, elem_min, unpaid_objects(t, self.get_spec, self.objects, self.sizes))
        a = self.var("_a")
        self.emit(ind, f"{a} = []")
        self.emit(ind, f"_ap{a} = {a}.append")
        it = self.var("_i")
        self.emit(ind, f"for {it} in _range({c}):")
        if t == "string":
            ln, e = self.var("_l"), self.var("_e")
            self.emit(ind + 1, f"{ln}, = _unpack_I(_buf, _o)")
            self.emit(ind + 1, "_o += 4")
            self.emit(ind + 1, f"{e} = _o + {ln}")
            self.emit(ind + 1, f"if {e} > _n: raise _DeserErr({_lit(f'{f.name}: string runs past end of buffer')})")
            self.emit(ind + 1, f"_ap{a}(_buf[_o:{e}].decode('utf-8', 'replace'))")
            self.emit(ind + 1, f"_o = {e}")
        elif t in ("time", "duration"):
            v = self.var("_t")
            s = self.struct("2I" if t == "time" else "2i")
            self.emit(ind + 1, f"{v} = {self.new_obj(t)}")
            self.emit(ind + 1, f"{v}.secs, {v}.nsecs = {s}.unpack_from(_buf, _o)")
            self.emit(ind + 1, "_o += 8")
            self.emit(ind + 1, f"if not 0 <= {v}.nsecs < 1000000000: {v}.canon()")
            self.emit(ind + 1, f"_ap{a}({v})")
        else:
            v = self.var("_v")
            self.emit(ind + 1, f"{v} = {self.new_obj(t)}")
            self.fields(self.get_spec(t), v, ind + 1)
            self.flush(ind + 1)
            self.emit(ind + 1, f"_ap{a}({v})")
        self.emit(ind, f"{target} = {a}")


def _as_bytes(value: Any) -> bytes:
    """Coerce a uint8[]/char[] field value (bytes-like or list of ints) to bytes."""
    if isinstance(value, str):
        return value.encode("latin-1")
    return bytes(value)


def _raise_short(msg: str) -> None:
    raise DeserializationError(msg)


def build_message_class(
    spec: MsgSpec,
    md5sum: str,
    full_text: str,
    get_spec: Callable[[str], MsgSpec],
    get_class: Callable[[str], type[Message]],
) -> type[Message]:
    """Generate, compile and return the Python class for *spec*.

    *get_spec* and *get_class* resolve nested message types (their classes
    must be buildable first; ROS types cannot be recursive).  Raises
    :class:`MessageSpecError` for a type :func:`check_spec` refuses.
    """
    check_spec(spec, get_spec)
    ns: dict[str, Any] = {
        "_Time": Time, "_Duration": Duration, "_new": object.__new__, "_range": range, "_str": str, "_memoryview": memoryview,
        "_pack": struct.pack, "_pack_I": struct.Struct("<I").pack,
        "_unpack_from": struct.unpack_from, "_unpack_I": struct.Struct("<I").unpack_from,
        "_as_bytes": _as_bytes, "_SerErr": SerializationError, "_DeserErr": DeserializationError,
        "_struct_error": struct.error,
    }
    cls_vars: dict[str, str] = {}

    def cls_var(t: str) -> str:
        name = cls_vars.get(t)
        if name is None:
            name = f"_C{len(cls_vars)}"  # never the type's name: two names must not meet in one variable
            cls_vars[t] = name
            ns[name] = get_class(t)
        return name

    fields = spec.fields
    names = [attribute_name(f.name) for f in fields]
    lines: list[str] = []
    # __init__
    simple = all(n.isidentifier() and not keyword.iskeyword(n) and n != "self" for n in names)
    defaults = {attribute_name(f.name): default_expr(f, cls_var) for f in fields}
    if simple and names:
        params = ", ".join(f"{n}=None" for n in names)
        lines.append(f"def __init__(self, {params}):")
        lines.append('    """Fields may be given positionally (field order) or by keyword; missing ones get defaults."""')
        for n in names:
            lines.append(f"    self.{n} = {defaults[n]} if {n} is None else {n}")
    elif not names:
        lines.append("def __init__(self):")
        lines.append('    """This message has no fields."""')
    # defaults table
    lines.append("_defaults = {" + ", ".join(f"{n!r}: lambda: {defaults[n]}" for n in names) + "}")

    # serialize
    sw = _SerWalker(ns, get_spec, cls_var)
    sw.fields(spec, "self", 2)
    sw.flush(2)
    lines.append("def serialize(self, buff=None):")
    lines.append('    """The message in ROS 1 wire format (little endian); written to *buff* instead when given (genpy)."""')
    lines.append("    _b = []")
    lines.append("    _w = _b.append")
    lines.append("    try:")
    lines.extend(sw.lines or ["        pass"])
    lines.append("    except _SerErr:")
    lines.append("        raise")
    lines.append("    except (_struct_error, TypeError, ValueError, AttributeError, OverflowError) as _exc:")
    lines.append(f"        raise _SerErr({_lit(f'cannot serialize {spec.type_name}: %s')} % (_exc,)) from _exc")
    lines.append("    if buff is None:")
    lines.append("        return b''.join(_b)")
    lines.append("    buff.write(b''.join(_b))")

    # deserialize
    dw = _DeserWalker(ns, get_spec, cls_var)
    dw.structs = sw.structs  # share Struct objects
    dw.counter = sw.counter
    dw.fields(spec, "self", 2)
    dw.flush(2)
    lines.append("def _deser(cls, _buf):")
    lines.append('    """Build a message from *_buf* (bytes, bytearray or memoryview)."""')
    lines.append("    if _buf.__class__ is not bytes: _buf = bytes(_buf)")
    lines.append("    _n = len(_buf)")
    lines.append("    _o = 0")
    lines.append(f"    _bud = {UNPAID_OBJECTS_FLOOR} + _n * {UNPAID_OBJECTS_PER_BYTE}")
    lines.append("    self = _new(cls)")
    lines.append("    try:")
    lines.extend(dw.lines or ["        pass"])
    lines.append("    except _DeserErr as _exc:")
    lines.append(f"        raise _DeserErr({_lit(f'{spec.type_name}: %s')} % (_exc,)) from None")
    lines.append("    except (_struct_error, ValueError, OverflowError, MemoryError) as _exc:")
    lines.append(f"        raise _DeserErr({_lit(f'{spec.type_name}: buffer too short or corrupt (%s)')} % (_exc,)) from None")
    lines.append("    return self")

    source = "\n".join(lines) + "\n"
    try:
        code = compile_source(source, f"<rostui msg {spec.type_name}>")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as exc:  # check_spec should make this unreachable
        raise MessageSpecError(f"{spec.type_name}: cannot generate its class ({exc})", spec.source) from None
    exec(code, ns)

    attrs: dict[str, Any] = {
        "__slots__": list(names),  # a list, as in genpy's classes
        "__doc__": f"ROS message {spec.type_name} (generated by rostui).",
        "__module__": "rostui.core.msg.generated",
        "_type": spec.type_name,
        "_md5sum": md5sum,
        "_full_text": full_text,
        "_has_header": spec.has_header,
        "_slot_types": [f.type for f in fields],
        "_defaults": ns["_defaults"],
        "_spec": spec,
        "_field_classes": {t: ns[name] for t, name in cls_vars.items()},
        "_source": source,
        "serialize": ns["serialize"],
        "deserialize": hybridmethod(ns["_deser"]),
    }
    if "__init__" in ns:
        attrs["__init__"] = ns["__init__"]
    for c in spec.constants:
        attrs[attribute_name(c.name)] = c.value
    cls = type(spec.short_name, (Message,), attrs)
    cls.__qualname__ = spec.short_name
    return cls
