"""Comparing rostui's command output with real ROS 1 tools on the same live system."""

from __future__ import annotations

import re
import subprocess
import sys
from typing import Sequence

from conftest import REPO

_PATTERNS = [
    (re.compile(r"http://[\w.\-]+:\d+/?"), "http://HOST:PORT/"),
    (re.compile(r"rosrpc://[\w.\-]+:\d+"), "rosrpc://HOST:PORT"),
    (re.compile(r"port \d+"), "port PORT"),
    (re.compile(r"(/\w+?)_\d+_\d{10,}"), r"\1_ANON"),
    (re.compile(r"Pid: \d+"), "Pid: PID"),
]


def normalize(text: str) -> str:
    """Replace ephemeral ports, URIs, pids and anonymous suffixes with placeholders."""
    for pattern, repl in _PATTERNS:
        text = pattern.sub(repl, text)
    return text


def rostui(args: Sequence[str], env: dict[str, str], timeout: float = 30.0,
           input: str | None = None) -> subprocess.CompletedProcess[str]:
    """Run the real `rostui` command line (this Python, ``-m rostui``) to completion."""
    return subprocess.run([sys.executable, "-m", "rostui", *args], env=env, cwd=REPO, capture_output=True,
                          text=True, timeout=timeout, input=input,
                          stdin=None if input is not None else subprocess.DEVNULL)


def interrupted_import() -> ImportError:
    """What numpy raises when Ctrl-C lands while one of its C modules loads: an ImportError whose
    context is the KeyboardInterrupt (seen in CI: ``numpy._core.multiarray failed to import``)."""
    try:
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt:
            raise ImportError("numpy._core.multiarray failed to import")
    except ImportError as exc:
        return exc
