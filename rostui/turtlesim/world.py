"""The turtlesim world: turtles, pens, walls and the path image, with no ROS in it.

The model follows ROS turtlesim (noetic's ``turtle.cpp`` / ``turtle_frame.cpp``)
number for number: the same 500 px image at 45 px per metre, the same
``float`` world size, the same update formulas evaluated in the same order
(ROS keeps positions in the image frame, y down, and so does this model;
``Turtle.y`` is the ROS-frame value, y up), velocity commands that expire
after one second of wall-clock time, and walls that clamp the turtle.

Geometry lives in a pymunk space, in the image frame (metres): the four
walls are static half-planes (very large boxes) around the square, so a
turtle past a wall is one the space finds inside that wall; each turtle is a
kinematic body with a circle shape.  With ``contacts=True`` the space also
keeps turtles from overlapping (off by default, as in ROS).
"""

from __future__ import annotations

import dataclasses
import math
import struct
import time
from dataclasses import dataclass, field
from typing import Callable, NamedTuple

import pymunk

from rostui.turtlesim.canvas import PIXELS, RGB, PathImage

METER = 45
"""Pixels per metre (the height of ROS turtlesim's turtle images)."""

_F32 = struct.Struct("f")


def f32(value: float) -> float:
    """``value`` rounded to a C ``float``, as ROS turtlesim stores sizes and spawn arguments."""
    return _F32.unpack(_F32.pack(value))[0]


WORLD_SIZE = f32((PIXELS - 1) / METER)
"""Width and height of the world in metres: (500 - 1) / 45 = 11.088889, as a C float like ROS's."""

UPDATE_PERIOD = 0.016
"""Seconds between updates (ROS turtlesim's 16 ms timer); also the fixed integration step."""

COMMAND_TIMEOUT = 1.0
"""Seconds of wall-clock time after which a velocity command stops applying."""

ROS_PI = 3.14159265
"""The value of pi turtlesim's headers define; angles wrap with it."""

DEFAULT_BACKGROUND: RGB = (69, 86, 255)
"""Background colour when the background_r/g/b parameters are absent."""

TURTLE_RADIUS = 0.5
"""Radius in metres of a turtle's body for contacts (the sprite is one metre across)."""

WALL_REACH = 1e100
"""How far (metres) each wall box extends outwards; positions beyond are not caught."""

_TWO_PI = 2 * ROS_PI
_WALL_CATEGORY = 0b01
_TURTLE_CATEGORY = 0b10
_WALLS_ONLY = pymunk.ShapeFilter(mask=_WALL_CATEGORY)


@dataclass(slots=True)
class Pen:
    """A turtle's pen: colour, width in pixels, and whether it is lifted."""

    r: int
    g: int
    b: int
    width: int
    off: bool = False

    @property
    def rgb(self) -> RGB:
        """The pen colour as an (r, g, b) tuple."""
        return self.r, self.g, self.b


DEFAULT_PEN = Pen(r=179, g=184, b=255, width=3, off=False)
"""Every turtle's pen when it is spawned (a copy of it)."""


class NameTaken(ValueError):
    """A turtle with the requested name already exists."""


