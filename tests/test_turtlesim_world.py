"""The turtlesim model: motion, walls, command timeout, pens, services' effects and the path image."""

from __future__ import annotations

import math

import pytest

from rostui.turtlesim.canvas import PIXELS, PathImage
from rostui.turtlesim.world import (
    COMMAND_TIMEOUT,
    DEFAULT_BACKGROUND,
    DEFAULT_PEN,
    METER,
    ROS_PI,
    TURTLE_RADIUS,
    UPDATE_PERIOD,
    WORLD_SIZE,
    NameTaken,
    TurtleWorld,
    UnknownTurtle,
)

CENTRE = WORLD_SIZE / 2.0
PEN_RGB = (DEFAULT_PEN.r, DEFAULT_PEN.g, DEFAULT_PEN.b)


class FakeClock:
    """A wall clock the test moves by hand."""

    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


def world_with_turtle1(**kwargs) -> tuple[TurtleWorld, FakeClock]:
    clock = FakeClock()
    world = TurtleWorld(clock=clock, **kwargs)
    world.spawn("", CENTRE, CENTRE, 0.0)
    return world, clock


def drive(world: TurtleWorld, name: str, lx: float, ly: float, az: float, updates: int) -> list:
    """Command once, then update ``updates`` times within the command's second."""
    world.command(name, lx, ly, az)
    hits = []
    for _ in range(updates):
        hits += world.update()
    return hits


def wrap(theta: float) -> float:
    return theta - 2 * ROS_PI * math.floor((theta + ROS_PI) / (2 * ROS_PI))


# --------------------------------------------------------------------------- constants
def test_world_matches_ros_turtlesim_dimensions() -> None:
    assert PIXELS == 500 and METER == 45
    assert WORLD_SIZE == pytest.approx(11.088889, abs=1e-6)
    assert UPDATE_PERIOD == 0.016
    world, _ = world_with_turtle1()
    t = world.turtles["turtle1"]
    assert (round(t.x, 6), round(t.y, 6), t.theta) == (5.544445, 5.544445, 0.0)
    assert world.background == DEFAULT_BACKGROUND == (69, 86, 255)
    assert t.pen == DEFAULT_PEN and (DEFAULT_PEN.width, DEFAULT_PEN.off) == (3, False)


# --------------------------------------------------------------------------- motion
def test_straight_line_matches_analytic_result() -> None:
    world, _ = world_with_turtle1()
    drive(world, "turtle1", 2.0, 0.0, 0.0, 50)
    t = world.turtles["turtle1"]
    assert t.x == pytest.approx(CENTRE + 50 * 2.0 * UPDATE_PERIOD, abs=1e-12)
    assert t.y == pytest.approx(CENTRE, abs=1e-12)
    assert t.theta == 0.0 and t.linear_velocity == 2.0


def test_sideways_velocity_moves_left_of_heading() -> None:
    world, _ = world_with_turtle1()
    drive(world, "turtle1", 0.0, 1.0, 0.0, 40)
    t = world.turtles["turtle1"]
    assert t.x == pytest.approx(CENTRE, abs=1e-12)
    assert t.y == pytest.approx(CENTRE + 40 * UPDATE_PERIOD, abs=1e-12)


def test_pure_rotation_wraps_like_turtlesim() -> None:
    world, _ = world_with_turtle1()
    drive(world, "turtle1", 0.0, 0.0, 2.0, 120)
    t = world.turtles["turtle1"]
    assert t.theta == pytest.approx(wrap(120 * 2.0 * UPDATE_PERIOD), abs=1e-9)
    assert -ROS_PI <= t.theta < ROS_PI
    assert (t.x, t.y) == pytest.approx((CENTRE, CENTRE), abs=1e-12)


