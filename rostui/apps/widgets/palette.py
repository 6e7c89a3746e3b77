"""KeysProvider: the command palette (ctrl+p) offers every action the app's keys run, each with its key.

Choosing a command runs the bound action in the namespace that binds it (the
app, or the focused widget), exactly as pressing the key would.
"""

from __future__ import annotations

from functools import partial
from typing import Awaitable, Callable, Protocol, runtime_checkable

from textual.command import DiscoveryHit, Hit, Hits, Provider
from textual.screen import Screen

from rostui.apps.widgets.keys import KeyRow, KeySection

__all__ = ["KeysProvider", "KeyedApp", "palette_rows"]

#: Actions the palette does not offer: opening the palette itself.
NOT_OFFERED = frozenset({"command_palette", "app.command_palette"})


@runtime_checkable
class KeyedApp(Protocol):
    """An app that can list its keys for a screen (:class:`~rostui.apps.widgets.app_keys.KeysApp`)."""

    def keys_for(self, screen: Screen[object]) -> list[KeySection]:
        """The key sections that ``screen`` answers to now."""
        ...


def palette_rows(sections: list[KeySection]) -> list[tuple[KeyRow, str]]:
    """Every row that runs an action (not the palette's own key), with its section's title."""
    return [(row, section.title) for section in sections for row in section.rows
            if row.action is not None and row.action not in NOT_OFFERED]


class KeysProvider(Provider):
    """Commands from the key bindings of the screen the palette was opened on."""

    def _rows(self) -> list[tuple[KeyRow, str]]:
        app = self.screen.app
        if not isinstance(app, KeyedApp):
            return []
        return palette_rows(app.keys_for(self.screen))

    def _command(self, row: KeyRow) -> Callable[[], Awaitable[bool]]:
        assert row.action is not None
        return partial(self.screen.app.run_action, row.action, row.namespace)

    async def discover(self) -> Hits:
        """Every action, in the order the help panel lists them."""
        for row, title in self._rows():
            yield DiscoveryHit(row.description, self._command(row), text=row.description,
                               help=f"key {row.keys} · {title}")

    async def search(self, query: str) -> Hits:
        """Actions whose description (or key) matches ``query``."""
        matcher = self.matcher(query)
        for row, title in self._rows():
            score = max(matcher.match(row.description), matcher.match(f"{row.keys} {row.description}"))
            if score > 0:
                yield Hit(score, matcher.highlight(row.description), self._command(row), text=row.description,
                          help=f"key {row.keys} · {title}")
