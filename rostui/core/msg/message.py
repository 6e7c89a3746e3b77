"""Base classes of generated message and service classes."""

from __future__ import annotations

from typing import Any, Callable, ClassVar

__all__ = ["Message", "Service", "hybridmethod"]


class hybridmethod:
    """Descriptor: ``Cls.deserialize(buf)`` builds a new message; ``msg.deserialize(buf)`` fills *msg*.

    The instance form exists for rospy-style code (``m = Cls(); m.deserialize(b)``).
    """

    def __init__(self, func: Callable[..., Any]) -> None:
        """Wrap *func*, a function ``(cls, buf) -> instance``."""
        self.func = func
        self.__doc__ = func.__doc__

    def __get__(self, obj: Any, objtype: type | None = None) -> Callable[..., Any]:
        cls = objtype if objtype is not None else type(obj)
        func = self.func
        if obj is None:
            return func.__get__(cls, type(cls))

        def fill(buf: bytes | bytearray | memoryview) -> Any:
            new = func(cls, buf)
            for name in cls.__slots__:
                setattr(obj, name, getattr(new, name))
            return obj

        return fill


class Message:
    """Base of every generated ROS message class (rospy-like, mutable, slotted).

    Generated subclasses define ``_type``, ``_md5sum``, ``_full_text``,
    ``_has_header``, ``__slots__`` (the field names, in order), ``_slot_types``,
    the constants, ``__init__``, ``serialize()`` and ``deserialize()``.
    ``_connection_header`` is a free slot the node layer may set on received messages.
    """

    __slots__ = ("_connection_header",)

    _type: ClassVar[str] = ""
    _md5sum: ClassVar[str] = ""
    _full_text: ClassVar[str] = ""
    _has_header: ClassVar[bool] = False
    _slot_types: ClassVar[list[str]] = []
    _defaults: ClassVar[dict[str, Callable[[], Any]]] = {}
    _spec: ClassVar[Any] = None

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

    def serialize(self) -> bytes:  # pragma: no cover - replaced in generated classes
        """The message in ROS 1 wire format."""
        raise NotImplementedError

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
        from .convert import message_to_yaml

        return message_to_yaml(self)

    def __repr__(self) -> str:
        return self.__str__()

    def __getstate__(self) -> list[Any]:
        return [getattr(self, n) for n in self.__slots__]

    def __setstate__(self, state: list[Any]) -> None:
        for n, v in zip(self.__slots__, state):
            setattr(self, n, v)

    def __reduce__(self) -> tuple[Any, ...]:
        from .registry import _reconstruct

        return (_reconstruct, (self._type, self._md5sum, self._full_text), self.__getstate__())


class Service:
    """Base of generated service classes: holds the request and response classes."""

    _type: ClassVar[str] = ""
    _md5sum: ClassVar[str] = ""
    _request_class: ClassVar[type[Message]]
    _response_class: ClassVar[type[Message]]
