"""`rostui view [TOPIC|VIEW_FILE]...`: sensor topics drawn in the terminal (images, scans, maps, markers, ...).

Each topic gets a panel with the view its message type has in
rostui/apps/view/registry.py.  Textual is imported only when the app opens.
No master is not an error: the app opens, says so and keeps trying.  A bad
topic name, view file or rviz file is one line on stderr and exit status 1
before any screen opens.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, List, Optional

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}

#: Arguments ending so are view files (`rostui view --save` writes them), not topics.
VIEW_FILE_SUFFIXES = (".yaml", ".yml")


def view_command(
    topics: List[str] = typer.Argument(None, metavar="TOPIC|VIEW_FILE...",
                                       help="Topics to show, each in its own panel (top-down ones share one), or a "
                                            "view file written by --save."),
    period: float = typer.Option(1.0, "--period", metavar="SECONDS", help="Seconds between master polls."),
    frame: str = typer.Option("", "--frame", metavar="FRAME",
                              help="Fixed frame of the top-down view (default: the first message's frame)."),
    goal_topic: str = typer.Option("", "--goal-topic", metavar="TOPIC",
                                   help="Where g (2D nav goal) sends its PoseStamped (default: /move_base_simple/goal)."),
    pose_topic: str = typer.Option("", "--pose-topic", metavar="TOPIC",
                                   help="Where p (2D pose estimate) sends its PoseWithCovarianceStamped "
                                        "(default: /initialpose)."),
    cmd_vel_topic: str = typer.Option("", "--cmd-vel-topic", metavar="TOPIC",
                                      help="Where t (teleop) sends its Twist (default: /cmd_vel)."),
    footprint: str = typer.Option("", "--footprint", metavar="FOOTPRINT",
                                  help="The robot's footprint, drawn at its frame: a parameter holding it (as "
                                       "costmap_2d reads it), the points themselves (a list of x, y pairs), or a "
                                       "radius."),
    robot_frame: str = typer.Option("", "--robot-frame", metavar="FRAME",
                                    help="The robot's frame, for its footprint and o (follow) (default: base_link)."),
    follow: bool = typer.Option(False, "--follow", help="Keep the robot's frame in the middle of the view."),
    from_rviz: Optional[Path] = typer.Option(None, "--from-rviz", metavar="RVIZ_FILE",
                                             help="Take the displays, fixed frame, tools and view of an rviz file."),
    save: Optional[Path] = typer.Option(None, "--save", metavar="VIEW_FILE",
                                        help="Write the view (topics, frame, zoom, centre, tools) to FILE on quit."),
) -> None:
    """Show sensor topics in the terminal: images, and scans, maps, paths, poses, clouds and markers from above.

    Images are drawn with the kitty graphics protocol or sixel where the
    terminal answers that it has them, else with half-block characters.
    Only the newest frame is drawn; frame rate and latency are shown.

    In the top-down view (scans, maps, markers...), g places a 2D nav goal and p a 2D pose estimate with a
    cursor (arrows or a click, a and d turn it, Enter sends it, Esc cancels), and t drives the robot with the
    arrows, as rviz's tools and a teleop do. Nothing is sent until then.

    Example: rostui view /camera/image_raw

    Example: rostui view --frame map /map /scan /move_base/NavfnROS/plan --save nav.yaml
    """
    from rostui.cli.common import fail
    from rostui.models.sensors.view_file import ViewFileError, ViewSpec, read_view_file, spec_from_rviz

    if not period > 0:
        fail(f"ERROR: --period must be a positive number of seconds, not {period:g}")
    spec = ViewSpec()
    try:
        if from_rviz is not None:
            spec, skipped = spec_from_rviz(from_rviz)
            left_out = f"; left out: {', '.join(skipped)}" if skipped else ""
            typer.echo(f"rostui view: {from_rviz}: {len(spec.topics)} displays{left_out}", err=True)
        for word in topics or []:
            if word.endswith(VIEW_FILE_SUFFIXES):
                _merge(spec, read_view_file(Path(word)))
            else:
                spec.topics.append(_checked_topic(word))
    except ViewFileError as exc:
        fail(f"ERROR: {exc}")
    if not spec.topics:
        fail("ERROR: no topic to show: give topics, a view file or --from-rviz FILE.rviz")
    spec.frame = frame.strip().lstrip("/") or spec.frame
    spec.goal_topic = _checked_topic(goal_topic) if goal_topic else spec.goal_topic
    spec.pose_topic = _checked_topic(pose_topic) if pose_topic else spec.pose_topic
    spec.cmd_vel_topic = _checked_topic(cmd_vel_topic) if cmd_vel_topic else spec.cmd_vel_topic
    spec.footprint = footprint or spec.footprint
    spec.robot_frame = robot_frame.strip().lstrip("/") or spec.robot_frame
    spec.follow = follow or spec.follow
    outline = _footprint_outline(spec.footprint) if spec.footprint not in (None, "") else None
    from rostui.apps.view.app import run_app

    raise typer.Exit(run_app(spec, period=period, footprint=outline, save=save))


def _checked_topic(word: str) -> str:
    """``word`` resolved as rostopic resolves a topic; one error line for a bad name."""
    from rostui.cli.common import fail
    from rostui.core.names import InvalidNameError, validate_name
    from rostui.tools.topic.common import resolve_topic

    try:
        validate_name(word, "topic")
    except InvalidNameError as exc:
        fail(f"ERROR: {exc}")
    if not word.strip("/"):
        fail(f"ERROR: {word!r} is not a topic name")
    return resolve_topic(word)


def _merge(spec: Any, more: Any) -> None:
    """``more``'s topics after ``spec``'s; its settings where ``spec`` has none."""
    spec.topics += [t for t in more.topics if t not in spec.topics]
    for key in ("frame", "span", "centre", "goal_topic", "pose_topic", "cmd_vel_topic", "footprint",
                "robot_frame"):
        if getattr(spec, key) is None:
            setattr(spec, key, getattr(more, key))
    spec.follow = spec.follow or more.follow


def _footprint_outline(value: Any) -> Any:
    """The footprint's closed outline: the points or radius given, or those of the parameter named."""
    from rostui.cli.common import fail
    from rostui.models.sensors.footprint import FootprintError, footprint_outline

    text = value.strip() if isinstance(value, str) else None
    try:
        if text is not None and not text.startswith("[") and not _is_number(text):
            value = _parameter(text)
        return footprint_outline(float(text) if text is not None and _is_number(text) else value)
    except FootprintError as exc:
        fail(f"ERROR: --footprint: {exc}")


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _parameter(name: str) -> Any:
    """The value of parameter ``name`` on the master (one error line when it cannot be read)."""
    from rostui.cli.common import fail, master_uri
    from rostui.core.xmlrpc import RosApiError, XmlRpcConnectionError, ros_result
    from rostui.core.xmlrpc.quick import quick_call
    from rostui.tools.param_quick import script_resolve

    key = script_resolve(name, "rostui_view")
    try:
        return ros_result(quick_call(master_uri(), "getParam", "/rostui_view", key, timeout=10.0))
    except RosApiError:
        fail(f"ERROR: --footprint: parameter {key} is not set")
    except XmlRpcConnectionError as exc:
        fail(f"ERROR: --footprint: cannot read parameter {key}: {exc}")


def register(app: typer.Typer) -> None:
    """Add ``rostui view``."""
    app.command("view", context_settings=CONTEXT)(view_command)
