"""Typer command-line front end; each command is thin and imports lazily."""
