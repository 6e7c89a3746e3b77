"""The command groups of ``rostui`` and the full-screen apps among them: the one list main, serve and help read.

A new command group is a module ``rostui/cli/<group>_cmd.py`` with ``register(app)`` and one entry in
:data:`COMMAND_GROUPS`; a new app is its package under ``rostui/apps/``, its command, and one row in :data:`APPS`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

__all__ = ["App", "APPS", "COMMAND_GROUPS", "OTHER_WORDS", "READS_EVERY_COMMAND", "app_of", "served_apps"]

#: Every command group, as ``rostui/cli/<group>_cmd.py`` registers it, in the order the help lists them.
COMMAND_GROUPS = ("core", "run", "node", "topic", "msg", "service", "param", "dynparam", "pkg", "wtf", "clean",
                  "turtlesim", "graph", "console", "loggers", "launch", "bag", "monitor", "serve", "python", "tf", "view",
                  "reconfigure", "diagnostics", "top", "action", "publish", "call")

#: The words a group registers besides its own name (``rostui srv`` lives in msg_cmd.py): with the groups' names,
#: what the first word of a command line may be.
OTHER_WORDS: dict[str, tuple[str, ...]] = {"msg": ("srv",), "turtlesim": ("teleop",), "python": ("shell-env",)}

#: Commands that look other commands up in the whole command tree (``rostui serve graph`` parses graph's options
#: with graph's own command): the tree is built whole for them.
READS_EVERY_COMMAND = ("serve",)


@dataclass(frozen=True)
class App:
    """A command that opens a full-screen app: its words, the package the app lives in, the option that opens it
    (of a command that otherwise prints), and whether ``rostui serve`` shows it in a browser."""

    words: tuple[str, ...]
    package: str
    option: str = ""
    served: bool = True

    @property
    def name(self) -> str:
        """The app as a user names it: ``bag view``, ``launch --tui``."""
        return " ".join((*self.words, self.option)) if self.option else " ".join(self.words)


#: Every full-screen app.
APPS = (
    App(("graph",), "rostui.apps.graph"),
    App(("console",), "rostui.apps.console"),
    App(("loggers",), "rostui.apps.loggers"),
    App(("monitor",), "rostui.apps.monitor"),
    App(("bag", "view"), "rostui.apps.bagview"),
    App(("turtlesim",), "rostui.turtlesim"),
    App(("launch",), "rostui.apps.launchmon", option="--tui"),
    App(("view",), "rostui.apps.view"),
    App(("reconfigure",), "rostui.apps.reconfigure"),
    App(("diagnostics",), "rostui.apps.diagnostics"),
    App(("top",), "rostui.apps.top"),
    App(("action",), "rostui.apps.action"),
    App(("publish",), "rostui.apps.form"),
    App(("call",), "rostui.apps.form"),
)


def served_apps() -> tuple[App, ...]:
    """The apps ``rostui serve`` runs."""
    return tuple(app for app in APPS if app.served)


def app_of(words: Sequence[str]) -> App | None:
    """The served app whose command ``words`` start with (the longest match), or None."""
    found = [app for app in served_apps() if tuple(words[:len(app.words)]) == app.words]
    return max(found, key=lambda app: len(app.words), default=None)
