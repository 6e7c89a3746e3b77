"""Base classes of generated message and service classes.

This module knows nothing of YAML or of the type registry: ``str()`` and
pickling of messages go through :attr:`Message._text_hook` and
:attr:`Message._unpickle_hook`, which :mod:`rostui.core.msg` installs with
:func:`install_hooks` when the package is imported.
"""

from __future__ import annotations

from collections.abc import Sequence
from types import MethodType
from typing import Any, Callable, ClassVar, Generic, Protocol, TypeAlias, TypeVar, cast, overload

from .spec import MsgSpec, SrvSpec

__all__ = ["Buffer", "Message", "Service", "Writable", "hybridmethod", "install_hooks"]

Buffer: TypeAlias = bytes | bytearray | memoryview
"""What ``deserialize`` reads: a serialized message."""

_M = TypeVar("_M", bound="Message")

_NUMPY_DTYPES = {
    "bool": "bool", "int8": "int8", "byte": "int8", "int16": "int16", "uint16": "uint16", "int32": "int32",
    "uint32": "uint32", "int64": "int64", "uint64": "uint64", "float32": "float32", "float64": "float64",
}


class Writable(Protocol):
    """Where ``serialize(buff)`` writes: anything with ``write(bytes)``, such as ``io.BytesIO``."""

    def write(self, data: bytes, /) -> Any:
        """Append *data*."""


class hybridmethod(Generic[_M]):
    """Descriptor: ``Cls.deserialize(buf)`` builds a new message; ``msg.deserialize(buf)`` fills *msg*.

    The instance form exists for rospy-style code (``m = Cls(); m.deserialize(b)``).
    """

    def __init__(self, func: Callable[[type[_M], Buffer], _M]) -> None:
        """Wrap *func*, a function ``(cls, buf) -> instance``."""
        self.func = func
        self.__doc__ = func.__doc__

    def __get__(self, obj: _M | None, objtype: type[_M] | None = None) -> Callable[[Buffer], _M]:
        """The builder bound to the class, or a function filling *obj* in place."""
        func = self.func
        if obj is None:
            if objtype is None:
                raise TypeError("hybridmethod.__get__ needs an instance or a class")
            return cast(Callable[[Buffer], _M], MethodType(func, objtype))
        cls = objtype if objtype is not None else type(obj)
        target = obj

        def fill(buf: Buffer) -> _M:
            new = func(cls, buf)
            for name in cls.__slots__:
                setattr(target, name, getattr(new, name))
            return target

        return fill


