"""Keyboard teleoperation of a turtle: arrow keys to velocity commands.

Two faces share the same key bindings and scales:

* :func:`key_to_command` maps a key name (Textual's names: ``up``, ``down``,
  ``left``, ``right``) to a ``(linear, angular)`` command; the turtlesim app
  uses it for its built-in teleop.
* :func:`run_teleop` is ROS's ``turtle_teleop_key`` for any plain terminal
  (also behind ``rostui teleop TOPIC``): node ``teleop_turtle``, one command
  per key press, ``q`` quits.  It publishes ``geometry_msgs/Twist`` on
  ``turtle1/cmd_vel`` (today's turtlesim) and ``turtlesim/Velocity`` on
  ``turtle1/command_velocity`` (the book's topic); both names can be remapped.

Sending the Twist too would defeat the book's remapping examples: in
``reverse.launch`` a translator node listens on the book's topic while the
simulator also listens on ``cmd_vel``, so an unreversed Twist would reach the
turtle beside the reversed command.  :func:`twist_bypasses_translator` spots
that case, and the Twist is then left out.

Scales come from the parameters ``~scale_linear`` and ``~scale_angular``
(``_scale_linear:=0.5`` on the command line); like ROS's teleop the node also
honours the relative names ``scale_linear`` / ``scale_angular``.  Both default
to 2.0, so Up publishes linear 2.0 and Left angular 2.0, as in the book.
"""

from __future__ import annotations

import os
import select
import sys
import termios
from typing import Any, Callable, Iterator, Sequence

__all__ = [
    "DEFAULT_SCALE_ANGULAR", "DEFAULT_SCALE_LINEAR", "BANNER", "KeyDecoder", "TeleopError",
    "key_to_command", "read_scales", "run_teleop", "twist_bypasses_translator", "main",
]

DEFAULT_SCALE_LINEAR = 2.0
"""Linear speed (m/s) of one Up/Down press when ``~scale_linear`` is not set."""

DEFAULT_SCALE_ANGULAR = 2.0
"""Turn rate (rad/s) of one Left/Right press when ``~scale_angular`` is not set."""

NODE_NAME = "teleop_turtle"
TWIST_TOPIC = "turtle1/cmd_vel"
VELOCITY_TOPIC = "turtle1/command_velocity"

BANNER = (
    "Reading from keyboard",
    "---------------------------",
    "Use arrow keys to move the turtle. 'q' to quit.",
)
"""The lines printed when the teleop starts reading keys (ROS's wording)."""

_DIRECTIONS: dict[str, tuple[float, float]] = {
    "up": (1.0, 0.0),
    "down": (-1.0, 0.0),
    "left": (0.0, 1.0),
    "right": (0.0, -1.0),
}

_ARROW_FINALS = {ord("A"): "up", ord("B"): "down", ord("C"): "right", ord("D"): "left"}
_ESC = 0x1B
_POLL_SECONDS = 0.1


class TeleopError(Exception):
    """The teleop cannot run; the message is the one line to show the user."""


def key_to_command(key: str, scale_linear: float = DEFAULT_SCALE_LINEAR,
                   scale_angular: float = DEFAULT_SCALE_ANGULAR) -> tuple[float, float] | None:
    """The ``(linear, angular)`` command for an arrow key, or None for any other key.

    Up drives forward, Down backward, Left turns counter-clockwise (positive
    angular), Right clockwise.
    """
    direction = _DIRECTIONS.get(key)
    if direction is None:
        return None
    return direction[0] * scale_linear, direction[1] * scale_angular


def twist_bypasses_translator(twist_subscribers: set[str], velocity_subscribers: set[str]) -> bool:
    """True when a node listening on the book's velocity topic does not also listen on ``cmd_vel``.

    That node (reverse_cmd_vel, a recorder, a relay) sits between the teleop
    and a simulator; a Twist sent beside the Velocity would reach the
    simulator around it.  A turtlesim that listens on both topics is not such
    a node: it gets the same command twice, which changes nothing.
    """
    return bool(velocity_subscribers - twist_subscribers)


