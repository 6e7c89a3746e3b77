"""The `rostui` command with its whole tree: every command group registered, for what reads every command.

A command line runs through :func:`rostui.cli.tree.main`, which builds only the
group it names; ``rostui serve``, the help tests and the layer checks read
:data:`app`, the whole tree.
"""

from __future__ import annotations

from rostui.cli.tree import groups_for, main, new_app, only_the_commands_named

__all__ = ["app", "groups_for", "main", "only_the_commands_named"]

app = new_app()
"""Every command group of ``rostui``."""
