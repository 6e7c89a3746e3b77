"""`rostui bag play FILE... [OPTIONS]` without Typer: the form scripts and launch files start a player with.

Loading Typer costs a player 16 ms of CPU, a sixth of a start (bench/README.md,
"Bag play CPU", eighth pass). A command line made only of bags, ``name:=value``
words and the options of :data:`PLAY_OPTIONS` written as ``-r 4``,
``--rate 4`` or ``--rate=4`` is read here into the same parameters Typer would
give :func:`~rostui.cli.bag_run.run_play` (a test holds the two to each other).
Anything else (``--help``, ``-r4``, ``-lq``, ``--``, a value Typer would
refuse, a word that starts with ``-`` where a value stands, no bag) goes to the
full CLI, which says what it always said.
"""

from __future__ import annotations

TYPE_CHECKING = False
if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from typing import Any

#: The options of ``bag play``: each spelling, the parameter it sets and how its value is read (``bool``: a flag,
#: ``list``: repeated, each a string).
PLAY_OPTIONS: dict[str, tuple[str, Callable[[str], Any]]] = {
    "-r": ("rate", float), "--rate": ("rate", float),
    "-l": ("loop_play", bool), "--loop": ("loop_play", bool),
    "--pause": ("pause", bool),
    "-s": ("start", float), "--start": ("start", float),
    "-u": ("duration", float), "--duration": ("duration", float),
    "-d": ("delay", float), "--delay": ("delay", float),
    "--clock": ("clock", bool),
    "--hz": ("hz", float),
    "--topics": ("topics", list),
    "--queue": ("queue", int),
    "-q": ("quiet", bool), "--quiet": ("quiet", bool),
}

DEFAULTS: dict[str, Any] = {"rate": 1.0, "loop_play": False, "pause": False, "start": 0.0, "duration": None,
                            "delay": 0.2, "clock": False, "hz": 100.0, "topics": None, "queue": 100,
                            "quiet": False}
"""What each parameter is when its option is not given, as ``bag play``'s Typer command declares it."""


def parse_plain(words: Sequence[str]) -> tuple[list[str], dict[str, Any]] | None:
    """The arguments and the options of a plain ``bag play`` command line (see the module's docstring); None
    for any other, which the full CLI reads."""
    args: list[str] = []
    params = dict(DEFAULTS)
    at = 0
    while at < len(words):
        word = words[at]
        at += 1
        if not word.startswith("-"):
            args.append(word)
            continue
        name, equals, value = word.partition("=")
        if name not in PLAY_OPTIONS:
            return None
        param, kind = PLAY_OPTIONS[name]
        if kind is bool:
            if equals:
                return None
            params[param] = True
            continue
        if not equals:
            if at == len(words):
                return None
            value = words[at]
            at += 1
        if value.startswith("-"):
            return None
        if kind is list:
            params[param] = [*(params[param] or []), value]
            continue
        try:
            params[param] = kind(value)
        except ValueError:
            return None
    return (args, params) if args else None


def run_plain(words: Sequence[str]) -> int | None:
    """Play as ``rostui bag play WORDS`` does when WORDS are plain; None (nothing done) otherwise."""
    parsed = parse_plain(words)
    if parsed is None:
        return None
    from rostui.compat.deferred import import_lean
    from rostui.core.startup_gc import collect_rarely

    collect_rarely()
    import_lean()
    args, params = parsed
    try:
        from rostui.cli.bag_run import run_play

        return run_play(args, **params)
    except (KeyboardInterrupt, Exception) as exc:  # Ctrl-C before the player's handlers: 130, as Typer ends it
        from rostui.cli.common import exit_if_interrupted

        exit_if_interrupted(exc)
        raise
