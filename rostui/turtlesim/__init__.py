"""turtlesim for the terminal: the world model (world, canvas), the ROS node, the renderer and teleop.

Only ``render`` and ``app`` import Textual; the model and the node do not.
"""
