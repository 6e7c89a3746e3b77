"""`rostui --version`: the installed distribution's version, on the fast path and in Typer's help."""

from __future__ import annotations

import os
import subprocess
from importlib.metadata import version

from conftest import rostui_cmd


def test_version_prints_the_installed_version() -> None:
    r = subprocess.run(rostui_cmd("--version"), capture_output=True, text=True, timeout=30, env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    assert r.stdout == f"rostui {version('rostui')}\n"


def test_version_is_an_option_of_the_full_command_line() -> None:
    from typer.testing import CliRunner

    from rostui.cli.main import app

    result = CliRunner().invoke(app, ["--version"])
    assert result.exit_code == 0 and result.output == f"rostui {version('rostui')}\n"
    assert "--version" in CliRunner().invoke(app, ["--help"]).output
