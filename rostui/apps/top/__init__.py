"""rostui top: every node's process, its CPU, memory, threads and connections (rqt_top)."""
