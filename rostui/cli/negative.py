"""A negative number where an option may stand (``rostui param set /p -3``): say to put ``--`` first.

The option parser reads ``-3`` as an unknown option, and ``-1.5`` after
``topic pub`` as its ``-1`` flag followed by ``.5``; rostopic and rosparam
behave the same way, and ROS's answer is ``--`` before the arguments.  This
module finds such a word before Typer parses the command line, from the
command's own declared options, so the user gets one line with the command
line that works.
"""

from __future__ import annotations

import re
import shlex
from typing import Any, Sequence

NEGATIVE = re.compile(r"-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")
"""A negative integer or float as a shell word (``-3``, ``-1.5``, ``-.5``, ``-2e-3``)."""

TAKE_NEGATIVES = frozenset({("dynparam", "set")})
"""Commands that read a negative number as an argument (they keep unknown options as arguments), as the ROS
tool does: ``dynparam set NODE int_ -30``."""


def looks_negative(word: str) -> bool:
    """True for a word that is a negative number."""
    return NEGATIVE.fullmatch(word) is not None


def _leaf(root: Any, argv: Sequence[str]) -> tuple[Any, list[str], list[str]] | None:
    """The command ``argv`` names, the words naming it and the words after them (None: no such command)."""
    command, rest = root, list(argv)
    path: list[str] = []
    while hasattr(command, "commands"):
        names = [w for w in rest if not w.startswith("-")]
        if not names:
            return None
        position = rest.index(names[0])
        sub = command.get_command(command.context_class(command), names[0])
        if sub is None:
            return None
        command, path, rest = sub, [*path, *rest[:position + 1]], rest[position + 1:]
    return command, path, rest


def _option_arity(command: Any) -> dict[str, bool]:
    """Each option spelling of ``command`` -> whether it takes a value."""
    arity: dict[str, bool] = {}
    for param in command.params:
        if getattr(param, "param_type_name", "") != "option":
            continue
        takes_value = not getattr(param, "is_flag", False) and not getattr(param, "count", False)
        for spelling in [*param.opts, *param.secondary_opts]:
            arity[spelling] = takes_value
    return arity


def bare_negative(root: Any, argv: Sequence[str]) -> tuple[str, str] | None:
    """The first negative number in ``argv`` the parser would take for an option, and the command line with ``--``.

    ``root`` is the Click command Typer builds.  None when there is none: numbers
    after ``--``, values of options (``-r -1``), words after the first argument
    of a command that stops reading options there (``service call``, ``run``)
    and spellings that are options (``topic pub -1``) are left alone, and so are numbers given to the commands
    of :data:`TAKE_NEGATIVES`, as long as they do not start with one of their options.
    """
    found = _leaf(root, argv)
    if found is None:
        return None
    command, path, rest = found
    arity = _option_arity(command)
    settings = getattr(command, "context_settings", None) or {}
    interspersed = settings.get("allow_interspersed_args", getattr(command, "allow_interspersed_args", True))
    takes_negatives = tuple(path) in TAKE_NEGATIVES
    options: list[str] = []
    positionals: list[str] = []
    culprit: str | None = None
    words = iter(rest)
    for word in words:
        if word == "--" or (positionals and not interspersed):
            break
        name = word.split("=", 1)[0]
        if name in arity:
            options.append(word)
            if arity[name] and "=" not in word:
                value = next(words, None)
                if value is not None:
                    options.append(value)
            continue
        if looks_negative(word):
            if not (takes_negatives and word[:2] not in arity):
                culprit = culprit or word
            positionals.append(word)
        elif word.startswith("-") and word != "-":
            options.append(word)
        else:
            positionals.append(word)
    if culprit is None:
        return None
    tail = rest[len(options) + len(positionals):]
    fixed = ["rostui", *path, *options, "--", *positionals, *(tail[1:] if tail[:1] == ["--"] else tail)]
    return culprit, shlex.join(fixed)


def refuse_bare_negatives(root: Any, argv: Sequence[str]) -> None:
    """Exit 2 with one line when ``argv`` holds a negative number the parser would take for an option."""
    found = bare_negative(root, argv)
    if found is None:
        return
    word, fixed = found
    from rostui.cli.common import fail

    fail(f"ERROR: negative numbers need `--` first, as with rostopic and rosparam ({word} reads as an option): "
         f"{fixed}", 2)
