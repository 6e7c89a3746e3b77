"""Bags: MCAP (ROS 1 profile) and rosbag v2.0 ``.bag`` files — record, play, inspect, repair, convert."""
