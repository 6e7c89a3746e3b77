"""`--help` of every command: usage lines that show every positional, one placeholder style (upper-case names, as
TOPIC, TYPE, FILE), and an Examples block on the commands a newcomer types first, readable at 80 columns and
made of command lines that parse."""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest
import typer.main
from typer.testing import CliRunner

from rostui.cli.main import app
from rostui.cli.negative import bare_negative


ROOT = typer.main.get_command(app)

#: The commands whose --help ends with an Examples block (issue 21).
WITH_EXAMPLES = [
    ("topic", "pub"), ("topic", "echo"), ("bag", "record"), ("bag", "play"), ("param", "set"),
    ("service", "call"), ("launch",),
]

#: One placeholder: an upper-case name (TOPIC, NUM_WIDTH, PRINT-EXPRESSION), maybe ARG:=VALUE or PACKAGE/SUBDIR.
NAME = re.compile(r"[A-Z][A-Z0-9_\-]*(:=[A-Z][A-Z0-9_]*|/[A-Z]+)?")
#: A choice list as an option's metavar (none|lz4|zstd|bz2).
CHOICES = re.compile(r"[a-z0-9]+(\|[a-z0-9]+)+")


def walk(command: Any, path: tuple[str, ...] = ()) -> Iterator[tuple[tuple[str, ...], Any]]:
    """Every visible command and group below ``command``, with the words that name it."""
    yield path, command
    for name, sub in sorted(getattr(command, "commands", {}).items()):
        if not sub.hidden:
            yield from walk(sub, (*path, name))


COMMANDS = dict(walk(ROOT))


def render(path: tuple[str, ...]) -> str:
    result = CliRunner().invoke(app, [*path, "--help"], env={"COLUMNS": "80", "NO_COLOR": "1", "TERM": "dumb"})
    assert result.exit_code == 0, result.output
    return result.output


def usage_line(text: str) -> str:
    return next(line.strip() for line in text.splitlines() if line.strip().startswith("Usage:"))


def placeholder_ok(text: str) -> bool:
    """True when every word of a usage fragment or metavar is an upper-case placeholder, an option or a bar."""
    text = re.sub(r"\[/([A-Z]+)\]", r"/\1", text)  # PACKAGE[/SUBDIR]
    words = re.split(r"[\s|]+", re.sub(r"\.\.\.|[\[\]{}]", " ", text))
    return all(not word or word.startswith("--") or NAME.fullmatch(word) for word in words)


def ids(path: tuple[str, ...]) -> str:
    return " ".join(path) or "rostui"


@pytest.mark.parametrize("path", list(COMMANDS), ids=ids)
def test_usage_shows_every_positional_in_one_style(path: tuple[str, ...]) -> None:
    command = COMMANDS[path]
    usage = usage_line(render(path))
    assert usage.startswith(" ".join(("Usage: rostui", *path)).strip()), usage
    tail = usage.split("[OPTIONS]", 1)[1] if "[OPTIONS]" in usage else ""
    assert placeholder_ok(tail), f"placeholder style in {usage!r}"
    for param in command.params:
        if param.param_type_name == "argument":
            assert param.metavar, f"{ids(path)}: argument {param.name} has no upper-case metavar"
            assert placeholder_ok(param.metavar), f"{ids(path)}: argument metavar {param.metavar!r}"
            assert param.metavar.strip("[]{}") in usage, f"{ids(path)}: {param.metavar} missing from {usage!r}"
        elif param.param_type_name == "option" and not param.is_flag and not getattr(param, "count", False):
            metavar = param.metavar or ""
            assert NAME.fullmatch(metavar) or CHOICES.fullmatch(metavar), \
                f"{ids(path)}: option {param.opts[0]} shows {metavar or 'its type'!r}, not an upper-case name"


@pytest.mark.parametrize("path", list(COMMANDS), ids=ids)
def test_help_strings_use_no_other_placeholder_style(path: tuple[str, ...]) -> None:
    command = COMMANDS[path]
    texts = [command.help or "", command.epilog or "", *(p.help or "" for p in command.params)]
    for text in texts:
        assert not re.search(r"<[a-z][a-z_\-]*>", text), f"{ids(path)}: <placeholder> in {text!r}"
        assert not re.search(r"\b(PKG|EXE)\b", text), f"{ids(path)}: PKG/EXE instead of PACKAGE/EXECUTABLE in {text!r}"


def example_lines(epilog: str) -> list[str]:
    """The command lines of an Examples epilog, continuation lines joined."""
    lines: list[str] = []
    pending = ""
    for line in epilog.splitlines()[1:]:
        if line.startswith("#"):
            continue
        if line.endswith("\\"):
            pending += line[:-1]
            continue
        lines.append(pending + line.strip() if pending else line)
        pending = ""
    return lines


@pytest.mark.parametrize("path", WITH_EXAMPLES, ids=ids)
def test_examples_in_help(path: tuple[str, ...]) -> None:
    command = COMMANDS[path]
    text = render(path)
    assert "Examples:" in text
    assert all(len(line) <= 80 for line in text.splitlines()), "a line is wider than 80 columns"
    shown = [line.strip() for line in text.splitlines()]
    epilog_lines = command.epilog.splitlines()
    assert epilog_lines[0] == "Examples:" and len(epilog_lines) >= 5
    for line in epilog_lines:  # every line verbatim: nothing eaten as Rich markup, nothing wrapped
        assert line.strip() in shown, f"{line!r} is not shown as written"
    examples = example_lines(command.epilog)
    assert len(examples) >= 3
    for example in examples:
        words = shlex.split(example.split(" | ")[0])
        assert words[:1 + len(path)] == ["rostui", *path], example
        args = words[1 + len(path):]
        ctx = command.make_context(" ".join(path), list(args))  # parses as the command line does
        assert ctx.params is not None
        assert bare_negative(ROOT, words[1:]) is None, example


def rostui_cmd(*args: str) -> list[str]:
    """The installed `rostui` script (its name is the one usage lines show)."""
    return [str(Path(sys.executable).with_name("rostui")), *args]


def test_launch_and_run_usage_of_the_real_command_line() -> None:
    """The installed `rostui` (fast entry point, then Typer) at 80 columns, as a user sees it."""
    env = {**os.environ, "COLUMNS": "80", "NO_COLOR": "1"}
    for args, usage in [
        (("launch",), "Usage: rostui launch [OPTIONS] [PACKAGE] FILE [ARG:=VALUE]..."),
        (("run",), "Usage: rostui run [OPTIONS] "),
        (("topic", "pub"), "Usage: rostui topic pub [OPTIONS] "),
    ]:
        r = subprocess.run(rostui_cmd(*args, "--help"), capture_output=True, text=True, timeout=60, env=env)
        assert r.returncode == 0, r.stderr
        assert usage_line(r.stdout).startswith(usage), r.stdout
    run_usage = usage_line(subprocess.run(rostui_cmd("run", "--help"), capture_output=True, text=True, timeout=60,
                                          env=env).stdout)
    assert re.search(r"PACKAGE\W+EXECUTABLE\W+\[ARGS\]\.\.\.$", run_usage), run_usage
