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
