"""Sensor views: `rostui view TOPIC...`, and the same views in the monitor and the bag view's inspector."""
