"""`rostui graph --dot` and the command's bad input, run as the real command line.

--dot runs against `rostui core` and a real roscore with the book's turtlesim
system, and must print Graphviz DOT that follows the view and filter options,
without loading Textual.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from cli_helpers import rostui
from conftest import REPO
from graph_helpers import book_system, stop_programs
from live_helpers import Program


@pytest.fixture
def book(any_master: str, ros_env: dict[str, str], tmp_path: Path) -> Iterator[list[Program]]:
    """The book's turtlesim system on `rostui core` and on a real roscore."""
    programs = book_system(ros_env, tmp_path)
    yield programs
    stop_programs(programs)


def test_dot_of_each_view(book: list[Program], ros_env: dict[str, str]) -> None:
    """Nodes only (edge labelled with its topic), the book's setup, and debug shown."""
    nodes = rostui(["graph", "--dot"], ros_env)
    assert nodes.returncode == 0, nodes.stderr
    assert nodes.stdout.startswith('digraph "rosgraph" {\n  rankdir=LR;\n')
    assert '"n:/teleop_turtle" -> "n:/turtlesim" [label="/turtle1/command_velocity"];' in nodes.stdout
    assert "rosout" not in nodes.stdout and "t:" not in nodes.stdout
    book_dot = rostui(["graph", "--dot", "--book"], ros_env)
    assert book_dot.returncode == 0, book_dot.stderr
    for line in ('"t:/turtle1/pose" [label="/turtle1/pose", shape=box];',
                 '"n:/turtlesim" [label="/turtlesim", shape=ellipse];',
                 '"n:/teleop_turtle" -> "t:/turtle1/command_velocity";',
                 '"t:/turtle1/command_velocity" -> "n:/turtlesim";',
                 '"n:/turtlesim" -> "t:/turtle1/color_sensor";'):
        assert line in book_dot.stdout
    debug = rostui(["graph", "--dot", "--view", "all", "--show-debug"], ros_env)
    assert '"n:/turtlesim" -> "t:/rosout";' in debug.stdout and '"t:/rosout" -> "n:/rosout";' in debug.stdout


def test_dot_follows_filters(book: list[Program], ros_env: dict[str, str]) -> None:
    """--include, --exclude, --hide-dead-sinks and --group shape the DOT as they shape the app."""
    out = rostui(["graph", "--dot", "--view", "all", "--include", "pose"], ros_env).stdout
    assert sorted(line.split(" [")[0].strip() for line in out.splitlines() if "label=" in line) == \
        ['"n:/turtlesim"', '"t:/turtle1/pose"']
    out = rostui(["graph", "--dot", "--book", "--exclude", "teleop|color"], ros_env).stdout
    assert "teleop" not in out and "color" not in out and '"t:/turtle1/pose"' in out
    out = rostui(["graph", "--dot", "--view", "all", "--hide-dead-sinks"], ros_env).stdout
    assert "/turtle1/pose" not in out and '"t:/turtle1/command_velocity"' in out
    out = rostui(["graph", "--dot", "--view", "all", "--group"], ros_env).stdout
    assert '"g:/turtle1" [label="▸ /turtle1 (4)", shape=folder];' in out


def test_dot_does_not_import_textual(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """The --dot path prints without loading Textual (the CLI module imports it only to open the app)."""
    code = ("import sys\nfrom rostui.cli.main import main\nsys.argv=['rostui','graph','--dot']\n"
            "try:\n    main()\nexcept SystemExit:\n    pass\n"
            "print('TEXTUAL' if any(m.startswith('textual') for m in sys.modules) else 'NO TEXTUAL')")
    result = subprocess.run([sys.executable, "-c", code], env=ros_env, cwd=REPO, capture_output=True, text=True,
                            timeout=60)
    assert result.stdout.rstrip().endswith("NO TEXTUAL"), result.stdout + result.stderr
    assert "digraph" in result.stdout


@pytest.mark.parametrize("args, message", [
    (["--include", "(turtle"], "ERROR: bad include regex '(turtle': missing ), unterminated subpattern at position 0"),
    (["--exclude", "*"], "ERROR: bad exclude regex '*': nothing to repeat at position 0"),
    (["--view", "edges"], "ERROR: --view must be one of nodes, active, all, not 'edges'"),
    (["--period", "0"], "ERROR: --period must be a positive number of seconds, not 0"),
])
def test_bad_input_is_one_line(ros_env: dict[str, str], args: list[str], message: str) -> None:
    """Bad options: one clear line on stderr, exit status 1, nothing on stdout."""
    result = rostui(["graph", "--dot", *args], ros_env)
    assert result.returncode == 1
    assert result.stderr == message + "\n" and result.stdout == ""


def test_no_master_is_one_line(ros_env: dict[str, str]) -> None:
    """--dot with nothing at ROS_MASTER_URI: rostopic's wording, exit 1."""
    result = rostui(["graph", "--dot"], ros_env)
    assert result.returncode == 1
    assert result.stderr.startswith(f"ERROR: Unable to communicate with master at {ros_env['ROS_MASTER_URI']}")
    assert result.stderr.count("\n") == 1


def test_app_needs_a_terminal(ros_env: dict[str, str]) -> None:
    """Without a TTY the app says to use --dot instead."""
    result = rostui(["graph"], ros_env)
    assert result.returncode == 1
    assert result.stderr.startswith("ERROR: rostui graph draws in a terminal") and "--dot" in result.stderr