def read_scales(get_param: Callable[[str, Any], Any]) -> tuple[float, float]:
    """``(scale_linear, scale_angular)`` from the parameter server via ``get_param(name, default)``.

    The private name wins over the relative one; raises :class:`TeleopError`
    when a value is not a number.
    """
    def lookup(name: str, default: float) -> float:
        value = get_param("~" + name, get_param(name, default))
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise TeleopError(f"parameter ~{name} must be a number, got {value!r}")
        return float(value)
    return lookup("scale_linear", DEFAULT_SCALE_LINEAR), lookup("scale_angular", DEFAULT_SCALE_ANGULAR)


class KeyDecoder:
    """Turns bytes typed in a terminal into key names.

    Arrow keys arrive as escape sequences: ``ESC [ A`` (normal cursor mode),
    ``ESC O A`` (application cursor mode, common under tmux and screen) or
    ``ESC [ 1 ; 5 A`` (with a modifier); all of them become ``up``.  Other
    control sequences are swallowed whole, printable ASCII characters come out
    as themselves, Ctrl-C as ``ctrl+c``.  A sequence split across reads is kept
    until the rest arrives; :meth:`flush` gives up on it (a lone Escape key).
    """

    def __init__(self) -> None:
        self._pending = b""

    def feed(self, data: bytes) -> list[str]:
        """Decode ``data`` (and any incomplete sequence left over) into key names."""
        buf = self._pending + data
        keys: list[str] = []
        i = 0
        while i < len(buf):
            byte = buf[i]
            if byte != _ESC:
                if byte == 0x03:
                    keys.append("ctrl+c")
                elif 0x20 <= byte < 0x7F:
                    keys.append(chr(byte))
                i += 1
                continue
            consumed, key = self._escape_sequence(buf, i)
            if consumed == 0:
                break  # incomplete: wait for more bytes
            if key:
                keys.append(key)
            i += consumed
        self._pending = buf[i:]
        return keys

    def flush(self) -> list[str]:
        """Give up on an incomplete sequence (nothing followed it): report ``escape``."""
        if not self._pending:
            return []
        self._pending = b""
        return ["escape"]

    @staticmethod
    def _escape_sequence(buf: bytes, start: int) -> tuple[int, str]:
        """``(bytes consumed, key name or "")`` for the sequence at ``start``; 0 consumed = incomplete."""
        if start + 1 >= len(buf):
            return 0, ""
        kind = buf[start + 1]
        if kind == ord("O"):  # SS3: one final byte
            if start + 2 >= len(buf):
                return 0, ""
            return 3, _ARROW_FINALS.get(buf[start + 2], "")
        if kind != ord("["):
            return 1, "escape"
        i = start + 2
        while i < len(buf) and 0x30 <= buf[i] <= 0x3F:  # parameter bytes
            i += 1
        while i < len(buf) and 0x20 <= buf[i] <= 0x2F:  # intermediate bytes
            i += 1
        if i >= len(buf):
            return 0, ""
        if 0x40 <= buf[i] <= 0x7E:
            return i + 1 - start, _ARROW_FINALS.get(buf[i], "")
        return i - start, ""  # malformed: drop what was read, decode the rest normally


class _CbreakTerminal:
    """Context manager: the terminal without line buffering and echo, restored on exit."""

    def __init__(self, fd: int) -> None:
        self.fd = fd
        self.saved: list[Any] | None = None

    def __enter__(self) -> "_CbreakTerminal":
        self.saved = termios.tcgetattr(self.fd)
        mode = termios.tcgetattr(self.fd)
        mode[3] &= ~(termios.ICANON | termios.ECHO)  # keep ISIG: Ctrl-C still interrupts
        mode[6][termios.VMIN] = 1
        mode[6][termios.VTIME] = 0
        termios.tcsetattr(self.fd, termios.TCSANOW, mode)
        return self

    def __exit__(self, *exc: object) -> None:
        if self.saved is not None:
            termios.tcsetattr(self.fd, termios.TCSANOW, self.saved)


def _keys(fd: int, is_shutdown: Callable[[], bool]) -> Iterator[str]:
    """Key names typed on ``fd`` until end of input or the node shuts down."""
    decoder = KeyDecoder()
    while not is_shutdown():
        ready, _, _ = select.select([fd], [], [], _POLL_SECONDS)
        if not ready:
            yield from decoder.flush()
            continue
        data = os.read(fd, 64)
        if not data:
            return
        yield from decoder.feed(data)


