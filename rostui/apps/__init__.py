"""Textual apps: graph, console, loggers (and later monitor, bag view, launch monitor).

Each app is a package of its own (``rostui.apps.graph``...), with its ``.tcss``
beside it; widgets used by two apps live in ``rostui.apps.widgets``.  Nothing
here is imported by rostui.core, and the CLI imports an app only inside the
command that opens it.
"""
