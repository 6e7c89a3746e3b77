"""The bag commands: play, record, info, filter and compress (:mod:`rostui.core.bag` keeps the formats and transport)."""
