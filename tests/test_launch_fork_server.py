"""The oracle's oracle: roslaunch run in a fork of the pre-imported server answers as a roslaunch process does.

The launch oracle tests ask Debian's roslaunch for its views through tests/peers/roslaunch_forks.py
(launch_helpers.run_roslaunch). Each case here runs once that way and once as `roslaunch ARGS`, its own
process, and the exit status, stdout and stderr must be the same: every view option, arguments on the
command line, an error in a file, a file that does not exist, and a usage error.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import need_peer
from launch_helpers import (
    VIEW_OPTIONS, _forks, corpus_file, have_roslaunch, launch_env, run_roslaunch_process, without_anon,
)

CASES = [
    ["--nodes", "agitr", "triplesim.launch", "use_sim3:=1"],
    ["--args", "/sim1/turtlesim", "agitr", "doublesim.launch"],
    ["--dump-params", "launch_corpus", "elements.launch", "needed:=given"],
    ["--files", "launch_corpus", "include_parent.launch", "needed:=given"],
    ["--ros-args", "launch_corpus", "substitutions.launch", "needed:=given"],
    ["--find-node", "/talker", "launch_corpus", "elements.launch", "needed:=given"],
    ["--nodes", str(corpus_file("malformed.launch"))],
    ["--dump-params", str(corpus_file("arg_not_set.launch"))],
    ["--nodes", "/no/such/file.launch"],
    ["--args", "/talker"],
]


@pytest.mark.parametrize("args", CASES, ids=[f"{a[0]} {Path(a[1]).name}" for a in CASES])
def test_a_fork_answers_as_a_process(ros_env: dict[str, str], args: list[str]) -> None:
    need_peer(have_roslaunch(), "roslaunch (Debian ros-core)")
    assert args[0] in VIEW_OPTIONS
    env = launch_env(ros_env)
    forked = _forks().run(args, env, 60.0)
    alone = run_roslaunch_process(args, env)
    if args[0] == "--files":  # roslaunch prints a set: its order changes from one process to the next
        forked.stdout, alone.stdout = ("".join(sorted(r.stdout.splitlines(True))) for r in (forked, alone))
    assert (forked.returncode, without_anon(forked.stdout), without_anon(forked.stderr)) == \
        (alone.returncode, without_anon(alone.stdout), without_anon(alone.stderr))
    assert forked.stdout or forked.stderr
