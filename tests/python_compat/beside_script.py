"""Imported by argv_and_exit.py from the script's own directory."""

VALUE = "beside the script"
