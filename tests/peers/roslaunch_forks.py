#!/usr/bin/env python3
"""Debian's roslaunch, imported once, run in a fresh fork per request (for the launch oracle tests).

Importing roslaunch takes two thirds of a CPU second (574 modules, numpy and pkg_resources among them);
the oracle tests ask it a few hundred times. This process imports it once and then, for each request,
forks a child that becomes what `/usr/bin/roslaunch ARGS` would be: the request's environment, working
directory and argv, stdin from /dev/null, stdout and stderr into the request's files, and the script
itself run as __main__; its exit status is the script's. Nothing one run changes reaches the next.

Requests and answers are JSON lines: ``{"argv": [...], "env": {...}, "cwd": "...", "out": PATH,
"err": PATH}`` in; ``{"pid": N}`` as the child starts, then ``{"status": S}`` when it ends (``S`` as
subprocess gives a returncode: negative for a signal). tests/test_launch_fork_server.py checks that
every kind of answer equals a separate roslaunch process's.
"""

import atexit
import json
import os
import runpy
import sys
import traceback

SCRIPT = "/usr/bin/roslaunch"
sys.path[0] = os.path.dirname(SCRIPT)  # the script's directory leads the path, as when it runs itself

import roslaunch  # noqa: E402,F401  (the point of this process: imported once, before any fork)


def _exit_status(code) -> int:
    """The status a Python process exits with for ``SystemExit(code)``, printing a message as Python does."""
    if code is None:
        return 0
    if isinstance(code, int):
        return code & 0xFF
    print(code, file=sys.stderr)
    return 1


def _become(request: dict) -> None:
    """In the child: be `roslaunch ARGV` and exit with its status (never returns)."""
    status = 1
    try:
        os.chdir(request["cwd"])
        os.environ.clear()
        os.environ.update(request["env"])
        null = os.open(os.devnull, os.O_RDONLY)
        out = os.open(request["out"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        err = os.open(request["err"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        for fd, target in ((null, 0), (out, 1), (err, 2)):
            os.dup2(fd, target)
            os.close(fd)
        sys.argv[:] = [SCRIPT, *request["argv"]]  # in place: roslaunch.main's default argument is this list
        try:
            runpy.run_path(SCRIPT, run_name="__main__")
            status = 0
        except SystemExit as exc:
            status = _exit_status(exc.code)
        except BaseException:
            traceback.print_exc()
            status = 1
        atexit._run_exitfuncs()
        sys.stdout.flush()
        sys.stderr.flush()
    finally:
        os._exit(status)


def main() -> None:
    """Serve requests from stdin until it closes."""
    answers = sys.stdout
    for line in sys.stdin:
        request = json.loads(line)
        answers.flush()
        pid = os.fork()
        if pid == 0:
            _become(request)
        answers.write(json.dumps({"pid": pid}) + "\n")
        answers.flush()
        _, wait_status = os.waitpid(pid, 0)
        status = -os.WTERMSIG(wait_status) if os.WIFSIGNALED(wait_status) else os.WEXITSTATUS(wait_status)
        answers.write(json.dumps({"status": status}) + "\n")
        answers.flush()


if __name__ == "__main__":
    main()
