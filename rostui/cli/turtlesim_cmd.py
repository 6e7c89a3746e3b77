"""`rostui turtlesim` (simulator + renderer + keyboard teleop) and `rostui teleop [TOPIC]`."""

from __future__ import annotations

from typing import List

import typer

ROS_ARGS_CONTEXT = {
    "help_option_names": ["-h", "--help"],
    "allow_extra_args": True,
    "ignore_unknown_options": True,
    "allow_interspersed_args": False,
}


def turtlesim_command(ctx: typer.Context) -> None:
    """Run turtlesim in this terminal: the simulator, its renderer and arrow-key teleop.

    Arrow keys drive the selected turtle, Tab selects the next one, q quits.
    ROS arguments (`__name:=`, `__ns:=`, `from:=to`, `_param:=value`) go to the
    turtlesim node.  When no master answers at ROS_MASTER_URI (and it names this
    machine) an embedded master runs inside the app until it quits.
    """
    from rostui.turtlesim.app import run_app

    raise typer.Exit(run_app(list(ctx.args)))


def teleop_command(ctx: typer.Context) -> None:
    """Drive a turtle with the arrow keys from a plain terminal (`rostui teleop [TOPIC] [ROS args]`).

    TOPIC is the geometry_msgs/Twist topic to publish (default `turtle1/cmd_vel`,
    plus the book's `turtle1/command_velocity`).  `_scale_linear:=` and
    `_scale_angular:=` set the speeds.
    """
    args: List[str] = list(ctx.args)
    plain = [a for a in args if ":=" not in a]
    if len(plain) > 1:
        from rostui.cli.common import fail

        fail(f"ERROR: rostui teleop takes one TOPIC, got {len(plain)}: {' '.join(plain)}")
    topic = plain[0] if plain else None
    ros_args = [a for a in args if ":=" in a]
    from rostui.turtlesim.teleop import run_teleop

    raise typer.Exit(run_teleop(ros_args, topic=topic))


def register(app: typer.Typer) -> None:
    """Add the commands to the rostui app."""
    app.command("turtlesim", context_settings=ROS_ARGS_CONTEXT)(turtlesim_command)
    app.command("teleop", context_settings=ROS_ARGS_CONTEXT)(teleop_command)
