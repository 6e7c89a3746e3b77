"""Logic behind the command-line tools (no typer/rich/textual here)."""
