"""`rostui bag play` read without Typer (rostui.cli.bag_play_fast) reads what Typer reads, or leaves it to Typer."""

from __future__ import annotations

from typing import Any

import pytest
import typer

from rostui.cli import bag_cmd
from rostui.cli.bag_play_fast import DEFAULTS, PLAY_OPTIONS, parse_plain


def _typer_play() -> Any:
    """The click command Typer makes of ``bag play`` (Typer keeps its own copy of click)."""
    return typer.main.get_command(bag_cmd.bag_app).commands["play"]  # type: ignore[attr-defined]


def _typer_call(words: list[str], monkeypatch: pytest.MonkeyPatch) -> tuple[list[str], dict[str, Any]]:
    """What Typer's ``bag play`` hands :func:`run_play` for ``words``."""
    calls: list[tuple[list[str], dict[str, Any]]] = []

    def capture(args: list[str], **params: Any) -> int:
        calls.append((args, params))
        return 0

    monkeypatch.setattr(bag_cmd, "run_play", capture)
    _typer_play().main(args=list(words), prog_name="play", standalone_mode=False)
    return calls[0]


def test_the_table_holds_every_option_of_the_typer_command_and_nothing_else() -> None:
    seen: dict[str, str] = {}
    for param in _typer_play().params:
        if param.param_type_name != "option" or param.name == "help":
            continue
        for spelling in [*param.opts, *param.secondary_opts]:
            seen[spelling] = param.name
            name, kind = PLAY_OPTIONS[spelling]
            assert name == param.name, spelling
            if param.is_flag:
                assert kind is bool, spelling
            elif param.multiple:
                assert kind is list, spelling
            else:
                assert kind is {"float": float, "int": int}[param.type.name], spelling
        assert DEFAULTS[param.name] == (None if param.multiple and not param.default else param.default), param.name
    assert set(seen) == set(PLAY_OPTIONS) - {"-h", "--help"}
    assert set(DEFAULTS) == set(seen.values())


@pytest.mark.parametrize("words", [
    ["a.bag"],
    ["a.bag", "b.bag", "/chatter:=/talk", "__name:=player"],
    ["-q", "-r", "4", "-d", "0.3", "a.bag"],
    ["a.bag", "--rate=2.5", "--loop", "--pause", "--clock", "--hz", "50", "--queue", "7"],
    ["-s", "1.5", "-u", "3", "--topics", "/a", "a.bag", "--topics=/b", "--start=2"],
    ["--delay", "0", "--duration", "1e-3", "-l", "--quiet", "a.bag"],
    ["a.bag", "--topics", "/a", "/b"],
])
def test_a_plain_command_line_gives_the_parameters_typer_gives(words: list[str],
                                                               monkeypatch: pytest.MonkeyPatch) -> None:
    assert parse_plain(words) == _typer_call(words, monkeypatch)


@pytest.mark.parametrize("words", [
    [], ["--help"], ["-h", "a.bag"], ["-r4", "a.bag"], ["-lq", "a.bag"], ["--", "a.bag"],
    ["-r", "-1", "a.bag"], ["-r", "x", "a.bag"], ["--rate=", "a.bag"], ["--queue", "1.5", "a.bag"],
    ["a.bag", "-r"], ["--loop=yes", "a.bag"], ["--unknown", "a.bag"], ["-q"], ["a.bag", "-"],
])
def test_anything_else_is_left_to_typer(words: list[str]) -> None:
    assert parse_plain(words) is None
