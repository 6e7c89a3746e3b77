"""The reconfigure app (rqt_reconfigure in the terminal)."""
