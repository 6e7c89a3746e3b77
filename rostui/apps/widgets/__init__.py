"""Widgets shared by two or more rostui apps."""
