"""The check every terminal app makes before it draws: is there a terminal?  (No Textual import.)"""

from __future__ import annotations

import sys


def terminal_missing(what: str, instead: str) -> bool:
    """True, after one error line on stderr, when stdin or stdout is not a TTY.

    ``what`` names the app (``rostui graph``); ``instead`` says what to use without a terminal.
    """
    if sys.stdin.isatty() and sys.stdout.isatty():
        return False
    print(f"ERROR: {what} draws in a terminal: stdin and stdout must be a TTY ({instead})", file=sys.stderr)
    return True
