"""The directory put on a script's import path; as ``rostui.compat.pylib`` it is only packaged data."""
