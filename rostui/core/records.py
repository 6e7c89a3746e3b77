"""Record classes with a dataclass's equality, repr, hash and read-only fields, without ``dataclasses``.

Making a dataclass compiles its methods when the class is made (0.3-1 ms a
class), and a rospy talker under ``rostui python`` imports ten record classes
before its first publish. A record class names its fields in ``_fields``, in
its constructor's order, and sets them in its own ``__init__`` (typed, with
its defaults); these bases give the rest from that one tuple.
"""

from __future__ import annotations

from typing import Any, ClassVar

__all__ = ["FrozenRecord", "Record"]


class _FieldsRecord:
    """Equality and repr by ``_fields`` (equality by ``_compared`` where a class gives it)."""

    __slots__ = ()
    _fields: ClassVar[tuple[str, ...]] = ()
    _compared: ClassVar[tuple[str, ...] | None] = None

    def _values(self, names: tuple[str, ...]) -> tuple[Any, ...]:
        return tuple(getattr(self, name) for name in names)

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        assert isinstance(other, _FieldsRecord)
        names = self._fields if self._compared is None else self._compared
        return self._values(names) == other._values(names)

    def __repr__(self) -> str:
        return f"{type(self).__name__}(" + ", ".join(f"{name}={getattr(self, name)!r}" for name in self._fields) + ")"


class Record(_FieldsRecord):
    """A mutable record: equality and repr by its fields; unhashable, as a dataclass with ``eq`` is."""

    __slots__ = ()
    __hash__ = None  # type: ignore[assignment]


class FrozenRecord(_FieldsRecord):
    """An immutable record: its ``__init__`` sets the fields once with :meth:`_set`; hashed and pickled by them (a
    field holding a list makes hashing a TypeError, as a frozen dataclass's)."""

    __slots__ = ()

    def _set(self, *values: Any) -> None:
        """Set every field, in ``_fields`` order (only ``__init__`` calls this)."""
        for name, value in zip(self._fields, values, strict=True):
            object.__setattr__(self, name, value)

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"cannot assign to field {name!r}")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"cannot assign to field {name!r}")

    def __hash__(self) -> int:
        return hash(self._values(self._fields))

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        return type(self), self._values(self._fields)
