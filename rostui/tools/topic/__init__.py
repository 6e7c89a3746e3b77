"""The logic of ``rostui topic`` (what ``rostopic`` does), free of any CLI framework, one module per concern.

Master queries take a ``call(method, *args)`` callable that returns the unwrapped value of a Master API call,
so the command layer decides how a missing master is reported.  The long-running tools (echo, hz, bw, pub) are
coroutines in :mod:`.runners`; they write their text through an ``out(text)`` callable.  Output follows real
``rostopic`` byte for byte; where rostopic prints a multi-line error, the error here is one line.

This package's face imports nothing, so ``topic list`` loads :mod:`.listing` alone.
"""
