"""What keys an app answers to right now: its bindings and those of the focused widgets, grouped for reading.

The help panel (:mod:`rostui.apps.widgets.help`) shows these sections and the
command palette (:mod:`rostui.apps.widgets.palette`) offers their actions, so
both always list exactly the bindings Textual would act on, hidden ones
(arrows, digits, ``+``/``-``) included.  :func:`key_line` starts every app's
key line with the two keys a newcomer needs first.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable

from textual.app import App
from textual.binding import Binding
from textual.dom import DOMNode
from textual.screen import Screen

__all__ = ["ESSENTIAL_KEYS", "KeyRow", "KeySection", "key_line", "key_sections", "namespace_title"]

#: What every key line shows first, so it is never cut off at 80 columns.
ESSENTIAL_KEYS = "? help  q quit"

#: Actions listed first in an app's section, in this order.
FIRST_ACTIONS = ("help", "quit")


def key_line(rest: str) -> str:
    """An app's key line: :data:`ESSENTIAL_KEYS`, then ``rest`` (which a narrow terminal may cut)."""
    return f"{ESSENTIAL_KEYS}  {rest}" if rest else ESSENTIAL_KEYS


@dataclass(frozen=True)
class KeyRow:
    """One line of help: the keys (``+ / =``), what they do, and the action they run (None: a note only)."""

    keys: str
    description: str
    action: str | None = None
    namespace: DOMNode | None = None


@dataclass
class KeySection:
    """The keys of one part of the screen: the app, the screen, or a focused widget."""

    title: str
    rows: list[KeyRow] = field(default_factory=list)


def namespace_title(node: DOMNode) -> str:
    """How the help names the part of the screen whose bindings follow."""
    if isinstance(node, App):
        return node.title or type(node).__name__
    if node.BINDING_GROUP_TITLE:
        return node.BINDING_GROUP_TITLE
    if isinstance(node, Screen) and type(node).__module__.startswith("textual."):
        return "every screen"
    name = type(node).__name__
    words = "".join(f" {c.lower()}" if c.isupper() else c for c in name).strip()
    return words


def _key_rank(display: str) -> int:
    """Single characters (``q``, ``?``) before named keys (``f1``, ``^c``); otherwise as bound."""
    return 0 if len(display) == 1 else 1


def _describe(binding: Binding) -> str:
    if binding.description:
        return binding.description
    return binding.action.rsplit(".", 1)[-1].split("(", 1)[0].replace("_", " ")


def key_sections(screen: Screen[object], notes: Iterable[tuple[str, str]] = (),
                 extra: Iterable[tuple[DOMNode, Binding]] = ()) -> list[KeySection]:
    """The keys ``screen`` answers to now, one section per namespace, the app's first.

    ``notes`` are (keys, description) pairs the app handles without a binding
    (turtlesim's arrow keys), added to the app's section; ``extra`` are
    bindings that work although the screen does not list them (the app's
    priority keys over a modal screen; they win over the screen's own binding
    of the same key, as they do when pressed).  Keys bound to the same action and
    description share a row.
    """
    app = screen.app
    groups: dict[DOMNode, dict[tuple[str, str], list[str]]] = {}
    overriding = {binding.key for _, binding in extra if binding.priority}
    chain = [(active.node, active.binding) for active in screen.active_bindings.values()
             if active.binding.key not in overriding or active.binding.priority]
    seen = {binding.key for _, binding in chain}
    chain += [(node, binding) for node, binding in extra if binding.key not in seen]
    for node, binding in chain:
        rows = groups.setdefault(node, {})
        rows.setdefault((binding.action, _describe(binding)), []).append(app.get_key_display(binding))
    order = sorted(groups, key=lambda node: 0 if isinstance(node, App) else 2 if isinstance(node, Screen) else 1)
    sections = []
    for node in order:
        items = list(groups[node].items())
        if isinstance(node, App):
            items.sort(key=lambda item: FIRST_ACTIONS.index(item[0][0]) if item[0][0] in FIRST_ACTIONS
                       else len(FIRST_ACTIONS))
        section = KeySection(namespace_title(node))
        for (action, description), keys in items:
            shown = sorted(dict.fromkeys(keys), key=_key_rank)
            section.rows.append(KeyRow(" / ".join(shown), description, action, node))
        if isinstance(node, App):
            section.rows += [KeyRow(keys, description) for keys, description in notes]
        sections.append(section)
    return sections
