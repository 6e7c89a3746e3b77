"""`rostui loggers`: the logger levels of running nodes, shown and set like rqt_logger_level."""
