"""Imports a package no ROS package path holds: Python's own ModuleNotFoundError (for these tests)."""

import no_such_pkg_anywhere.msg

print(no_such_pkg_anywhere.msg)