def test_arc_matches_closed_form_of_the_update_rule() -> None:
    """Each update turns first, then moves along the new heading: a sum of cosines with a closed form."""
    world, _ = world_with_turtle1()
    v, w, n = 2.0, 1.8, 60
    drive(world, "turtle1", v, 0.0, w, n)
    t = world.turtles["turtle1"]
    d = w * UPDATE_PERIOD
    ratio = math.sin(n * d / 2) / math.sin(d / 2)
    mid = (n + 1) * d / 2
    assert t.x == pytest.approx(CENTRE + v * UPDATE_PERIOD * ratio * math.cos(mid), abs=1e-9)
    assert t.y == pytest.approx(CENTRE + v * UPDATE_PERIOD * ratio * math.sin(mid), abs=1e-9)
    assert t.theta == pytest.approx(wrap(n * d), abs=1e-9)
    # And it is close to the continuous circle of radius v/w.
    radius = v / w
    assert math.hypot(t.x - CENTRE, t.y - (CENTRE + radius)) == pytest.approx(radius, rel=0.02)


def test_command_expires_after_one_second_of_wall_clock() -> None:
    world, clock = world_with_turtle1()
    world.command("turtle1", 1.0, 0.0, 0.5)
    clock.now += COMMAND_TIMEOUT  # exactly one second: still applies
    world.update()
    t = world.turtles["turtle1"]
    moved_to = t.x
    assert moved_to > CENTRE and t.linear_x == 1.0
    clock.now += 0.01
    world.update()
    assert t.x == moved_to and (t.linear_x, t.angular, t.linear_velocity) == (0.0, 0.0, 0.0)
    world.command("turtle1", 1.0, 0.0, 0.0)
    world.update()
    assert t.x > moved_to


# --------------------------------------------------------------------------- walls
def test_driving_into_right_wall_clamps_and_reports_the_hit() -> None:
    world, _ = world_with_turtle1()
    hits = drive(world, "turtle1", 2.0, 0.0, 0.0, 200)
    t = world.turtles["turtle1"]
    assert t.x == WORLD_SIZE and t.y == pytest.approx(CENTRE)
    assert hits, "no wall hit reported"
    first = hits[0]
    assert first.name == "turtle1" and first.x > WORLD_SIZE and first.x < WORLD_SIZE + 2.0 * UPDATE_PERIOD
    assert first.message().startswith("Oh no! I hit the wall! (Clamping from [x=11.1")
    # Pushing on keeps warning every update, as turtlesim does.
    assert len(hits) == 200 - math.floor((WORLD_SIZE - CENTRE) / (2.0 * UPDATE_PERIOD))


def test_top_wall_warning_shows_turtlesims_downward_y() -> None:
    world, _ = world_with_turtle1()
    world.teleport_absolute("turtle1", 3.0, CENTRE, math.pi / 2)
    hits = drive(world, "turtle1", 2.0, 0.0, 0.0, 200)
    t = world.turtles["turtle1"]
    assert t.y == WORLD_SIZE and t.x == pytest.approx(3.0)
    assert hits and hits[0].y < 0.0 and hits[0].x == pytest.approx(3.0)
    assert "y=-0.0" in hits[0].message()


def test_turtle_resting_on_a_wall_does_not_warn() -> None:
    world, _ = world_with_turtle1()
    drive(world, "turtle1", 2.0, 0.0, 0.0, 200)
    world.teleport_absolute("turtle1", 0.0, 2.0, math.pi / 2)
    assert drive(world, "turtle1", 1.0, 0.0, 0.0, 20) == []
    assert world.turtles["turtle1"].x == pytest.approx(0.0, abs=1e-12)


def test_corner_clamps_both_axes_with_one_hit() -> None:
    world, _ = world_with_turtle1()
    world.teleport_absolute("turtle1", 0.05, 0.05, -3 * math.pi / 4)
    hits = drive(world, "turtle1", 5.0, 0.0, 0.0, 1)
    t = world.turtles["turtle1"]
    assert (t.x, t.y) == (0.0, WORLD_SIZE - WORLD_SIZE)
    assert len(hits) == 1 and hits[0].x < 0 and hits[0].y > WORLD_SIZE


def test_spawn_outside_is_clamped_on_next_update() -> None:
    world, _ = world_with_turtle1()
    world.spawn("far", -4.0, 30.0, 0.0)
    hits = world.update()
    assert [h.name for h in hits] == ["far"]
    far = world.turtles["far"]
    assert (far.x, far.y) == (0.0, WORLD_SIZE)


