"""What `rostui param` does, as plain functions: rosparam's YAML typing, output and file formats.

Every function here either transforms values or talks to the master through
``call(method, *args)``, a callable that returns the unwrapped value of a
Master API call (the CLI binds the caller id and handles an absent master).
Nothing is sent to the server before the whole input has been parsed and
checked, so malformed YAML never leaves a half-applied change behind.
"""

from __future__ import annotations

import os
import re
from typing import Any, Callable, Iterable

from .param_quick import script_resolve, simple_value_text

__all__ = [
    "ParamError",
    "script_resolve",
    "parse_value",
    "leaf_assignments",
    "check_marshallable",
    "format_get",
    "format_dump",
    "list_names",
    "load_text",
    "set_param",
    "apply_assignments",
    "delete_param",
]

Call = Callable[..., Any]

#: Largest integer XML-RPC (i4) can carry.
_INT_MAX = 2**31 - 1


class ParamError(Exception):
    """A one-line, user-facing reason why a parameter command cannot proceed."""


# --------------------------------------------------------------------------- YAML typing

_ANGLE = re.compile(r"^\s*!(degrees|radians)\s+(.+)$")


def _loader() -> Any:
    """A SafeLoader that also understands rosparam's ``!degrees`` and ``!radians`` tags."""
    import yaml

    class Loader(yaml.SafeLoader):
        pass

    def angle(factor: float) -> Callable[[Any, Any], float]:
        def construct(loader: Any, node: Any) -> float:
            text = str(loader.construct_scalar(node)).strip()
            return _angle_value(text) * factor

        return construct

    import math

    Loader.add_constructor("!degrees", angle(math.pi / 180.0))
    Loader.add_constructor("!radians", angle(1.0))
    return Loader


def _angle_value(text: str) -> float:
    """A number, optionally written with ``pi`` (``pi/2``, ``2*pi``, ``-pi``): no eval."""
    import math

    t = text.replace(" ", "")
    m = re.fullmatch(r"([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)?(\*?pi)?(?:/((?:\d+(?:\.\d*)?|\.\d+)))?", t)
    if not m or not (m.group(1) or m.group(2)):
        raise ParamError(f"invalid angle [{text}]")
    coef = m.group(1)
    value = float(coef) if coef not in (None, "+", "-") else (-1.0 if coef == "-" else 1.0)
    if m.group(2):
        value *= math.pi
    if m.group(3):
        value /= float(m.group(3))
    return value


def _yaml_error_line(exc: Exception, source: str | None) -> str:
    """``file:line:col: problem`` (or ``line L, column C: problem``) from a YAML error."""
    mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
    problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
    context = getattr(exc, "context", None)
    text = f"{context}: {problem}" if context else str(problem)
    if mark is None:
        return f"{source}: {text}" if source else text
    if source:
        return f"{source}:{mark.line + 1}:{mark.column + 1}: {text}"
    return f"line {mark.line + 1}, column {mark.column + 1}: {text}"


def parse_value(text: str) -> Any:
    """Type a command-line value the way rosparam does (one YAML document).

    ``1.0`` is a float, ``'1'`` and ``!!str 5`` strings, ``[1, 2]`` a list, a
    multi-line ``key: value`` block a dict.  Raises ParamError for bad YAML.
    """
    import yaml
    try:
        return yaml.load(text, Loader=_loader())
    except yaml.YAMLError as exc:
        raise ParamError(f"ERROR: invalid YAML value: {_yaml_error_line(exc, None)}") from None


def check_marshallable(name: str, value: Any) -> None:
    """Refuse values the parameter server cannot hold (None, huge ints, dates, odd keys)."""
    import datetime

    from rostui.core import names

    if value is None:
        raise ParamError(f"ERROR: cannot set [{name}] to null: the parameter server has no null value")
    if isinstance(value, bool) or isinstance(value, (float, str, bytes)):
        return
    if isinstance(value, int):
        if not -_INT_MAX - 1 <= value <= _INT_MAX:
            raise ParamError(f"ERROR: cannot set [{name}] to {value}: integers must fit in 32 bits")
        return
    if isinstance(value, (datetime.date, datetime.datetime)):
        raise ParamError(f"ERROR: cannot set [{name}] to a date ({value}); quote it to store a string")
    if isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            check_marshallable(f"{name}[{i}]", item)
        return
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str):
                raise ParamError(f"ERROR: cannot set [{name}]: dictionary key {key!r} is not a string")
            check_marshallable(names.join_names(name, key), item)
        return
    raise ParamError(f"ERROR: cannot set [{name}] to a value of type {type(value).__name__}")


