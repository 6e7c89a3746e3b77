"""How a launched node whose executable is a ROS 1 Python script starts: as `rostui run` starts it.

A ``<node pkg="my_pkg" type="talker.py">`` whose file is a rospy script (a
``.py`` file, or an executable whose ``#!`` line names python) gets what
`rostui run` gives it: rostui's ``rospy``, ``genpy``, ``roslib``, ``rosbag`` and
message modules, unless the Python its ``#!`` line names imports a real ROS,
which then wins (the decision is :func:`rostui.compat.launcher.plan`'s, the
one `rostui run` and `rostui python` use). ``ROSTUI_PYTHON`` in the node's
environment (``rostui``, ``real``) chooses as `rostui run --rostui` and
``--real-ros`` do. Other executables, and rostui's own programs, start as
:func:`rostui.launch.inspect.node_argv` says.
"""

from __future__ import annotations

import shlex
from dataclasses import dataclass

from rostui.compat.choice import Mode
from rostui.compat.launcher import plan
from rostui.launch.inspect import node_argv, node_executable
from rostui.launch.model import NodeSpec
from rostui.tools.run import ros_python_script

__all__ = ["NodeCommand", "node_command"]


@dataclass(frozen=True)
class NodeCommand:
    """What starts a node: ``argv`` in ``env``; ``notice`` is the one stderr line saying which ROS it gets."""

    argv: list[str]
    env: dict[str, str]
    notice: str | None = None


def node_command(node: NodeSpec, anons: dict[str, str], env: dict[str, str],
                 extra_args: list[str] | None = None) -> NodeCommand:
    """How to start *node* in *env* (its :func:`~rostui.launch.inspect.node_env`), *extra_args* appended.

    Raises :class:`~rostui.launch.errors.LaunchError` when the executable cannot be found.
    """
    extra = extra_args or []
    path, args = node_executable(node, anons)
    script = ros_python_script(path, env.get("PATH"))
    if script is None:
        return NodeCommand([*node_argv(node, anons), *extra], env)
    how = plan(Mode.from_env(env), str(path), [*args, *extra], env, interpreter=script.interpreter)
    prefix = shlex.split(node.launch_prefix) if node.launch_prefix else []
    return NodeCommand([*prefix, *how.argv], how.env, how.notice)
