"""Imports a type std_msgs does not define: Python's own ImportError (for these tests)."""

from std_msgs.msg import NoSuchType

print(NoSuchType)
