"""roslaunch substitution args: ``$(find)``, ``$(arg)``, ``$(anon)``, ``$(env)``, ``$(optenv)``,
``$(eval)`` and ``$(dirname)``.

The text is scanned for ``$(command args)`` spans; ``env``, ``optenv``,
``dirname``, ``anon`` and ``arg`` are replaced first, ``find`` afterwards (so
``$(find $(arg pkg))`` works), each replacing the first occurrence of its exact
span, like roslaunch.  A whole value of the form ``$(eval EXPR)`` is a Python
expression over the args, with the math functions and ``env``/``optenv``/
``find``/``anon``/``arg``/``dirname`` callables.
"""

from __future__ import annotations

import math
import os
import random
import socket
import sys
from dataclasses import dataclass, field
from typing import Any, Callable

from rostui.core import packages
from rostui.launch.errors import ArgNotSetError, LaunchError
from rostui.launch.values import convert_value

COMMANDS = ("find", "env", "optenv", "dirname", "anon", "arg")


@dataclass
class SubstitutionContext:
    """What substitutions see: the args in scope, the anon names of this launch and the current file."""

    args: dict[str, str] = field(default_factory=dict)
    anons: dict[str, str] = field(default_factory=dict)
    filename: str | None = None


def _spans(text: str) -> list[str]:
    """The inner texts of the ``$( ... )`` spans of ``text``, in order."""
    spans: list[str] = []
    state = "out"
    buffer: list[str] = []
    for char in text:
        if char == "$":
            if state in ("in", "lp"):
                raise LaunchError(f"Dollar signs '$' cannot be inside of substitution args [{text}]")
            state = "dollar"
        elif char == "(":
            if state == "dollar":
                state = "lp"
            elif state != "out":
                raise LaunchError(f"Invalid left parenthesis '(' in substitution args [{text}]")
        elif char == ")":
            if state == "in":
                spans.append("".join(buffer))
                buffer = []
            state = "out"
        elif state == "dollar":
            state = "out"
        elif state == "lp":
            state = "in"
        if state == "in":
            buffer.append(char)
    return spans


def _env_value(name: str) -> str:
    try:
        return os.environ[name]
    except KeyError:
        raise LaunchError(f"environment variable '{name}' is not set") from None


def _find(name: str) -> str:
    path = packages.find_package(name)
    if path is None:
        raise LaunchError(f"$(find {name}): package '{name}' not found")
    return str(path)


def launch_anonymous_name(base: str) -> str:
    """roslaunch's anonymous name: ``base_<host>_<pid>_<random>`` (host with ``-``/``.`` as ``_``)."""
    host = socket.gethostname().replace("-", "_").replace(".", "_").replace(":", "_")
    return f"{base}_{host}_{os.getpid()}_{random.randint(0, sys.maxsize)}"


def _anon(base: str, ctx: SubstitutionContext) -> str:
    if base not in ctx.anons:
        ctx.anons[base] = launch_anonymous_name(base)
    return ctx.anons[base]


def _dirname(ctx: SubstitutionContext) -> str:
    if not ctx.filename:
        raise LaunchError("Cannot substitute $(dirname), no file/directory information available.")
    return os.path.abspath(os.path.dirname(ctx.filename))


def _arg(name: str, ctx: SubstitutionContext) -> str:
    try:
        return ctx.args[name]
    except KeyError:
        raise ArgNotSetError(name) from None


def _replace_find(text: str, token: str, package_dir: str) -> str:
    """Replace ``token`` by the package directory joined with the word right after it (as roslaunch does)."""
    start = text.find(token)
    before, after = text[:start], text[start + len(token):]
    cut = after.find(" ")
    path, rest = (after, "") if cut < 0 else (after[:cut], after[cut:])
    if path.startswith("/"):
        path = path[1:]
    if not path:
        return before + package_dir + after
    return before + os.path.join(package_dir, path) + rest


def _replace_one(text: str, span: str, ctx: SubstitutionContext, phase: str) -> str:
    words = span.split()
    if not words or words[0] not in COMMANDS:
        raise LaunchError(f"Unknown substitution command [{span}]. Valid commands are {list(COMMANDS)}")
    command, args = words[0], words[1:]
    token = f"$({span})"
    if phase == "find":
        if command != "find":
            return text
        if len(args) != 1:
            raise LaunchError(f"$(find pkg) command only accepts one argument [{span}]")
        return _replace_find(text, token, _find(args[0]))
    if command == "env":
        if len(args) != 1:
            raise LaunchError(f"$(env var) command only accepts one argument [{span}]")
        value = _env_value(args[0])
    elif command == "optenv":
        if not args:
            raise LaunchError(f"$(optenv var) must specify an environment variable [{span}]")
        value = os.environ.get(args[0], " ".join(args[1:]))
    elif command == "dirname":
        value = _dirname(ctx)
    elif command == "anon":
        if len(args) != 1:
            raise LaunchError(f"$(anon var) must specify exactly one name [{span}]")
        value = _anon(args[0], ctx)
    elif command == "arg":
        if len(args) != 1:
            raise LaunchError(f"$(arg var) must specify exactly one arg name [{span}]")
        value = _arg(args[0], ctx)
    else:
        return text
    return text.replace(token, value, 1)


class _EvalNames(dict):
    """Names an ``$(eval)`` expression sees: functions first, then args converted like param values."""

    def __init__(self, functions: dict[str, Any], args: dict[str, str]) -> None:
        super().__init__()
        self._functions = functions
        self._args = args

    def __getitem__(self, key: str) -> Any:
        if key in self._functions:
            return self._functions[key]
        if key in self._args:
            return convert_value(self._args[key], "auto")
        raise NameError(f"name '{key}' is not defined")


def _eval(expression: str, ctx: SubstitutionContext) -> str:
    if "__" in expression:
        raise LaunchError("$(eval ...) may not contain double underscore expressions")
    functions: dict[str, Callable[..., Any] | Any] = {name: getattr(math, name) for name in dir(math)
                                                      if not name.startswith("_")}
    functions.update({
        "true": True, "false": False, "True": True, "False": False,
        "list": list, "dict": dict, "map": map, "str": str, "float": float, "int": int,
        "env": _env_value, "optenv": lambda name, default="": os.environ.get(name, default),
        "find": _find, "anon": lambda base: _anon(base, ctx),
        "arg": lambda name: convert_value(_arg(name, ctx), "auto"), "dirname": lambda: _dirname(ctx),
    })
    try:
        return str(eval(expression, {"__builtins__": {}}, _EvalNames(functions, ctx.args)))  # noqa: S307
    except LaunchError:
        raise
    except Exception as exc:  # the user's expression: any Python error is theirs to see
        raise LaunchError(f"$(eval {expression}) failed: {type(exc).__name__}: {exc}") from None


def resolve(text: str | None, ctx: SubstitutionContext) -> str | None:
    """``text`` with every substitution arg replaced (None and text without ``$`` unchanged)."""
    if not text or "$" not in text:
        return text
    if text.startswith("$(eval ") and text.endswith(")"):
        return _eval(text[7:-1], ctx)
    for phase in ("plain", "find"):
        for span in _spans(text):
            text = _replace_one(text, span, ctx, phase)
    return text
