"""NameList: a list of names (nodes, servers) that keeps the cursor on the same name when the list changes."""

from __future__ import annotations

from collections.abc import Sequence

from rich.text import Text
from textual.widgets import OptionList
from textual.widgets.option_list import Option

__all__ = ["NameList"]


class NameList(OptionList):
    """Names, one an option; the highlighted one is the selected name."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id, markup=False)
        self.names: list[str] = []

    @property
    def highlighted_name(self) -> str | None:
        """The highlighted name, if any."""
        option = self.highlighted_option
        return None if option is None else option.id

    def highlight_name(self, name: str) -> None:
        """Put the cursor on *name* (if listed) without announcing it as a new selection."""
        if name in self.names and self.highlighted_name != name:
            with self.prevent(OptionList.OptionHighlighted):
                self.highlighted = self.names.index(name)

    def show_names(self, names: Sequence[str], keep: str | None) -> bool:
        """List *names*, keeping *keep* highlighted when it is still there; False when nothing changed."""
        names = list(names)
        if names == self.names:
            return False
        self.names = names
        with self.prevent(OptionList.OptionHighlighted):  # a rebuild keeps the cursor; it selects nothing
            self.set_options(Option(Text(name), id=name) for name in names)
            if keep in names:
                self.highlighted = names.index(keep)
        return True
