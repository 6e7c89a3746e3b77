"""The check every terminal app makes before it draws: is there a terminal?  (No Textual import.)"""

from __future__ import annotations

import os
import sys

#: ``TEXTUAL_DRIVER`` as textual-serve sets it for each app it runs: Textual's web driver, which speaks
#: textual-serve's packet protocol over stdin and stdout (pipes), so the app needs no terminal.
WEB_DRIVER = "textual.drivers.web_driver:WebDriver"


def served_to_browser() -> bool:
    """True when Textual will draw through its web driver (the app runs under `rostui serve`)."""
    return os.environ.get("TEXTUAL_DRIVER") == WEB_DRIVER


def terminal_missing(what: str, instead: str) -> bool:
    """True, after one error line on stderr, when stdin or stdout is not a TTY and no browser is the screen.

    ``what`` names the app (``rostui graph``); ``instead`` says what to use without a terminal.
    """
    if served_to_browser() or (sys.stdin.isatty() and sys.stdout.isatty()):
        return False
    print(f"ERROR: {what} draws in a terminal: stdin and stdout must be a TTY ({instead})", file=sys.stderr)
    return True
