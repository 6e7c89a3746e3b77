"""The `rostui` command tree: a Typer app holding the command groups a command line needs.

Every ``rostui/cli/<group>_cmd.py`` named in :data:`rostui.cli.registry.COMMAND_GROUPS`
exposes ``register(app)``; its command functions import their work lazily.  A
command line gets a tree of the one group its first word names
(:func:`groups_for`: importing and registering all 28 cost 13 ms of every
start), and within it only the command its words name
(:func:`only_the_commands_named`); help, errors and typos get the whole tree.
:mod:`rostui.cli.main` holds the whole tree for what reads every command.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

import typer

from rostui.cli.help_text import reflow_commands
from rostui.cli.registry import COMMAND_GROUPS, OTHER_WORDS, READS_EVERY_COMMAND

CONTEXT = {"help_option_names": ["-h", "--help"]}



def _print_version(value: bool) -> None:
    if value:
        from rostui import __version__

        typer.echo(f"rostui {__version__}")
        raise typer.Exit()


def root(
    version: bool = typer.Option(False, "--version", callback=_print_version, is_eager=True,
                                 help="Print rostui's version and exit."),
) -> None:
    """rostui: roscore, rostopic, rosnode, rosservice, rosparam and friends, in one terminal tool."""


def register_groups(typer_app: typer.Typer, groups: Sequence[str]) -> None:
    """Register the command groups named (``rostui/cli/<group>_cmd.py``) on ``typer_app``, help reflowed."""
    for group in groups:
        importlib.import_module(f"rostui.cli.{group}_cmd").register(typer_app)
    reflow_commands(typer_app)


def groups_for(words: Sequence[str]) -> tuple[str, ...]:
    """The command groups a command line needs: the one whose word (or other word, :data:`OTHER_WORDS`) comes
    first; every group for anything else (no word, an option such as ``--help``, a typo, or a command of
    :data:`READS_EVERY_COMMAND`), so help, errors and suggestions see the whole tree."""
    first = words[0] if words else ""
    if first in COMMAND_GROUPS and first not in READS_EVERY_COMMAND:
        return (first,)
    for group, others in OTHER_WORDS.items():
        if first in others:
            return (group,)
    return COMMAND_GROUPS


def new_app(groups: Sequence[str] = COMMAND_GROUPS) -> typer.Typer:
    """The ``rostui`` Typer app with the command groups ``groups``."""
    typer_app = typer.Typer(
        name="rostui",
        help="The ROS 1 developer toolbox for the terminal.",
        no_args_is_help=True,
        add_completion=True,
        context_settings=CONTEXT,
    )
    typer_app.callback()(root)
    register_groups(typer_app, groups)
    return typer_app


def main() -> None:
    """Console-script entry point: a bare negative number is refused with one line before Typer parses; a
    Ctrl-C that surfaced as another error (see :func:`~rostui.cli.common.interrupted`) exits 130 without a traceback."""
    import sys

    from rostui.cli.common import exit_if_interrupted
    from rostui.cli.negative import looks_negative, refuse_bare_negatives

    words = sys.argv[1:]
    typer_app = new_app(groups_for(words))
    if any(looks_negative(word) for word in words):
        refuse_bare_negatives(typer.main.get_command(typer_app), words)
    try:
        with only_the_commands_named(typer_app, words):
            typer_app()
    except Exception as exc:
        exit_if_interrupted(exc)  # Ctrl-C during a lazy import
        raise


@contextmanager
def only_the_commands_named(typer_app: typer.Typer, words: Sequence[str]) -> Iterator[None]:
    """While inside, ``typer_app`` (and each group on the way) holds only the command or group that ``words``
    name, level by level, as far as they name one.

    Typer builds the click command of every command it holds before it parses a word, which was a third of
    the start of a command that does little (``rostui bag play``: 84 commands and 216 signatures read). What
    runs, its help and its errors are the same; a word that names nothing (an option, a typo, no word at all)
    leaves that level whole, so ``rostui --help`` and "No such command" still list everything. The commands of
    :data:`~rostui.cli.registry.READS_EVERY_COMMAND` get the whole tree.
    """
    kept: list[tuple[typer.Typer, list[Any], list[Any]]] = []
    level: typer.Typer | None = typer_app if words[:1] and words[0] not in READS_EVERY_COMMAND else None
    try:
        for word in words:
            if not isinstance(level, typer.Typer) or word.startswith("-"):
                break
            commands = [c for c in level.registered_commands if _command_name(c) == word]
            groups = [g for g in level.registered_groups if g.name == word]
            if len(commands) + len(groups) != 1:
                break
            kept.append((level, level.registered_commands, level.registered_groups))
            level.registered_commands, level.registered_groups = commands, groups
            level = groups[0].typer_instance if groups else None
        yield
    finally:
        for level_app, commands_before, groups_before in reversed(kept):
            level_app.registered_commands, level_app.registered_groups = commands_before, groups_before


def _command_name(info: Any) -> str:
    """The word that runs a registered Typer command (Typer's own rule: the function's name, dashed)."""
    if info.name:
        return str(info.name)
    return typer.main.get_command_name(info.callback.__name__) if info.callback is not None else ""
