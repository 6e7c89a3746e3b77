"""Textual apps: graph, console, loggers, monitor, bag view and the launch monitor; widgets and wiring only.

Each app is a package of its own (``rostui.apps.graph``...), with its ``.tcss``
beside it; widgets used by two apps live in ``rostui.apps.widgets``.  What an
app knows without a screen is in :mod:`rostui.models`.  Nothing below the apps
imports them, and the CLI imports an app only inside the command that opens it.
"""