def _stdin_terminal(program: str) -> int:
    """The file descriptor of stdin when it is a terminal; TeleopError otherwise."""
    try:
        fd = sys.stdin.fileno()
    except (AttributeError, ValueError, OSError):
        fd = -1
    if fd < 0 or not os.isatty(fd):
        raise TeleopError(f"{program}: standard input is not a terminal; run it in a terminal to read the arrow keys")
    return fd


def run_teleop(argv: Sequence[str], *, topic: str | None = None) -> int:
    """Drive a turtle with the arrow keys of this terminal; returns the exit status.

    ``argv`` is the command line after the program name (remaps such as
    ``turtle1/cmd_vel:=/foo``, ``_scale_linear:=0.5``, ``__name:=``...).
    With ``topic`` only ``geometry_msgs/Twist`` is published, on that topic.
    Prints one line and returns 1 when stdin is not a terminal or a scale
    parameter is not a number.
    """
    from rostui import client as ros
    from rostui.core.node.node import MasterError

    program = "turtle_teleop_key" if topic is None else "rostui teleop"
    try:
        fd = _stdin_terminal(program)
    except TeleopError as exc:
        print(exc, file=sys.stderr)
        return 1
    taken = _name_in_use(argv)
    if taken:
        print(f"[ WARN] {taken} is already running (turtlesim's arrow keys, or another teleop): ROS gives the name "
              "to the newest node, so that one stops; turtlesim's arrow keys drive again once this teleop ends",
              file=sys.stderr, flush=True)
    try:
        ros.init_node(NODE_NAME, argv=[sys.argv[0], *argv])
        scale_linear, scale_angular = read_scales(ros.get_param)
    except ros.ROSInterruptException:
        return 0
    except TeleopError as exc:
        print(f"{program}: {exc}", file=sys.stderr)
        ros.signal_shutdown("bad parameter")
        return 1
    try:
        return _drive(fd, ros, topic, scale_linear, scale_angular)
    except MasterError as exc:  # the master went away (a turtlesim hosting it quit)
        print(f"{program}: {exc}", file=sys.stderr)
        ros.signal_shutdown("no master")
        return 1


def _name_in_use(argv: Sequence[str]) -> str | None:
    """This teleop's node name when the master already knows a node by it (None otherwise, or without a
    master: init_node then says what is wrong)."""
    from rostui.core import names
    from rostui.core.masteruri import master_uri_from_env
    from rostui.core.xmlrpc.quick import quick_call

    try:
        args = names.parse_argv(list(argv))
        name = names.node_global_name(NODE_NAME, args)
        code, _message, _uri = quick_call(master_uri_from_env(args.master), "lookupNode", "/rostui_teleop", name,
                                          timeout=2.0)
    except Exception:
        return None
    return name if code == 1 else None


def _drive(fd: int, ros: Any, topic: str | None, scale_linear: float, scale_angular: float) -> int:
    """Advertise, print the banner and publish a command per arrow key until q or Ctrl-C."""
    Twist = ros.msg("geometry_msgs/Twist")
    Velocity = ros.msg("turtlesim/Velocity")
    twist_pub = ros.Publisher(topic or TWIST_TOPIC, Twist, queue_size=1)
    velocity_pub = None if topic else ros.Publisher(VELOCITY_TOPIC, Velocity, queue_size=1)

    with _CbreakTerminal(fd):
        for line in BANNER:
            print(line, flush=True)
        for key in _keys(fd, ros.is_shutdown):
            if key in ("q", "ctrl+c"):
                break
            command = key_to_command(key, scale_linear, scale_angular)
            if command is None:
                continue
            linear, angular = command
            twist: Any = Twist()  # a generated class: its fields are not known statically
            twist.linear.x = linear
            twist.angular.z = angular
            if velocity_pub is None:
                twist_pub.publish(twist)
                continue
            if not twist_bypasses_translator(twist_pub.subscriber_names(), velocity_pub.subscriber_names()):
                twist_pub.publish(twist)
            velocity_pub.publish(Velocity(linear=linear, angular=angular))
    ros.signal_shutdown("teleop finished")
    return 0


def main() -> int:
    """``turtle_teleop_key``: run_teleop with this process's command line."""
    return run_teleop(sys.argv[1:])
