"""The README's quick start is what a new machine runs: a venv line, then the test command CI runs verbatim."""

from __future__ import annotations

import re

from conftest import REPO


def _quick_start_block() -> list[str]:
    text = (REPO / "README.md").read_text()
    section = text.split("## Quick start", 1)[1]
    block = re.search(r"```bash\n(.*?)```", section, re.S)
    assert block is not None, "README's quick start has no bash block"
    return block.group(1).strip().splitlines()


def test_quick_start_is_two_commands_that_install_into_a_venv() -> None:
    first, second = _quick_start_block()
    assert first.startswith("python3 -m venv .venv && .venv/bin/pip install . && ")
    assert first.endswith(".venv/bin/rostui turtlesim")
    assert second.startswith("python3 -m venv .venv && .venv/bin/pip install -e '.[test]' && ")


def test_ci_runs_the_readme_test_command_verbatim() -> None:
    test_command = _quick_start_block()[1].split(" && ")[-1]
    run = [line for line in (REPO / ".ci" / "run").read_text().splitlines() if line and not line.startswith("#")]
    assert run[-1] == test_command
