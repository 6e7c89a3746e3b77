"""`rostui python` pauses the garbage collector for its own start and for ``import rospy`` only.

The script's first line, and the line after ``import rospy``, find the collector running as Python
left it; a script that turned it off before importing rospy finds it still off.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from conftest import rostui_cmd

SCRIPT = """\
import gc
print(gc.isenabled())
import rospy
print(gc.isenabled())
gc.disable()
import importlib, sys
del sys.modules["rospy"]
importlib.import_module("rospy")
print(gc.isenabled())
"""


def test_the_collector_runs_as_the_script_left_it(ros_env: dict[str, str], tmp_path: Path) -> None:
    script = tmp_path / "script.py"
    script.write_text(SCRIPT)
    done = subprocess.run(rostui_cmd("python", str(script)), env=ros_env, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["True", "True", "False"]
