"""rostui: the ROS 1 developer toolbox, rebuilt in Python for the terminal."""

__version__ = "0.1.0"
