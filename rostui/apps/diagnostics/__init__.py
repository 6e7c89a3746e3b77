"""rostui diagnostics: the robot's /diagnostics_agg and /diagnostics (rqt_robot_monitor, rqt_runtime_monitor)."""
