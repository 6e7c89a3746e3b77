"""Ctrl-C that lands inside a lazy import still reads as Ctrl-C: no traceback, the shell's exit code."""

from __future__ import annotations

import pytest

from cli_helpers import interrupted_import


def test_an_import_cut_by_ctrl_c_is_an_interrupt_and_an_import_error_of_its_own_is_not() -> None:
    from rostui.cli.common import interrupted

    assert interrupted(interrupted_import())
    assert interrupted(KeyboardInterrupt())
    assert not interrupted(ImportError("No module named 'numpy'"))


def test_the_command_line_exits_130_without_a_traceback(monkeypatch: pytest.MonkeyPatch,
                                                        capsys: pytest.CaptureFixture[str]) -> None:
    from rostui.cli import tree as cli_main

    def cut_short() -> None:
        raise interrupted_import()

    monkeypatch.setattr(cli_main, "new_app", lambda _groups: cut_short)
    monkeypatch.setattr("sys.argv", ["rostui", "topic", "list"])
    with pytest.raises(SystemExit) as stopped:
        cli_main.main()
    assert stopped.value.code == 130
    assert capsys.readouterr().err == ""


def test_any_other_error_still_surfaces(monkeypatch: pytest.MonkeyPatch) -> None:
    from rostui.cli import tree as cli_main

    def broken() -> None:
        raise ImportError("No module named 'numpy'")

    monkeypatch.setattr(cli_main, "new_app", lambda _groups: broken)
    monkeypatch.setattr("sys.argv", ["rostui", "topic", "list"])
    with pytest.raises(ImportError):
        cli_main.main()
