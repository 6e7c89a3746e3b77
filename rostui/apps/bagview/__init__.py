"""`rostui bag view`: play, step, seek and inspect a bag; record with live per-topic counts."""
