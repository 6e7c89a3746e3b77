"""Python modules that ROS packages ship besides their messages, rewritten for rostui, one folder per package.

Not imported under these names: the import hook (:mod:`rostui.compat.finder`) makes a folder here the
``__path__`` of the ROS package of the same name, so ``from sensor_msgs import point_cloud2`` finds it.
"""
