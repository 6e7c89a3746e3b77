"""What ``rostui monitor`` knows without a screen: topic rows, rate and bandwidth, message trees, publishing.

Nothing here imports Textual; the app in :mod:`rostui.apps.monitor` draws it.
"""
