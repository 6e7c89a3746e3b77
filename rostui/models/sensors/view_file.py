"""A picture of `rostui view` kept in a file: its topics, fixed frame, zoom, centre, tools and robot.

::

    # rostui view: `rostui view FILE` opens it
    topics: [/map, /scan, /move_base/NavfnROS/plan]
    frame: map
    span: 12.5            # metres across the view
    centre: [1.5, -0.75]
    goal_topic: /move_base_simple/goal
    pose_topic: /initialpose
    cmd_vel_topic: /cmd_vel
    footprint: /move_base/local_costmap/footprint   # a parameter, or [[x, y], ...]
    robot_frame: base_link
    follow: false

``rostui view --save FILE`` writes one when the app quits; :func:`spec_from_rviz` makes one from an rviz
configuration (its enabled displays of the types rostui draws, its fixed frame, its SetGoal and
SetInitialPose topics and its current view), and says which displays it left out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from rostui.core import names
from rostui.core.one_line import exception_line
from rostui.tools.yaml_file import YamlFileError, node_line, node_value, read_yaml_node

__all__ = ["ViewFileError", "ViewSpec", "read_view_file", "write_view_file", "spec_from_rviz", "RVIZ_TOPIC_FIELDS"]

#: The rviz display classes `rostui view` draws, and the field that names each one's topic.
RVIZ_TOPIC_FIELDS: dict[str, str] = {
    "rviz/LaserScan": "Topic", "rviz/Map": "Topic", "rviz/Path": "Topic", "rviz/PoseArray": "Topic",
    "rviz/Pose": "Topic", "rviz/Odometry": "Topic", "rviz/PointCloud2": "Topic", "rviz/Polygon": "Topic",
    "rviz/Marker": "Marker Topic", "rviz/MarkerArray": "Marker Topic", "rviz/Image": "Image Topic",
}

#: The keys of a view file.
_KEYS = ("topics", "frame", "span", "centre", "goal_topic", "pose_topic", "cmd_vel_topic", "footprint",
         "robot_frame", "follow")

#: Most topics a view file opens (each is a subscription).
MAX_TOPICS = 64

#: rviz's window width when its file does not say (pixels), to turn its scale into metres across.
RVIZ_DEFAULT_WIDTH = 1200

#: The narrowest and widest views a file may ask for (metres across).
MIN_SPAN, MAX_SPAN = 1e-3, 1e7


class ViewFileError(ValueError):
    """What is wrong with a view file (or an rviz file): one line, ``FILE:LINE: what``."""


@dataclass
class ViewSpec:
    """What `rostui view` shows and how; None leaves a setting to the command line or the default."""

    topics: list[str] = field(default_factory=list)
    frame: str | None = None
    span: float | None = None
    centre: tuple[float, float] | None = None
    goal_topic: str | None = None
    pose_topic: str | None = None
    cmd_vel_topic: str | None = None
    footprint: Any = None
    robot_frame: str | None = None
    follow: bool = False

    def as_document(self) -> dict[str, Any]:
        """The spec as a YAML document (settings left as None are left out)."""
        document: dict[str, Any] = {"topics": list(self.topics)}
        for key in _KEYS[1:]:
            value = getattr(self, key)
            if key == "centre" and value is not None:
                value = [round(float(v), 4) for v in value]
            elif key == "span" and value is not None:
                value = round(float(value), 4)
            if value is not None and (key != "follow" or value):
                document[key] = value
        return document


def write_view_file(spec: ViewSpec, path: Path) -> None:
    """Write ``spec`` to ``path`` (OSError as the system says it)."""
    text = yaml.safe_dump(spec.as_document(), sort_keys=False, default_flow_style=None, width=100,
                          allow_unicode=True)
    path.write_text(f"# rostui view: `rostui view {path.name}` opens it\n{text}", encoding="utf-8")


def _topic(value: Any, where: str, line: int, key: str) -> str:
    if not isinstance(value, str) or not value.strip():
        raise ViewFileError(f"{where}:{line}: {key}: {value!r} is not a topic name")
    try:
        names.validate_name(value.strip(), "topic")
    except names.InvalidNameError as exc:
        raise ViewFileError(f"{where}:{line}: {key}: {exc}") from None
    return names.resolve_name(value.strip(), "/")


def _number(value: Any, where: str, line: int, key: str) -> float:
    try:
        number = float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else math.nan
    except OverflowError:
        number = math.nan
    if not math.isfinite(number):
        raise ViewFileError(f"{where}:{line}: {key}: {str(value)[:40]!r} is not a number")
    return number


def _value(node: yaml.Node, where: str) -> Any:
    """``node`` as Python values; one line for a value YAML cannot make (``!!float abc``, a list as a key)."""
    try:
        return node_value(node)
    except (yaml.YAMLError, ValueError, TypeError, OverflowError) as exc:
        raise ViewFileError(f"{where}:{node_line(node)}: not a value: {exception_line(exc)}") from None


def read_view_file(path: Path) -> ViewSpec:
    """The spec in the view file at ``path``; :class:`ViewFileError` (``FILE:LINE: what``) for anything wrong."""
    where = str(path)
    try:
        root = read_yaml_node(path, "a view file")
    except YamlFileError as exc:
        raise ViewFileError(str(exc)) from None
    if not isinstance(root, yaml.MappingNode):
        raise ViewFileError(f"{where}:{node_line(root)}: a view file is a mapping of {', '.join(_KEYS)}")
    spec = ViewSpec()
    for key_node, value_node in root.value:
        key, line = key_node.value, node_line(key_node)
        if key not in _KEYS:
            raise ViewFileError(f"{where}:{line}: unknown key {key!r} (a view file has {', '.join(_KEYS)})")
        value = _value(value_node, where)
        line = node_line(value_node)
        if key == "topics":
            if not isinstance(value, list) or not value or len(value) > MAX_TOPICS:
                raise ViewFileError(f"{where}:{line}: topics: a list of 1 to {MAX_TOPICS} topic names")
            spec.topics = [_topic(t, where, line, "topics") for t in value]
        elif key in ("goal_topic", "pose_topic", "cmd_vel_topic"):
            setattr(spec, key, _topic(value, where, line, key))
        elif key in ("frame", "robot_frame"):
            if not isinstance(value, str) or not value.strip("/ "):
                raise ViewFileError(f"{where}:{line}: {key}: {value!r} is not a frame name")
            setattr(spec, key, value.strip().lstrip("/"))
        elif key == "span":
            spec.span = _number(value, where, line, key)
            if not MIN_SPAN <= spec.span <= MAX_SPAN:
                raise ViewFileError(f"{where}:{line}: span: {value!r} metres is not between {MIN_SPAN:g} and "
                                    f"{MAX_SPAN:g}")
        elif key == "centre":
            if not isinstance(value, list) or len(value) != 2:
                raise ViewFileError(f"{where}:{line}: centre: [x, y] in metres")
            spec.centre = (_number(value[0], where, line, key), _number(value[1], where, line, key))
        elif key == "follow":
            if not isinstance(value, bool):
                raise ViewFileError(f"{where}:{line}: follow: true or false")
            spec.follow = value
        else:
            spec.footprint = value
    if not spec.topics:
        raise ViewFileError(f"{where}:{node_line(root)}: a view file needs `topics: [TOPIC, ...]`")
    return spec


def _mapping(value: Any) -> dict[str, Any]:
    return value if isinstance(value, dict) else {}


def _displays(displays: Any, kept: list[tuple[str, str]], skipped: list[str]) -> None:
    """Walk rviz's display list (groups nest their own); enabled displays of a drawn class give their topic."""
    for display in displays if isinstance(displays, list) else []:
        display = _mapping(display)
        kind, name = str(display.get("Class", "")), str(display.get("Name", ""))
        if display.get("Enabled", True) is False:
            continue
        if kind == "rviz/Group":
            _displays(display.get("Displays"), kept, skipped)
        elif kind in RVIZ_TOPIC_FIELDS:
            topic = display.get(RVIZ_TOPIC_FIELDS[kind])
            if isinstance(topic, str) and topic.strip():
                kept.append((kind, topic.strip()))
            else:
                skipped.append(f"{name or kind} ({kind}: no topic)")
        elif kind not in ("rviz/Grid", "rviz/Axes"):
            skipped.append(f"{name or kind} ({kind})")


