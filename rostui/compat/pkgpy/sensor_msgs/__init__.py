"""The sensor_msgs package's Python modules (``sensor_msgs.point_cloud2``); see :mod:`rostui.compat.pkgpy`."""