class UnknownTurtle(KeyError):
    """No turtle has the given name."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else "unknown turtle"


class WallHit(NamedTuple):
    """A turtle went past a wall during an update and was clamped back.

    ``x`` and ``y`` are the unclamped position as ROS turtlesim prints it in
    its warning: ``y`` is measured *down* from the top edge (the image frame),
    so hitting the top wall shows a negative y.
    """

    name: str
    x: float
    y: float

    def message(self) -> str:
        """The WARN line ROS turtlesim logs for this hit."""
        return f"Oh no! I hit the wall! (Clamping from [x={self.x:f}, y={self.y:f}])"


@dataclass(slots=True, eq=False)
class Turtle:
    """One turtle: pose, commanded velocities, pen and colour sensor reading.

    ``x`` is metres from the left edge; ``down`` metres from the top edge (the
    frame ROS turtlesim computes in); ``y`` (property) is the ROS-frame value,
    metres up from the bottom edge.  ``theta`` is in radians, counter-clockwise
    from +x, wrapped to [-pi, pi) after each update.
    """

    name: str
    x: float
    down: float
    theta: float
    linear_x: float = 0.0
    linear_y: float = 0.0
    angular: float = 0.0
    pen: Pen = field(default_factory=lambda: dataclasses.replace(DEFAULT_PEN))
    last_command: float = -math.inf
    color: RGB = DEFAULT_BACKGROUND
    body: pymunk.Body | None = field(default=None, repr=False)
    prev_x: float = 0.0
    prev_down: float = 0.0

    @property
    def y(self) -> float:
        """Metres up from the bottom edge (ROS frame)."""
        return WORLD_SIZE - self.down

    @y.setter
    def y(self, value: float) -> None:
        self.down = WORLD_SIZE - value

    @property
    def linear_velocity(self) -> float:
        """The speed turtlesim reports in its Pose: the length of the commanded linear velocity."""
        return math.sqrt(self.linear_x * self.linear_x + self.linear_y * self.linear_y)


class _Wall(NamedTuple):
    """A wall: its shape in the space and the line it clamps to (axis 0 = x, 1 = down)."""

    shape: pymunk.Poly
    axis: int
    limit: float
    below: bool  # True when the wall covers coordinates below the limit


class TurtleWorld:
    """Turtles moving in a walled square and drawing on a shared path image."""

    def __init__(self, *, contacts: bool = False, clock: Callable[[], float] = time.monotonic,
                 background: RGB = DEFAULT_BACKGROUND) -> None:
        self.contacts = contacts
        self.clock = clock
        self.turtles: dict[str, Turtle] = {}
        self.image = PathImage(background)
        self.generation = 0
        self.space = pymunk.Space()
        self._walls = self._build_walls()
        self._id_counter = 0

    # -- geometry -----------------------------------------------------------------
    def _build_walls(self) -> tuple[_Wall, ...]:
        """Four static boxes that together cover everything outside [0, W] x [0, W]."""
        size, reach = WORLD_SIZE, WALL_REACH
        body = self.space.static_body
        boxes = (
            ((-reach, -reach, 0.0, reach), 0, 0.0, True),      # left: x < 0
            ((size, -reach, reach, reach), 0, size, False),    # right: x > W
            ((-reach, -reach, reach, 0.0), 1, 0.0, True),      # top: down < 0
            ((-reach, size, reach, reach), 1, size, False),    # bottom: down > W
        )
        walls = []
        for (left, top, right, bottom), axis, limit, below in boxes:
            shape = pymunk.Poly(body, [(left, top), (right, top), (right, bottom), (left, bottom)])
            shape.filter = pymunk.ShapeFilter(categories=_WALL_CATEGORY)
            self.space.add(shape)
            walls.append(_Wall(shape, axis, limit, below))
        return tuple(walls)

    def _clamp_to_walls(self, turtle: Turtle) -> WallHit | None:
        """Clamp a turtle the space finds inside a wall; report where it was."""
        found = self.space.point_query((turtle.x, turtle.down), 0.0, _WALLS_ONLY)
        if not found:
            return None
        hit = None
        for info in found:
            for wall in self._walls:
                if wall.shape is not info.shape:
                    continue
                value = turtle.x if wall.axis == 0 else turtle.down
                # The space also reports a turtle touching the wall's face; only one past it is clamped.
                if (value < wall.limit) if wall.below else (value > wall.limit):
                    if hit is None:
                        hit = WallHit(turtle.name, turtle.x, turtle.down)
                    if wall.axis == 0:
                        turtle.x = wall.limit
                    else:
                        turtle.down = wall.limit
        return hit

    def _place_body(self, turtle: Turtle) -> None:
        body = turtle.body
        assert body is not None
        body.position = (turtle.x, turtle.down)
        body.angle = -turtle.theta
        self.space.reindex_shapes_for_body(body)

    def _separate_turtles(self) -> None:
        """Push overlapping turtles apart; a turtle that did not move this update is not pushed."""
        turtles = list(self.turtles.values())
        for turtle in turtles:
            self._place_body(turtle)
        for turtle in turtles:
            body = turtle.body
            assert body is not None
            for info in self.space.shape_query(next(iter(body.shapes))):
                other = _turtle_of(info.shape)
                if other is None or other is turtle:
                    continue
                points = info.contact_point_set.points
                if not points:
                    continue
                depth = -min(p.distance for p in points)
                if depth <= 0.0:
                    continue
                nx, ny = info.contact_point_set.normal  # from `turtle` towards `other`
                mine = _moved(turtle)
                theirs = _moved(other)
                share = 0.5 if mine == theirs else (1.0 if mine else 0.0)
                turtle.x -= nx * depth * share
                turtle.down -= ny * depth * share
                other.x += nx * depth * (1.0 - share)
                other.down += ny * depth * (1.0 - share)
                self._place_body(turtle)
                self._place_body(other)

    # -- turtles --------------------------------------------------------------------
    @property
    def background(self) -> RGB:
        """The colour the image was last cleared with."""
        return self.image.background

    def _get(self, name: str) -> Turtle:
        try:
            return self.turtles[name]
        except KeyError:
            raise UnknownTurtle(name) from None

    def spawn(self, name: str, x: float, y: float, theta: float) -> str:
        """Add a turtle at ROS-frame (x, y) heading theta; "" picks the next free ``turtleN``.

        Raises NameTaken when a turtle of that name exists.  Like ROS, the
        position is not clamped here; the next update does that (with a WARN).
        """
        if not name:
            while True:
                self._id_counter += 1
                name = f"turtle{self._id_counter}"
                if name not in self.turtles:
                    break
        elif name in self.turtles:
            raise NameTaken(f"A turtle named [{name}] already exists")
        turtle = Turtle(name=name, x=f32(x), down=f32(WORLD_SIZE - f32(y)), theta=f32(theta))
        body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        shape = pymunk.Circle(body, TURTLE_RADIUS)
        shape.filter = pymunk.ShapeFilter(categories=_TURTLE_CATEGORY, mask=_TURTLE_CATEGORY)
        shape.turtle = turtle
        turtle.body = body
        turtle.prev_x, turtle.prev_down = turtle.x, turtle.down
        self.space.add(body, shape)
        self._place_body(turtle)
        turtle.color = self._sample(turtle)
        self.turtles[name] = turtle
        self.generation += 1
        return name

    def kill(self, name: str) -> None:
        """Remove a turtle; UnknownTurtle if there is none of that name."""
        turtle = self._get(name)
        del self.turtles[name]
        if turtle.body is not None:
            self.space.remove(turtle.body, *turtle.body.shapes)
            turtle.body = None
        self.generation += 1

    def command(self, name: str, linear_x: float, linear_y: float, angular: float) -> None:
        """Set a turtle's velocities (m/s, m/s, rad/s in its own frame) for the next second."""
        turtle = self._get(name)
        turtle.last_command = self.clock()
        turtle.linear_x = linear_x
        turtle.linear_y = linear_y
        turtle.angular = angular

    def set_pen(self, name: str, r: int, g: int, b: int, width: int, off: bool) -> None:
        """Change a turtle's pen as turtlesim's set_pen does.

        ``off`` lifts the pen and keeps its colour and width; otherwise the pen
        gets the colour and, unless ``width`` is 0, the width (0 gives 1 px).
        """
        turtle = self._get(name)
        if off:
            turtle.pen.off = True
            return
        turtle.pen = Pen(r=int(r), g=int(g), b=int(b), width=int(width) if width else 1, off=False)

    def teleport_absolute(self, name: str, x: float, y: float, theta: float) -> None:
        """Move a turtle to ROS-frame (x, y) heading theta, drawing the jump if the pen is down."""
        turtle = self._get(name)
        old_x, old_down = turtle.x, turtle.down
        turtle.x = f32(x)
        turtle.down = max(0.0, WORLD_SIZE - f32(y))
        turtle.theta = theta
        self._jumped(turtle, old_x, old_down)

    def teleport_relative(self, name: str, linear: float, angular: float) -> None:
        """Turn a turtle by ``angular`` then move it ``linear`` metres ahead, drawing if the pen is down."""
        turtle = self._get(name)
        old_x, old_down = turtle.x, turtle.down
        turtle.theta += angular
        turtle.x += math.cos(turtle.theta) * linear
        turtle.down += -math.sin(turtle.theta) * linear
        self._jumped(turtle, old_x, old_down)

    def _jumped(self, turtle: Turtle, old_x: float, old_down: float) -> None:
        if not turtle.pen.off:
            self._draw(turtle, old_x, old_down)
        if turtle.body is not None and self.contacts:
            self._place_body(turtle)
        self.generation += 1

    def clear(self, background: RGB | None = None) -> None:
        """Erase all trails, filling with ``background`` (default: the current one)."""
        self.image.clear(background)
        self.generation += 1

    def reset(self, background: RGB | None = None) -> None:
        """Remove every turtle, restart the names, spawn turtle1 at the centre and clear."""
        for name in list(self.turtles):
            self.kill(name)
        self._id_counter = 0
        centre = WORLD_SIZE / 2.0
        self.spawn("", centre, centre, 0.0)
        self.clear(background)

    def color_under(self, name: str) -> RGB:
        """What the turtle's colour sensor reads: the pixel under it before its own pen marked it this update."""
        return self._get(name).color

    # -- time -------------------------------------------------------------------------
    def update(self, dt: float = UPDATE_PERIOD) -> list[WallHit]:
        """Advance every turtle by ``dt`` seconds; return the wall hits of this update."""
        now = self.clock()
        hits: list[WallHit] = []
        moved = False
        turtles = self.turtles.values()
        for turtle in turtles:
            moved |= self._integrate(turtle, dt, now)
        if self.contacts and moved and len(self.turtles) > 1:
            self._separate_turtles()
        for turtle in turtles:
            hit = self._clamp_to_walls(turtle)
            if hit is not None:
                hits.append(hit)
            turtle.color = self._sample(turtle)
            if turtle.x != turtle.prev_x or turtle.down != turtle.prev_down:
                if not turtle.pen.off:
                    self._draw(turtle, turtle.prev_x, turtle.prev_down)
        if moved or hits:
            self.generation += 1
        return hits

    def _integrate(self, turtle: Turtle, dt: float, now: float) -> bool:
        """Apply the velocities for one step exactly as turtlesim computes it; True if the pose changed."""
        if now - turtle.last_command > COMMAND_TIMEOUT:
            turtle.linear_x = turtle.linear_y = turtle.angular = 0.0
        x = turtle.prev_x = turtle.x
        down = turtle.prev_down = turtle.down
        old_theta = turtle.theta
        theta = old_theta + turtle.angular * dt
        theta -= _TWO_PI * math.floor((theta + ROS_PI) / _TWO_PI)
        lx = turtle.linear_x
        ly = turtle.linear_y
        if lx != 0.0 or ly != 0.0:
            cos_t = math.cos(theta)
            sin_t = math.sin(theta)
            turtle.x = x + (cos_t * lx * dt - sin_t * ly * dt)
            turtle.down = down - (cos_t * ly * dt + sin_t * lx * dt)
        turtle.theta = theta
        return theta != old_theta or turtle.x != x or turtle.down != down

    def _sample(self, turtle: Turtle) -> RGB:
        """The image pixel nearest to the turtle (Qt's rounding of the position in pixels)."""
        last = self.image.size - 1
        px = min(max(math.floor(turtle.x * METER + 0.5), 0), last) if math.isfinite(turtle.x) else 0
        py = min(max(math.floor(turtle.down * METER + 0.5), 0), last) if math.isfinite(turtle.down) else 0
        return self.image.pixel(px, py)

    def _draw(self, turtle: Turtle, from_x: float, from_down: float) -> None:
        pen = turtle.pen
        self.image.draw_line(turtle.x * METER, turtle.down * METER, from_x * METER, from_down * METER,
                             (pen.r, pen.g, pen.b), pen.width)


def _turtle_of(shape: pymunk.Shape) -> Turtle | None:
    return getattr(shape, "turtle", None)


def _moved(turtle: Turtle) -> bool:
    return turtle.x != turtle.prev_x or turtle.down != turtle.prev_down
