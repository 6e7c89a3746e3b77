"""The command line builds only the commands a command line names, and says the same as the whole tree would."""

from __future__ import annotations

import pytest
import typer
from typer.testing import CliRunner

from rostui.cli.main import app, only_the_commands_named

WORDS = [
    ["bag", "play", "--help"],
    ["bag", "pla"],  # a typo: "No such command" with bag's list
    ["bag"],
    ["topic", "echo"],  # a missing argument
    ["param", "get", "--bogus"],
    ["nosuch"],
    ["--help"],
]


def said(words: list[str]) -> tuple[int, str]:
    """Exit code and output of ``rostui WORDS`` run in-process."""
    result = CliRunner().invoke(app, words, prog_name="rostui")
    return result.exit_code, result.output


@pytest.mark.parametrize("words", WORDS, ids=" ".join)
def test_what_a_command_line_says_does_not_change(words: list[str]) -> None:
    whole = said(words)
    with only_the_commands_named(app, words):
        named = said(words)
    assert named == whole


def test_only_the_named_path_is_built_and_the_tree_comes_back_whole() -> None:
    before = set(typer.main.get_command(app).commands)  # type: ignore[attr-defined]
    assert {"bag", "topic", "serve"} <= before
    with only_the_commands_named(app, ["bag", "play", "-r", "2", "x.bag"]):
        root = typer.main.get_command(app)
        assert set(root.commands) == {"bag"}  # type: ignore[attr-defined]
        assert set(root.commands["bag"].commands) == {"play"}  # type: ignore[attr-defined]
    assert set(typer.main.get_command(app).commands) == before  # type: ignore[attr-defined]


def test_serve_gets_every_command_to_look_its_app_up() -> None:
    with only_the_commands_named(app, ["serve", "graph"]):
        assert {"graph", "serve"} <= set(typer.main.get_command(app).commands)  # type: ignore[attr-defined]


def test_each_group_registers_its_own_word_and_its_other_words_only() -> None:
    """groups_for finds a group by the first word of a command line: each group must register exactly its
    name and the other words the registry gives it (a new top-level command elsewhere would be missed)."""
    import importlib

    from rostui.cli.main import groups_for
    from rostui.cli.registry import COMMAND_GROUPS, OTHER_WORDS
    from rostui.cli.tree import _command_name

    for group in COMMAND_GROUPS:
        alone = typer.Typer()
        importlib.import_module(f"rostui.cli.{group}_cmd").register(alone)
        words = {_command_name(c) for c in alone.registered_commands} | {g.name for g in alone.registered_groups}
        assert words == {group, *OTHER_WORDS.get(group, ())}, group
        for word in words:
            assert groups_for([word, "--help"]) == (COMMAND_GROUPS if word == "serve" else (group,))


@pytest.mark.parametrize("words", [[], ["--help"], ["-h"], ["nosuch"], ["serve", "graph"], ["--version"]],
                         ids=lambda w: " ".join(w) or "nothing")
def test_help_typos_and_serve_get_every_group(words: list[str]) -> None:
    from rostui.cli.main import groups_for
    from rostui.cli.registry import COMMAND_GROUPS

    assert groups_for(words) == COMMAND_GROUPS


@pytest.mark.parametrize("words", WORDS + [["srv", "list"], ["teleop", "--help"]], ids=" ".join)
def test_a_tree_of_the_named_group_says_what_the_whole_tree_says(words: list[str]) -> None:
    from rostui.cli.main import groups_for
    from rostui.cli.tree import new_app

    lean = new_app(groups_for(words))
    result = CliRunner().invoke(lean, words, prog_name="rostui")
    assert (result.exit_code, result.output) == said(words)
