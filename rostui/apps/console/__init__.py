"""``rostui console``: rqt_console in the terminal (live /rosout_agg or a rosout.log file)."""
