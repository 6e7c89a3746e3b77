"""TfTreeApp: `rostui tf tree`, the tf tree alone on the screen (what `rostui view /tf` shows in a panel)."""

from __future__ import annotations

from typing import ClassVar

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.widgets import Static

from rostui.apps.terminal import terminal_missing
from rostui.apps.view.tf_tree_view import TfTreeView
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.core.network import master_uri_from_env

__all__ = ["TfTreeApp", "run_app", "KEYS"]

#: Key help at the bottom.
KEYS = key_line("↑↓ frame")


class TfTreeApp(ReleasesOnExit, KeysApp):
    """The tf tree of the master at ``master_uri`` (ROS_MASTER_URI by default); ``view`` may be given for tests."""

    TITLE = "rostui tf tree"
    DEFAULT_CSS = """
    TfTreeApp > Screen > #keys { height: 1; background: $panel; }
    """

    BINDINGS: ClassVar[list[BindingType]] = [Binding("q", "quit", "quit")]

    def __init__(self, *, master_uri: str | None = None, view: TfTreeView | None = None) -> None:
        super().__init__()
        self.master_uri = master_uri_from_env(master_uri)
        self.view = view if view is not None else TfTreeView("/tf", master_uri=self.master_uri, id="tf-tree")

    def compose(self) -> ComposeResult:
        """The tree and the keys."""
        yield self.view
        yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Quit cleanly on SIGTERM/SIGHUP; the table has the focus."""
        quit_on_signals(self)
        self.view.table.focus()

    async def release(self) -> None:
        """Unsubscribe, leave the master."""
        await self.view.stop()


def run_app() -> int:
    """Run :class:`TfTreeApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui tf tree", "use `rostui tf echo SOURCE TARGET` without one"):
        return 1
    app = TfTreeApp()
    app.run()
    return app.return_code or 0
