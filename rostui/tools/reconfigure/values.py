"""A value a user typed, as the type a reconfigure server declared for the parameter, as dynamic_reconfigure's
client converts it: a bool from "yes"/"true"/"t"/"1", an enum value from its constant's name, a number from its
text. An enum's ``edit_method`` (text the server sends) is read as a Python literal, never evaluated as code.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable, Mapping
from typing import Any

__all__ = ["ParameterValueError", "TYPES", "convert_value", "enum_constants", "type_of"]

TYPES: dict[str, type] = {"int": int, "double": float, "str": str, "bool": bool}
"""The parameter types a ``.cfg`` file declares, as Python types."""
_TRUE_WORDS = ("yes", "true", "t", "1")


class ParameterValueError(ValueError):
    """A parameter that is not the server's, or a value that is not of its type (dynamic_reconfigure's words)."""


def type_of(type_name: str) -> type:
    """The Python type of a declared parameter type ("int", "double", "str", "bool")."""
    try:
        return TYPES[type_name]
    except KeyError:
        raise ParameterValueError(
            f"parameter has unknown type: {type_name}. This is a bug in dynamic_reconfigure.") from None


def enum_constants(edit_method: str) -> list[dict[str, Any]]:
    """The constants of an enum's ``edit_method`` text ([] when it is no enum or cannot be read)."""
    if not edit_method:
        return []
    try:
        described = ast.literal_eval(edit_method)
        constants = described["enum"]
    except (ValueError, TypeError, SyntaxError, KeyError, MemoryError, RecursionError):
        return []
    return [c for c in constants if isinstance(c, dict)] if isinstance(constants, list) else []


def convert_value(descriptions: Iterable[Mapping[str, Any]], name: str, value: Any) -> Any:
    """*value* as the declared type of parameter *name* among the server's parameter *descriptions*."""
    descriptions = list(descriptions)
    exact = next((d for d in descriptions if d.get("name") == name and d.get("type") is not None), None)
    if exact is None:
        raise ParameterValueError(f"don't know parameter: {name}")
    dest_type = type_of(str(exact["type"]))
    # the first description whose name matches in any case, as dynamic_reconfigure's client picks it
    described = next(d for d in descriptions if str(d.get("name", "")).lower() == name.lower())
    try:
        if dest_type is bool and type(value) is str:
            return value.lower() in _TRUE_WORDS
        if type(value) is str and described.get("edit_method"):
            converted: Any = None
            for const in enum_constants(str(described["edit_method"])):
                if value.lower() == str(const.get("name", "")).lower():
                    converted = type_of(str(const.get("type")))(const["value"])
            if converted is not None:
                return converted
        return dest_type(value)
    except ValueError as exc:
        raise ParameterValueError(f"can't set parameter '{name}' of {dest_type}: {exc}") from exc
