"""Real rospy scripts run as background processes, under rostui's rospy ("shim") or Debian's ("real")."""

from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

from conftest import SYSTEM_PYTHON, rostui_cmd, stop_process, wait_until


def script_command(side: str, script: Path, *args: str) -> list[str]:
    """The command line running *script* under rostui's rospy (``shim``) or Debian's (any other side)."""
    if side == "shim":
        return rostui_cmd("python", "--rostui", str(script), *args)
    return [SYSTEM_PYTHON, str(script), *args]


def python_stacks(pid: int) -> str:
    """Every thread's Python stack in process *pid*, as py-spy dumps them (what it said when it cannot)."""
    spy = Path(sys.executable).with_name("py-spy")
    try:
        done = subprocess.run([str(spy), "dump", "--pid", str(pid)], capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return f"(py-spy: {exc})"
    return done.stdout + done.stderr


class Running:
    """A process running in the background, its output collected in a file."""

    def __init__(self, cmd: list[str], env: dict[str, str], log: Path) -> None:
        self.log = log
        self.proc = subprocess.Popen(cmd, env=env, stdout=log.open("w"), stderr=subprocess.STDOUT, text=True)
        self.outlived_ctrl_c = False
        """True when :meth:`interrupt` had to end it with more than SIGINT."""
        self.stacks_when_stuck = ""
        """The process's Python stacks (py-spy) when it outlived Ctrl-C, to show where it hung."""

    def output(self) -> str:
        """What it printed so far."""
        return self.log.read_text(errors="replace")

    def wait_for(self, text: str, count: int = 1) -> None:
        """Wait until *text* is in its output *count* times; fail with its output when it never is."""
        try:
            wait_until(lambda: self.output().count(text) >= count or self.proc.poll() is not None,
                       f"{text!r} printed {count} times", timeout=60)
        except AssertionError as exc:
            raise AssertionError(f"{exc}; {self.proc.args} printed:\n{self.output()}") from None
        assert self.output().count(text) >= count, self.output()

    def interrupt(self) -> str:
        """Ctrl-C it, wait for it to end, and return everything it printed."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.outlived_ctrl_c = True
                self.stacks_when_stuck = python_stacks(self.proc.pid)
                stop_process(self.proc)
        return self.output()
