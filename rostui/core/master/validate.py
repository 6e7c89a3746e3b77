"""Argument checking for Master API calls, matching rosmaster's codes and messages.

Every API method takes ``caller_id`` first.  :func:`api` wraps a method so a
wrong argument count, a non-string caller_id or an invalid argument returns
``[-1, message, error_value]`` instead of raising, exactly as rosmaster does,
and canonicalises names before the method runs.
"""

from __future__ import annotations

import functools
import logging
from typing import Any, Callable, Sequence

from rostui.core.names import resolve_for_caller as resolve

_log = logging.getLogger("rostui.master")

ANYTYPE = "*"

#: A validator receives (value, caller_id) and returns the canonical value.
Validator = Callable[[Any, str], Any]


class ParameterInvalid(Exception):
    """An API argument failed validation; the message is returned to the caller."""


def non_empty_str(name: str) -> Validator:
    """The argument must be a non-empty string."""
    def check(value: Any, caller_id: str) -> Any:
        if not value:
            raise ParameterInvalid(f"ERROR: parameter [{name}] must be specified and non-empty")
        if not isinstance(value, str):
            raise ParameterInvalid(f"ERROR: parameter [{name}] must be a string")
        return value
    return check


def not_none(name: str) -> Validator:
    """The argument must be present (not nil)."""
    def check(value: Any, caller_id: str) -> Any:
        if value is None:
            raise ParameterInvalid(f"ERROR: parameter [{name}] must be specified")
        return value
    return check


def is_api(name: str) -> Validator:
    """The argument must be an ``http://`` or ``rosrpc://`` URI."""
    def check(value: Any, caller_id: str) -> Any:
        if not value or not isinstance(value, str):
            raise ParameterInvalid(f"ERROR: parameter [{name}] is not an XMLRPC URI")
        if not value.startswith(("http://", "rosrpc://")):
            raise ParameterInvalid(f"ERROR: parameter [{name}] is not an RPC URI")
        return value
    return check


def _resolved_name(name: str, value: Any, caller_id: str) -> str:
    if not value or not isinstance(value, str):
        raise ParameterInvalid(f"ERROR: parameter [{name}] must be a non-empty string")
    if ":" in value or " " in value:
        raise ParameterInvalid(f"ERROR: parameter [{name}] contains illegal chars")
    return resolve(value, caller_id)


def valid_name(name: str) -> Validator:
    """A graph name, resolved against the caller."""
    def check(value: Any, caller_id: str) -> Any:
        return _resolved_name(name, value, caller_id)
    return check


def is_graph_resource(name: str) -> Validator:
    """A topic or service name: resolved, and not the root namespace."""
    def check(value: Any, caller_id: str) -> Any:
        resolved = _resolved_name(name, value, caller_id)
        if value == "/":
            raise ParameterInvalid(f"ERROR: parameter [{name}] cannot be the global namespace")
        return resolved
    return check


def empty_or_valid_name(name: str) -> Validator:
    """A string: empty stays empty, anything else is resolved."""
    def check(value: Any, caller_id: str) -> Any:
        if not isinstance(value, str):
            raise ParameterInvalid(f"ERROR: parameter [{name}] must be a string")
        if not value:
            return ""
        return resolve(value, caller_id)
    return check


def valid_type_name(name: str) -> Validator:
    """A ``package/Type`` name, or ``*``."""
    def check(value: Any, caller_id: str) -> Any:
        if value == ANYTYPE:
            return value
        if not value or not isinstance(value, str):
            raise ParameterInvalid(f"ERROR: parameter [{name}] must be a non-empty string")
        if value.count("/") != 1:
            raise ParameterInvalid(f"ERROR: parameter [{name}] is not a valid package resource name")
        return value
    return check


def api(error_value: Any, validators: Sequence[Validator | None] = ()) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Decorate a Master API method ``f(self, caller_id, ...)`` with rosmaster's checking.

    ``validators`` apply, in order, to the arguments after caller_id; ``None``
    leaves an argument as it is.  Failures return ``(code, message, error_value)``.
    """
    def wrap(f: Callable[..., Any]) -> Callable[..., Any]:
        arity = f.__code__.co_argcount - 1  # without self
        assert len(validators) == arity - 1, f"{f.__name__}: validators do not match arguments"
        name = f.__name__
        checks = tuple(validators)

        @functools.wraps(f)
        def wrapper(self: Any, *args: Any) -> Any:
            if not args:
                return -1, "missing required caller_id parameter", error_value
            if len(args) != arity:
                return -1, "Error: bad call arity", error_value
            caller_id = args[0]
            if not isinstance(caller_id, str):
                return -1, "caller_id must be a string", error_value
            try:
                if checks:
                    fixed = [caller_id]
                    for check, value in zip(checks, args[1:]):
                        if check is None:
                            fixed.append(value)
                        else:
                            try:
                                fixed.append(check(value, caller_id))
                            except ParameterInvalid as exc:
                                return -1, str(exc) or "error", error_value
                    code, msg, val = f(self, *fixed)
                else:
                    code, msg, val = f(self, *args)
                if val is None:
                    return -1, "Internal error (None value returned)", error_value
                return code, msg, val
            except TypeError as exc:
                _log.debug("%s: invalid arguments", name, exc_info=True)
                return -1, f"Error: invalid arguments: {exc}", error_value
            except Exception as exc:
                _log.error("%s: internal failure", name, exc_info=True)
                return 0, f"Internal failure: {exc}", error_value

        return wrapper
    return wrap