# --------------------------------------------------------------------------- teleport
def test_teleport_absolute_and_relative() -> None:
    world, _ = world_with_turtle1()
    world.teleport_absolute("turtle1", 2.0, 3.0, 1.0)
    t = world.turtles["turtle1"]
    assert (t.x, t.theta) == (2.0, 1.0) and t.y == pytest.approx(3.0, abs=1e-6)
    world.teleport_relative("turtle1", 2.0, math.pi / 2 - 1.0)
    assert t.theta == pytest.approx(math.pi / 2)
    assert t.x == pytest.approx(2.0, abs=1e-9) and t.y == pytest.approx(5.0, abs=1e-6)
    world.teleport_absolute("turtle1", 4.0, 50.0, 0.0)  # above the top: turtlesim puts it on the top edge
    assert t.y == WORLD_SIZE


def test_teleport_draws_with_the_pen_unless_it_is_off() -> None:
    world, _ = world_with_turtle1()
    world.teleport_absolute("turtle1", 1.0, 1.0, 0.0)
    world.teleport_absolute("turtle1", 9.0, 1.0, 0.0)
    row = round((WORLD_SIZE - 1.0) * METER)
    assert world.image.pixel(round(5.0 * METER), row) == PEN_RGB
    world.set_pen("turtle1", 0, 0, 0, 0, True)
    world.teleport_absolute("turtle1", 9.0, 8.0, 0.0)
    assert world.image.pixel(round(9.0 * METER), round((WORLD_SIZE - 5.0) * METER)) == DEFAULT_BACKGROUND


# --------------------------------------------------------------------------- pen
def _trail_row(world: TurtleWorld) -> int:
    return round(world.turtles["turtle1"].down * METER)


def test_pen_colour_and_width_draw_into_the_image() -> None:
    world, _ = world_with_turtle1()
    world.set_pen("turtle1", 255, 0, 0, 5, False)
    drive(world, "turtle1", 2.0, 0.0, 0.0, 40)
    row = _trail_row(world)
    col = round(6.5 * METER)
    assert world.image.pixel(col, row) == (255, 0, 0)
    assert world.image.pixel(col, row - 2) == (255, 0, 0) and world.image.pixel(col, row + 2) == (255, 0, 0)
    assert world.image.pixel(col, row - 3) == DEFAULT_BACKGROUND
    assert world.image.pixel(col, row + 3) == DEFAULT_BACKGROUND


def test_default_pen_is_three_pixels_wide() -> None:
    world, _ = world_with_turtle1()
    drive(world, "turtle1", 2.0, 0.0, 0.0, 40)
    col = round(6.5 * METER)
    painted = [py for py in range(PIXELS) if world.image.pixel(col, py) != DEFAULT_BACKGROUND]
    assert len(painted) == 3 and all(world.image.pixel(col, py) == PEN_RGB for py in painted)


def test_pen_off_draws_nothing_and_keeps_the_colour() -> None:
    world, _ = world_with_turtle1()
    world.set_pen("turtle1", 10, 20, 30, 4, False)
    world.set_pen("turtle1", 0, 0, 0, 0, True)
    before = world.image.generation
    drive(world, "turtle1", 2.0, 0.0, 1.0, 40)
    assert world.image.generation == before
    pen = world.turtles["turtle1"].pen
    assert pen.off and pen.rgb == (10, 20, 30) and pen.width == 4
    world.set_pen("turtle1", 1, 2, 3, 0, False)  # width 0: Qt's default one-pixel pen
    assert world.turtles["turtle1"].pen.width == 1 and not world.turtles["turtle1"].pen.off


# --------------------------------------------------------------------------- clear, reset, spawn, kill
def test_clear_erases_trails_and_can_change_background() -> None:
    world, _ = world_with_turtle1()
    drive(world, "turtle1", 2.0, 0.0, 0.0, 40)
    world.clear()
    assert set(world.image.region(0, 0, PIXELS - 1, PIXELS - 1)) == {DEFAULT_BACKGROUND}
    world.clear((255, 255, 0))
    assert world.background == (255, 255, 0)
    assert set(world.image.region(100, 100, 110, 110)) == {(255, 255, 0)}