def leaf_assignments(name: str, value: Any) -> list[tuple[str, Any]]:
    """The ``setParam`` calls rosparam makes for ``name = value``.

    A dictionary is merged key by key into what is already stored (nested
    dictionaries too), so setting ``{huey: x}`` on ``/duck_colors`` keeps the
    other ducks; an empty dictionary sets nothing.  Anything else is one call.
    """
    from rostui.core import names

    if isinstance(value, dict):
        out: list[tuple[str, Any]] = []
        for key, item in value.items():
            out.extend(leaf_assignments(names.join_names(name, str(key)), item))
        return out
    return [(name, value)]


def apply_assignments(call: Call, assignments: Iterable[tuple[str, Any]]) -> None:
    """Send the ``setParam`` calls."""
    for key, value in assignments:
        call("setParam", key, _to_wire(value))


def _to_wire(value: Any) -> Any:
    if isinstance(value, bytes):
        from xmlrpc.client import Binary

        return Binary(value)
    if isinstance(value, tuple):
        return [_to_wire(v) for v in value]
    if isinstance(value, list):
        return [_to_wire(v) for v in value]
    return value


def set_param(call: Call, name: str, text: str) -> None:
    """``rosparam set NAME VALUE``: parse and check first, then set."""
    value = parse_value(text)
    check_marshallable(name, value)
    apply_assignments(call, leaf_assignments(name, value))


def delete_param(call: Call, name: str) -> None:
    """``rosparam delete NAME``; a missing parameter is a ParamError with rosparam's words."""
    from rostui.core.xmlrpc import RosApiError

    try:
        call("deleteParam", name)
    except RosApiError:
        raise ParamError(f"ERROR: parameter [{name}] is not set") from None


# --------------------------------------------------------------------------- output


def _plain(value: Any) -> Any:
    """XML-RPC values as YAML-friendly Python values (Binary -> bytes, nested)."""
    data = getattr(value, "data", None)
    if isinstance(data, bytes) and type(value).__name__ == "Binary":
        return data
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_plain(v) for v in value]
    return value


def format_get(value: Any) -> str:
    """What ``rosparam get`` prints (without the final newline print adds).

    A dictionary or list is block YAML ending in a newline (so a blank line
    follows it); a scalar is its YAML form without the ``...`` end marker.
    """
    simple = simple_value_text(value)
    if simple is not None:
        return simple
    import yaml
    text = yaml.safe_dump(_plain(value), default_flow_style=False)
    if text.endswith("\n...\n"):
        text = text[: -len("\n...\n")]
    return text


def format_dump(value: Any) -> str:
    """The text ``rosparam dump`` writes to its file."""
    import yaml
    return yaml.safe_dump(_plain(value), default_flow_style=False)


def list_names(all_names: Iterable[str], namespace: str | None) -> list[str]:
    """``rosparam list [NS]``: sorted names, those under ``namespace`` when given."""
    found = sorted(all_names)
    if namespace:
        found = [n for n in found if n.startswith(namespace)]
    return found


# --------------------------------------------------------------------------- files


def load_text(text: str, namespace: str, source: str) -> list[tuple[str, Any]]:
    """Parse a parameter file (one or more YAML documents) into ``setParam`` assignments.

    Each document must be a dictionary; a ``_ns`` key moves that document
    into a sub-namespace.  Errors carry ``source:line:column``.
    """
    from rostui.core import names

    import yaml
    docs: list[Any] = []
    try:
        for doc in yaml.load_all(text, Loader=_loader()):
            docs.append(doc)
    except yaml.YAMLError as exc:
        raise ParamError(f"ERROR: {_yaml_error_line(exc, source)}") from None
    except ParamError as exc:
        raise ParamError(f"ERROR: {source}: {exc}") from None
    assignments: list[tuple[str, Any]] = []
    for doc in docs:
        if doc is None:
            continue
        if not isinstance(doc, dict):
            raise ParamError(f"ERROR: {source}: a parameter file must hold a dictionary, "
                             f"not {type(doc).__name__} ({doc!r:.40})")
        ns = namespace
        if "_ns" in doc:
            doc = dict(doc)
            ns = names.resolve_name(str(doc.pop("_ns")), namespace)
        check_marshallable(ns, doc)
        assignments.extend(leaf_assignments(ns, doc))
    return assignments


def read_param_file(path: str) -> str:
    """The text of a parameter file (``-`` is stdin); ParamError in rosparam's words if absent."""
    import sys

    if path == "-":
        return sys.stdin.read()
    if not os.path.isfile(path):
        raise ParamError(f"ERROR: file [{path}] does not exist")
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except (OSError, UnicodeDecodeError) as exc:
        raise ParamError(f"ERROR: cannot read [{path}]: {exc}") from None
