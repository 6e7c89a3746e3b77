"""The one error type of launch-file loading: a message tied to a file and line."""

from __future__ import annotations


class LaunchError(Exception):
    """A launch file cannot be loaded; ``str()`` is one line ``FILE:LINE: message``."""

    def __init__(self, message: str, filename: str | None = None, line: int | None = None) -> None:
        """Keep the message and, when known, where in which file it arose."""
        super().__init__(message)
        self.message = message
        self.filename = filename
        self.line = line

    def located(self, filename: str | None, line: int | None) -> "LaunchError":
        """This error with a location filled in where it has none yet."""
        if self.filename is None:
            self.filename = filename
            self.line = line
        return self

    def __str__(self) -> str:
        """``FILE:LINE: message`` (or just the message when the place is unknown)."""
        message = " ".join(self.message.split())
        if self.filename and self.line:
            return f"{self.filename}:{self.line}: {message}"
        if self.filename:
            return f"{self.filename}: {message}"
        return message


class ArgNotSetError(LaunchError):
    """``$(arg NAME)`` used where NAME has no value."""

    def __init__(self, name: str) -> None:
        """Remember the arg's name."""
        super().__init__(f"arg '{name}' is used but never set")
        self.name = name


class StrictError(LaunchError):
    """``--strict``: the files hold unknown elements or attributes; one ``FILE:LINE: message`` line each."""

    def __init__(self, lines: list[str]) -> None:
        """Keep every problem's line."""
        super().__init__(lines[0] if lines else "unknown elements or attributes")
        self.lines = lines

    def __str__(self) -> str:
        """One line per problem."""
        return "\n".join(self.lines)