def test_reset_leaves_only_turtle1_at_the_centre() -> None:
    world, _ = world_with_turtle1()
    world.spawn("", 1.0, 1.0, 0.0)
    world.spawn("Mikey", 3.0, 3.0, 0.0)
    drive(world, "turtle1", 2.0, 0.0, 1.0, 40)
    world.reset((1, 2, 3))
    assert list(world.turtles) == ["turtle1"]
    t = world.turtles["turtle1"]
    assert (t.x, t.y, t.theta) == pytest.approx((CENTRE, CENTRE, 0.0))
    assert world.background == (1, 2, 3)
    assert world.spawn("", 1.0, 1.0, 0.0) == "turtle2"


def test_spawn_picks_free_names_and_refuses_duplicates() -> None:
    world, _ = world_with_turtle1()
    assert world.spawn("", 1.0, 1.0, 0.0) == "turtle2"
    assert world.spawn("turtle3", 1.0, 2.0, 0.0) == "turtle3"
    assert world.spawn("", 1.0, 3.0, 0.0) == "turtle4"
    assert world.spawn("Mikey", 3.0, 3.0, 0.0) == "Mikey"
    with pytest.raises(NameTaken, match=r"A turtle named \[Mikey\] already exists"):
        world.spawn("Mikey", 4.0, 4.0, 0.0)
    assert list(world.turtles) == ["turtle1", "turtle2", "turtle3", "turtle4", "Mikey"]
    m = world.turtles["Mikey"]
    assert (m.x, m.y) == pytest.approx((3.0, 3.0), abs=1e-6)


def test_kill_removes_and_unknown_is_an_error() -> None:
    world, _ = world_with_turtle1()
    world.spawn("Mikey", 3.0, 3.0, 0.0)
    generation = world.generation
    world.kill("Mikey")
    assert "Mikey" not in world.turtles and world.generation != generation
    with pytest.raises(UnknownTurtle):
        world.kill("Mikey")
    with pytest.raises(KeyError):
        world.command("nobody", 1.0, 0.0, 0.0)
    assert world.spawn("Mikey", 3.0, 3.0, 0.0) == "Mikey"


# --------------------------------------------------------------------------- colour sensor
def test_colour_sensor_reads_trails_and_background() -> None:
    world, _ = world_with_turtle1()
    world.set_pen("turtle1", 200, 10, 10, 3, False)
    drive(world, "turtle1", 2.0, 0.0, 0.0, 60)  # a red trail along the middle row
    world.spawn("reader", 6.0, CENTRE + 2.0, -math.pi / 2)
    world.set_pen("reader", 0, 0, 0, 0, True)
    world.update()
    assert world.color_under("reader") == DEFAULT_BACKGROUND
    world.command("reader", 2.0, 0.0, 0.0)
    seen = []
    for _ in range(120):
        world.update()
        seen.append(world.color_under("reader"))
    assert (200, 10, 10) in seen and seen[-1] == DEFAULT_BACKGROUND
    # The sensor sees what lay there before the turtle's own pen marked it: a crossing of the own trail.
    world.set_pen("turtle1", 0, 200, 0, 3, False)
    world.teleport_absolute("turtle1", 6.0, CENTRE - 1.0, math.pi / 2)
    world.command("turtle1", 2.0, 0.0, 0.0)
    readings = []
    for _ in range(60):
        world.update()
        readings.append(world.color_under("turtle1"))
    assert (200, 10, 10) in readings