def spec_from_rviz(path: Path) -> tuple[ViewSpec, list[str]]:
    """A view of the rviz configuration at ``path``, and the displays it leaves out (``Name (Class)``)."""
    where = str(path)
    try:
        root = read_yaml_node(path, "an rviz file")
    except YamlFileError as exc:
        raise ViewFileError(str(exc)) from None
    document = _mapping(_value(root, where)) if root is not None else {}
    manager = _mapping(document.get("Visualization Manager"))
    if not manager:
        raise ViewFileError(f"{where}:1: not an rviz configuration (no `Visualization Manager`)")
    kept: list[tuple[str, str]] = []
    skipped: list[str] = []
    _displays(manager.get("Displays"), kept, skipped)
    spec = ViewSpec()
    for kind, topic in kept:
        try:
            resolved = _topic(topic, where, 1, kind)
        except ViewFileError:
            skipped.append(f"{topic} ({kind}: not a topic name)")
            continue
        if resolved not in spec.topics and len(spec.topics) < MAX_TOPICS:
            spec.topics.append(resolved)
    frame = _mapping(manager.get("Global Options")).get("Fixed Frame")
    if isinstance(frame, str) and frame.strip("/ "):
        spec.frame = frame.strip().lstrip("/")
    tools = manager.get("Tools")
    for tool in tools if isinstance(tools, list) else []:
        tool = _mapping(tool)
        tool_topic = tool.get("Topic")
        key = {"rviz/SetGoal": "goal_topic", "rviz/SetInitialPose": "pose_topic"}.get(str(tool.get("Class")))
        if key and isinstance(tool_topic, str) and tool_topic.strip():
            try:
                setattr(spec, key, _topic(tool_topic, where, 1, key))
            except ViewFileError:
                skipped.append(f"{tool_topic} ({tool.get('Class')}: not a topic name)")
    current = _mapping(_mapping(manager.get("Views")).get("Current"))
    width = _mapping(document.get("Window Geometry")).get("Width", RVIZ_DEFAULT_WIDTH)
    width = width if isinstance(width, (int, float)) and not isinstance(width, bool) and width > 0 \
        else RVIZ_DEFAULT_WIDTH
    try:
        if current.get("Class") == "rviz/TopDownOrtho":
            scale = float(current.get("Scale", 0))
            if scale > 0 and math.isfinite(scale):
                spec.span = float(width) / scale
            spec.centre = (float(current.get("X", 0.0)), float(current.get("Y", 0.0)))
        elif current.get("Class") in ("rviz/Orbit", "rviz/XYOrbit", "rviz/ThirdPersonFollower"):
            distance = float(current.get("Distance", 0))
            if distance > 0 and math.isfinite(distance):
                spec.span = distance
            focal = _mapping(current.get("Focal Point"))
            spec.centre = (float(focal.get("X", 0.0)), float(focal.get("Y", 0.0)))
    except (TypeError, ValueError, OverflowError):
        spec.span, spec.centre = None, None
    if spec.span is not None and not MIN_SPAN <= spec.span <= MAX_SPAN:
        spec.span = None
    if spec.centre is not None and not all(math.isfinite(v) for v in spec.centre):
        spec.centre = None
    if not spec.topics:
        raise ViewFileError(f"{where}:1: no enabled display of a type rostui view draws "
                            f"({', '.join(sorted(RVIZ_TOPIC_FIELDS))})")
    return spec, skipped
