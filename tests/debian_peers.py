"""What the tests take from Debian: each program, file and system-Python module a test uses as a
real peer, and the Debian package that installs it.

``.ci/run`` installs the packages on its ``apt-get install`` line; ``test_ci_peers.py`` checks
that every package named here is in that list, that every program, ``/usr`` file and module the
tests name is here, and (where the package is installed) that ``dpkg -S`` agrees with this table.
"""

from __future__ import annotations

#: Programs a test runs or looks up on PATH, and the package that installs each.
COMMANDS: dict[str, str] = {
    "roscore": "python3-roslaunch",
    "roslaunch": "python3-roslaunch",
    "rosmaster": "python3-rosmaster",
    "rosversion": "python3-rospkg",
    "rostopic": "python3-rostopic",
    "rosnode": "python3-rosnode",
    "rosservice": "python3-rosservice",
    "rosparam": "python3-rosparam",
    "rosbag": "python3-rosbag",
    "rosmsg": "python3-rosmsg",
    "rossrv": "python3-rosmsg",
    "roswtf": "python3-roswtf",
    "rosrun": "rosbash",
    "rospack": "rospack-tools",
    "g++": "g++",
    "tmux": "tmux",
    "ssh": "openssh-client",
    "ssh-keygen": "openssh-client",
    "ip": "iproute2",
    "nsenter": "util-linux",
    "prlimit": "util-linux",
    "chromium": "chromium",
    "chromedriver": "chromium-driver",
}

#: Files a test reads or runs by absolute path, and the package that installs each.
FILES: dict[str, str] = {
    "/usr/share/bash-completion/completions/rosbash": "rosbash",
    "/usr/include/ros/ros.h": "libroscpp-dev",
    "/usr/lib/genpy/genmsg_py.py": "python3-genpy",
    "/usr/lib/actionlib_msgs/genaction.py": "libactionlib-msgs-dev",
    "/usr/lib/genpy/gensrv_py.py": "python3-genpy",
    "/usr/bin/roslaunch": "python3-roslaunch",
    "/usr/lib/rostopic/rostopic": "python3-rostopic",
    "/usr/lib/rosbag/play": "python3-rosbag",
    "/usr/lib/rosout/rosout": "rosout",
    "/usr/lib/python3/dist-packages/rospy/": "python3-rospy",
    "/usr/lib/python3/dist-packages/rospy/__init__.py": "python3-rospy",
    "/usr/sbin/sshd": "openssh-server",
    "/usr/lib/python3/dist-packages/paramiko/": "python3-paramiko",
    "/usr/share/rosgraph_msgs/package.xml": "libros-rosgraph-msgs-dev",
    "/usr/lib/tf2_ros/static_transform_publisher": "tf2-tools",
    "/usr/lib/tf2_ros/buffer_server": "tf2-tools",
    "/usr/lib/tf/tf_echo": "tf-tools",
    "/usr/lib/dynamic_reconfigure/dynparam": "python3-dynamic-reconfigure",
    "/usr/share/dynamic_reconfigure": "libdynamic-reconfigure-config-init-mutex-dev",
    "/usr/lib/diagnostic_aggregator/aggregator_node": "libdiagnostic-aggregator-tools",
}

#: Top-level modules a test imports under the system Python (/usr/bin/python3), and their packages.
MODULES: dict[str, str] = {
    "rospy": "python3-rospy",
    "rosbag": "python3-rosbag",
    "roslz4": "python3-roslz4",
    "rosgraph": "python3-rosgraph",
    "rostopic": "python3-rostopic",
    "roslaunch": "python3-roslaunch",
    "genpy": "python3-genpy",
    "genmsg": "python3-genmsg",
    "roslib": "python3-roslib",
    "std_msgs": "python3-std-msgs",
    "std_srvs": "python3-std-srvs",
    "geometry_msgs": "python3-geometry-msgs",
    "sensor_msgs": "python3-sensor-msgs",
    "nav_msgs": "python3-nav-msgs",
    "tf2_msgs": "python3-tf2-msgs",
    "visualization_msgs": "python3-visualization-msgs",
    "rosgraph_msgs": "python3-rosgraph-msgs",
    "roscpp": "python3-roscpp-msg",
    "numpy": "python3-numpy",
    "tf2_ros": "python3-tf2-ros",
    "tf2_py": "python3-tf2",
    "tf2_geometry_msgs": "python3-tf2-geometry-msgs",
    "tf": "python3-tf",
    "rostest": "python3-rostest",
    "actionlib": "python3-actionlib",
    "message_filters": "python3-message-filters",
    "cv_bridge": "python3-cv-bridge",
    "dynamic_reconfigure": "python3-dynamic-reconfigure",
    "diagnostic_updater": "python3-diagnostic-updater",
    "rosdiagnostic": "rosdiagnostic",
    "dateutil": "python3-dateutil",
    "rospkg": "python3-rospkg",
}

#: What a bare Debian with python3, venv, pip, git, ca-certificates, procps already has.
BASE_COMMANDS: frozenset[str] = frozenset({
    "bash", "sh", "du", "stty", "dpkg", "env", "kill", "ps", "pgrep", "python3", "git", "cat", "true", "sleep",
})
BASE_FILES: frozenset[str] = frozenset({"/usr/bin/python3", "/bin/sh", "/usr/share"})
#: Paths that real test data names as values only, never reading them: rospkg's own test compares
#: ``get_etc_ros_dir()`` with ``/etc/ros`` (tests/python_compat/real/rospkg_tests).
NAMED_NOT_READ: frozenset[str] = frozenset({"/etc/ros"})

#: Modules the tests generate themselves (with genpy, from rostui's own .msg files) before importing, and
#: packages the tests write whose messages or .cfg modules rostui's import hook builds (demo_pkg in
#: test_run_python.py, old_robot and new_robot in test_python_packages.py, broken_cfg in
#: test_dynamic_reconfigure.py).
GENERATED_MODULES: frozenset[str] = frozenset({"turtlesim", "rospy_tutorials", "beginner_tutorials", "demo_pkg",
                                                "old_robot", "new_robot", "broken_cfg"})

#: Programs a test looks for but passes without, checking the behaviour either way (named, so the
#: scan knows they are not forgotten): xterm is a launch-prefix whose absence roslaunch reports too.
OPTIONAL_COMMANDS: frozenset[str] = frozenset({"xterm"})


def describe(name: str) -> str:
    """``name (Debian package)`` for a program, file or module in the tables above."""
    for table in (COMMANDS, FILES, MODULES):
        if name in table:
            return f"{name} (Debian {table[name]})"
    raise KeyError(f"{name} is not in tests/debian_peers.py: add it and its Debian package")