def test_colour_sensor_reads_the_own_trail_unless_the_turtle_outruns_it() -> None:
    """As in ROS turtlesim: the pixel under the turtle's centre, read after each move and before that move's stroke.

    The previous stroke's square end reaches half a pen width (1.5 px) past where the turtle was, so a turtle
    with its pen down mostly reads its own trail (chapter 7's fast_yellow: the pen colour, not the yellow): always
    at 1 m/s and after it stops; never at 3 m/s, which moves it 2.2 px per update; with the pen off, the background.
    """
    def readings(speed: float, pen_off: bool = False) -> list[tuple[int, int, int]]:
        world, _ = world_with_turtle1()
        world.clear((255, 255, 0))
        world.set_pen("turtle1", 179, 184, 255, 3, pen_off)
        seen = []
        for _ in range(40):
            world.command("turtle1", speed, 0.0, 0.0)
            world.update()
            seen.append(world.color_under("turtle1"))
        world.command("turtle1", 0.0, 0.0, 0.0)
        world.update()
        return seen[1:] + [world.color_under("turtle1")]

    assert set(readings(1.0)) == {DEFAULT_PEN.rgb}
    fast = readings(3.0)
    assert set(fast[:-1]) == {(255, 255, 0)} and fast[-1] == DEFAULT_PEN.rgb  # stopped on the end of its trail
    assert set(readings(1.0, pen_off=True)) == {(255, 255, 0)}


# --------------------------------------------------------------------------- contacts
def _head_on(contacts: bool) -> float:
    clock = FakeClock()
    world = TurtleWorld(clock=clock, contacts=contacts)
    world.spawn("a", 3.0, 5.0, 0.0)
    world.spawn("b", 8.0, 5.0, math.pi)
    for _ in range(120):
        world.command("a", 2.0, 0.0, 0.0)
        world.command("b", 2.0, 0.0, 0.0)
        world.update()
    a, b = world.turtles["a"], world.turtles["b"]
    return math.hypot(a.x - b.x, a.y - b.y)


def test_contacts_keep_turtles_apart_and_are_off_by_default() -> None:
    assert _head_on(contacts=True) >= 2 * TURTLE_RADIUS - 1e-6
    assert _head_on(contacts=False) > 2.0  # they passed through each other, as in ROS
    assert TurtleWorld().contacts is False


def test_contact_does_not_push_a_resting_turtle() -> None:
    world = TurtleWorld(clock=FakeClock(), contacts=True)
    world.spawn("mover", 2.0, 5.0, 0.0)
    world.spawn("rock", 5.0, 5.0, 0.0)
    for _ in range(150):
        world.command("mover", 2.0, 0.0, 0.0)
        world.update()
    rock, mover = world.turtles["rock"], world.turtles["mover"]
    assert (rock.x, rock.y) == pytest.approx((5.0, 5.0), abs=1e-6)
    assert rock.x - mover.x == pytest.approx(2 * TURTLE_RADIUS, abs=1e-6)


# --------------------------------------------------------------------------- path image
def test_path_image_reports_dirty_rectangles_and_full_redraws() -> None:
    image = PathImage((0, 0, 0))
    g0 = image.generation
    rect = image.draw_line(10.0, 10.0, 20.0, 10.0, (1, 2, 3), 3)
    assert rect == (9, 9, 21, 11)
    assert image.pixel(15, 10) == (1, 2, 3) and image.pixel(15, 12) == (0, 0, 0)
    generation, rects = image.changes_since(g0)
    assert generation == image.generation > g0 and rects == [rect]
    assert image.changes_since(generation) == (generation, [])
    image.clear((9, 9, 9))
    assert image.changes_since(generation) == (image.generation, None)
    assert image.draw_line(5.0, 5.0, 5.0, 5.0, (1, 1, 1), 3) is None
    edge = image.draw_line(-50.0, -50.0, 600.0, 600.0, (4, 4, 4), 1)
    assert edge is not None and edge[0] >= 0 and edge[3] <= PIXELS - 1
    assert image.pixel(0, 0) == image.pixel(499, 499) == (4, 4, 4)


def test_world_generation_changes_only_when_something_visible_changes() -> None:
    world, _ = world_with_turtle1()
    g = world.generation
    world.update()
    assert world.generation == g
    drive(world, "turtle1", 1.0, 0.0, 0.0, 1)
    assert world.generation > g