class Message:
    """Base of every generated ROS message class (rospy-like, mutable, slotted).

    The annotations below are what each generated subclass provides: its
    fields (``__slots__``, in order, and their types ``_slot_types``), the
    constants, ``__init__``, ``serialize()`` and ``deserialize()``.
    ``_connection_header`` is a free slot the node layer may set on received messages.
    """

    __slots__: ClassVar[Sequence[str]] = ("_connection_header",)

    _connection_header: dict[str, str]
    """The publisher's connection header, on messages a subscriber received."""

    _type: ClassVar[str] = ""
    """The type name, ``pkg/Name``."""
    _md5sum: ClassVar[str] = ""
    """The md5sum of the definition, as genmsg computes it."""
    _full_text: ClassVar[str] = ""
    """The ``message_definition``: own text, then each nested type."""
    _has_header: ClassVar[bool] = False
    """True when the first field is a ``std_msgs/Header`` named ``header``."""
    _slot_types: ClassVar[list[str]] = []
    """The type of each field, in field order (``float64[9]``, ``std_msgs/Header``)."""
    _defaults: ClassVar[dict[str, Callable[[], Any]]] = {}
    """For each field, a function building its default value."""
    _spec: ClassVar[MsgSpec | None] = None
    """The parsed definition the class was generated from."""
    _field_classes: ClassVar[dict[str, type[Message]]] = {}
    """The class of each message type its fields hold, by type name (from the same definition as this one)."""
    _source: ClassVar[str]
    """The generated Python source of ``__init__``, ``serialize`` and ``deserialize``."""

    deserialize: ClassVar[hybridmethod[Message]]
    """``Cls.deserialize(buf)`` builds a message from wire bytes; ``msg.deserialize(buf)`` fills *msg*."""

    _text_hook: ClassVar[Callable[[Message], str]]
    """Renders a message for ``str()`` (installed by :func:`install_hooks`)."""
    _unpickle_hook: ClassVar[Callable[[str, str, str], Message]]
    """``(type, md5sum, full_text)`` to an empty instance when unpickling (installed by :func:`install_hooks`)."""

    def __init__(self, *args: Any, **kwds: Any) -> None:
        """Fill fields from positional values (field order) and keywords; the rest get defaults."""
        slots = self.__slots__
        if len(args) > len(slots):
            raise TypeError(f"{self._type}: expected at most {len(slots)} positional arguments, got {len(args)}")
        for key in kwds:
            if key not in slots:
                raise TypeError(f"{key} is not a field of {self._type}")
        for i, name in enumerate(slots):
            if i < len(args):
                if name in kwds:
                    raise TypeError(f"{self._type}: field {name} given twice")
                value = args[i]
            else:
                value = kwds.get(name)
            setattr(self, name, self._defaults[name]() if value is None else value)

    @overload
    def serialize(self) -> bytes: ...
    @overload
    def serialize(self, buff: Writable) -> None: ...
    def serialize(self, buff: Writable | None = None) -> bytes | None:  # pragma: no cover - replaced in generated classes
        """The message in ROS 1 wire format; with *buff* (genpy's form) written there instead."""
        raise NotImplementedError

    def serialize_numpy(self, buff: Writable, numpy: Any) -> None:
        """genpy's numpy form of :meth:`serialize`: numeric arrays may be numpy arrays (*numpy* is the module)."""
        self.serialize(buff)

    def deserialize_numpy(self, data: Buffer, numpy: Any) -> Message:
        """Fill this message from *data* as genpy does, numeric arrays as numpy arrays (*numpy* is the module)."""
        filled = self.deserialize(data)
        _arrays_to_numpy(filled, numpy)
        return filled

    def _get_types(self) -> list[str]:
        """The field types, in field order (genpy compatibility)."""
        return list(self._slot_types)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Message) or other._type != self._type:
            return False
        return all(getattr(self, n) == getattr(other, n) for n in self.__slots__)

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)

    __hash__ = None  # type: ignore[assignment]  # mutable, like genpy messages

    def __str__(self) -> str:
        return Message._text_hook(self)

    def __repr__(self) -> str:
        return self.__str__()

    def __getstate__(self) -> list[Any]:
        return [getattr(self, n) for n in self.__slots__]

    def __setstate__(self, state: list[Any]) -> None:
        for n, v in zip(self.__slots__, state):
            setattr(self, n, v)

    def __reduce__(self) -> tuple[Callable[[str, str, str], Message], tuple[str, str, str], list[Any]]:
        return (Message._unpickle_hook, (self._type, self._md5sum, self._full_text), self.__getstate__())


def _arrays_to_numpy(msg: Message, numpy: Any) -> None:
    """Turn *msg*'s numeric array fields (nested messages too) into numpy arrays, as genpy's numpy mode does."""
    for name, slot_type in zip(msg.__slots__, msg._slot_types):
        value = getattr(msg, name)
        base, is_array = slot_type.split("[", 1)[0], "[" in slot_type
        if isinstance(value, Message):
            _arrays_to_numpy(value, numpy)
        elif is_array and base in _NUMPY_DTYPES:
            setattr(msg, name, numpy.array(value, dtype=_NUMPY_DTYPES[base]))
        elif is_array:
            for item in value:
                if isinstance(item, Message):
                    _arrays_to_numpy(item, numpy)


class Service:
    """Base of generated service classes: holds the request and response classes."""

    _type: ClassVar[str] = ""
    """The service type name, ``pkg/Name``."""
    _md5sum: ClassVar[str] = ""
    """The md5sum of request and response definitions together."""
    _request_class: ClassVar[type[Message]]
    """The generated class of ``pkg/NameRequest``."""
    _response_class: ClassVar[type[Message]]
    """The generated class of ``pkg/NameResponse``."""
    _spec: ClassVar[SrvSpec]
    """The parsed definition the class was generated from."""


def install_hooks(
    *,
    text: Callable[[Message], str],
    unpickle: Callable[[str, str, str], Message],
) -> None:
    """Give every message its ``str()`` (*text*) and its unpickling constructor (*unpickle*)."""
    Message._text_hook = text
    Message._unpickle_hook = unpickle
