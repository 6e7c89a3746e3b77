"""`rostui view TOPIC...`: sensor topics drawn in the terminal (images; other views as they register).

Each topic gets a panel with the view its message type has in
rostui/apps/view/registry.py.  Textual is imported only when the app opens.
No master is not an error: the app opens, says so and keeps trying.  A bad
topic name is one line on stderr and exit status 1 before any screen opens.
"""

from __future__ import annotations

from typing import List

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}


def view_command(
    topics: List[str] = typer.Argument(..., metavar="TOPIC...", help="Topics to show, each in its own panel."),
    period: float = typer.Option(1.0, "--period", metavar="SECONDS", help="Seconds between master polls."),
    frame: str = typer.Option("", "--frame", metavar="FRAME",
                              help="Fixed frame of the top-down view (default: the first message's frame)."),
    goal_topic: str = typer.Option("/move_base_simple/goal", "--goal-topic", metavar="TOPIC",
                                   help="Where g (2D nav goal) sends its PoseStamped."),
    pose_topic: str = typer.Option("/initialpose", "--pose-topic", metavar="TOPIC",
                                   help="Where p (2D pose estimate) sends its PoseWithCovarianceStamped."),
    cmd_vel_topic: str = typer.Option("/cmd_vel", "--cmd-vel-topic", metavar="TOPIC",
                                      help="Where t (teleop) sends its Twist."),
) -> None:
    """Show sensor topics in the terminal: sensor_msgs/Image and CompressedImage (and every type a view registers).

    Images are drawn with the kitty graphics protocol or sixel where the
    terminal answers that it has them, else with half-block characters.
    Only the newest frame is drawn; frame rate and latency are shown.

    In the top-down view (scans, maps, markers...), g places a 2D nav goal and p a 2D pose estimate with a
    cursor (arrows or a click, a and d turn it, Enter sends it, Esc cancels), and t drives the robot with the
    arrows, as rviz's tools and a teleop do. Nothing is sent until then.

    Example: rostui view /camera/image_raw
    """
    from rostui.cli.common import fail
    from rostui.core.names import InvalidNameError, validate_name
    from rostui.tools.topic.common import resolve_topic

    if not period > 0:
        fail(f"ERROR: --period must be a positive number of seconds, not {period:g}")
    resolved = []
    for topic in [*topics, goal_topic, pose_topic, cmd_vel_topic]:
        try:
            validate_name(topic, "topic")
        except InvalidNameError as exc:
            fail(f"ERROR: {exc}")
        if not topic.strip("/"):
            fail(f"ERROR: {topic!r} is not a topic name")
        resolved.append(resolve_topic(topic))
    from rostui.apps.view.app import run_app
    from rostui.models.sensors.tools2d import ToolTopics

    *shown, goal, pose, cmd_vel = resolved
    raise typer.Exit(run_app(shown, period=period, frame=frame or None,
                             tool_topics=ToolTopics(goal=goal, pose=pose, cmd_vel=cmd_vel)))


def register(app: typer.Typer) -> None:
    """Add ``rostui view``."""
    app.command("view", context_settings=CONTEXT)(view_command)
