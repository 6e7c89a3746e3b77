"""Run a script (argv[1], with the rest of argv as its own) with each print() written at once, whole.

print() writes its arguments, separators and end one by one, so two threads printing together mix their
lines. The test of dynamic_reconfigure's testclient.py (whose config callback prints from a subscriber
thread while the main thread prints) runs it through this, unmodified, under both rospys.
"""

import builtins
import runpy
import sys
import threading

_lock = threading.Lock()
_print = builtins.print


def whole_print(*args, sep=" ", end="\n", file=None, flush=False):
    text = (" " if sep is None else sep).join(str(a) for a in args) + ("\n" if end is None else end)
    with _lock:
        _print(text, end="", file=file, flush=flush)


builtins.print = whole_print
sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name="__main__")
