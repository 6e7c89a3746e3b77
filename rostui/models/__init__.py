"""What the terminal apps know without a screen: graph, monitor, console and loggers models, and their master link.

Nothing here imports Textual; the apps in :mod:`rostui.apps` draw it.
"""
