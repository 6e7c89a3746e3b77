"""rostui action: the action servers on the master and a goal sent to one (axclient, rqt_action)."""
