"""How `rostui python` turns ROS packages into Python: rosbuild packages, a package's own Python, and the
modules rostui does not provide.

- A package with only a rosbuild ``manifest.xml`` on ROS_PACKAGE_PATH is a package, as rospack finds it:
  its messages import.
- A package whose source tree holds its own Python (``src/<pkg>/__init__.py``, catkin's layout) is that
  Python, with its messages beside it (``<pkg>.msg``), as in a catkin devel space.
- A package whose real Python module rostui lacks (one that Debian installed beside its messages) fails at the
  import, naming the module and docs/rospy.md, never as an empty module that fails later.
"""

from __future__ import annotations

import subprocess
import textwrap
from pathlib import Path

import pytest

from conftest import rostui_cmd


def run_script(tmp_path: Path, body: str, package_path: Path) -> subprocess.CompletedProcess[str]:
    script = tmp_path / "script.py"
    script.write_text(textwrap.dedent(body))
    env = {"PATH": "/usr/bin:/bin", "ROS_PACKAGE_PATH": str(package_path), "ROS_HOME": str(tmp_path / "home")}
    return subprocess.run(rostui_cmd("python", "--rostui", str(script)), env=env, capture_output=True, text=True,
                          timeout=120)


def test_rosbuild_and_own_python_packages(tmp_path: Path) -> None:
    root = tmp_path / "src"
    old = root / "old_robot"
    (old / "msg").mkdir(parents=True)
    (old / "manifest.xml").write_text("<package><description brief='a rosbuild package'/></package>\n")
    (old / "msg" / "Reading.msg").write_text("float64 value\nstring unit\n")
    new = root / "new_robot"
    (new / "msg").mkdir(parents=True)
    (new / "src" / "new_robot").mkdir(parents=True)
    (new / "package.xml").write_text("<package format='2'><name>new_robot</name><version>1.0.0</version>"
                                     "<description>d</description><maintainer email='a@b.c'>m</maintainer>"
                                     "<license>BSD</license></package>\n")
    (new / "msg" / "Wheel.msg").write_text("int32 ticks\n")
    (new / "src" / "new_robot" / "__init__.py").write_text("GREETING = 'from new_robot'\n")
    (new / "src" / "new_robot" / "helpers.py").write_text("def double(x):\n    return 2 * x\n")
    out = run_script(tmp_path, """
        from old_robot.msg import Reading
        import new_robot
        from new_robot import helpers
        from new_robot.msg import Wheel
        print(Reading(2.5, "V"))
        print(new_robot.GREETING, helpers.double(21), Wheel(ticks=7).ticks, Wheel._type)
    """, root)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == ["value: 2.5", 'unit: "V"', "from new_robot 42 7 new_robot/Wheel"]


def test_a_module_rostui_lacks_fails_at_the_import(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Debian's install of a package with Python beside its messages (here a stand-in for dist-packages): its
    messages still import, its Python modules fail at the import with the hint; so does a ROS module rostui
    does not provide at all."""
    from rostui.compat import finder

    dist = tmp_path / "dist-packages"
    (dist / "std_msgs" / "msg").mkdir(parents=True)
    (dist / "std_msgs" / "__init__.py").write_text("")
    (dist / "std_srvs" / "msg").mkdir(parents=True)
    (dist / "std_srvs" / "client.py").write_text("")
    monkeypatch.setattr(finder, "DEBIAN_PYTHON", dist)
    hook = finder.MessageModuleFinder()
    assert hook.find_spec("std_msgs", None) is not None  # messages only: the package module, as genpy's
    assert hook.find_spec("std_msgs.helpers", []) is None  # an unknown module of it is Python's own error
    assert hook.find_spec("std_srvs", None) is not None and hook.find_spec("std_srvs.srv", []) is not None
    with pytest.raises(ModuleNotFoundError, match=r"No module named 'std_srvs.client': rostui python serves "
                                                  r"std_srvs's messages \(std_srvs.msg\) but not its Python "
                                                  r"modules; docs/rospy.md") as caught:
        hook.find_spec("std_srvs.client", [])
    assert caught.value.name == "std_srvs.client"
    with pytest.raises(ModuleNotFoundError, match=r"No module named 'image_geometry': rostui python does "
                                                  r"not provide this ROS module yet; docs/rospy.md"):
        hook.find_spec("image_geometry", None)
