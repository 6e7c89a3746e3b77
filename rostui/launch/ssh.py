"""The SSH transport of remote launch: OpenSSH's client, run as a child process.

rostui runs ``ssh`` rather than an SSH library: it reads the user's own
``~/.ssh/config``, agent and keys exactly as a terminal login does, and its
``known_hosts`` check is the one users already trust.  Every connection is
made with ``BatchMode=yes`` (no password or passphrase prompt in the middle of
a launch) and ``StrictHostKeyChecking=yes`` (a host missing from
``known_hosts``, or with a changed key, is refused, never added silently).
``ROSTUI_SSH_CONFIG`` names another ssh_config file (``ssh -F``), e.g. one
kept just for the robots.
"""

from __future__ import annotations

import os
import shlex
from dataclasses import dataclass

#: Seconds roslaunch waits for a remote machine when its ``<machine>`` has no ``timeout``.
DEFAULT_TIMEOUT = 10.0


@dataclass(frozen=True)
class SshTarget:
    """Where to log in: address, port, user (None: ssh's own choice) and the connect timeout in seconds."""

    address: str
    port: int = 22
    user: str | None = None
    timeout: float = DEFAULT_TIMEOUT

    def describe(self) -> str:
        """``user@address:port`` as the error lines show it."""
        user = f"{self.user}@" if self.user else ""
        return f"{user}{self.address}:{self.port}"


def ssh_argv(target: SshTarget, command: list[str]) -> list[str]:
    """The ``ssh`` command line that runs ``command`` (quoted for the remote shell) on ``target``."""
    argv = ["ssh"]
    config = os.environ.get("ROSTUI_SSH_CONFIG")
    if config:
        argv += ["-F", config]
    argv += [
        "-o", "BatchMode=yes",
        "-o", "StrictHostKeyChecking=yes",
        "-o", f"ConnectTimeout={max(1, int(round(target.timeout)))}",
        "-o", "ServerAliveInterval=5",
        "-o", "ServerAliveCountMax=3",
        "-T",
        "-p", str(target.port),
    ]
    if target.user:
        argv += ["-l", target.user]
    argv += ["--", target.address, shlex.join(command)]
    return argv


def ssh_failure(lines: list[str]) -> str:
    """The line of ssh's own complaints that says why a connection failed (its last one)."""
    meaningful = [line.strip() for line in lines if line.strip() and not line.startswith("Warning: Permanently")]
    return meaningful[-1] if meaningful else "the connection closed without a word"
