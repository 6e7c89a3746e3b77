"""FrameBudget: frames are spaced so one panel's CPU per second stays within the share (fake clocks), and
what another panel (or thread) spends is never charged to it."""

from __future__ import annotations

import threading
import time

import pytest

from rostui.models.frame_budget import FrameBudget, SharedCost


class Clocks:
    """A wall clock and a CPU clock the test moves by hand."""

    def __init__(self) -> None:
        self.wall = 0.0
        self.cpu = 0.0


def run(frame_cost: float, arrivals_hz: float, share: float, seconds: float) -> tuple[int, float]:
    """Frames drawn and CPU seconds used when frames costing ``frame_cost`` arrive at ``arrivals_hz``.

    As in the view's panel: a frame that arrives waits (only the newest is kept) until the budget lets
    it be drawn; drawing costs CPU, measured around the frame.  Time moves in 1 ms ticks.
    """
    clocks = Clocks()
    budget = FrameBudget(share, wall=lambda: clocks.wall, cpu=lambda: clocks.cpu)
    drawn = 0
    period = 1.0 / arrivals_hz
    next_arrival = 0.0
    pending = False
    for tick in range(int(seconds * 1000)):
        clocks.wall = tick / 1000
        if clocks.wall >= next_arrival:
            pending, next_arrival = True, next_arrival + period
        if pending and budget.wait() == 0.0:
            with budget.spending():
                clocks.cpu += frame_cost
            drawn, pending = drawn + 1, False
    return drawn, clocks.cpu


def test_cheap_frames_are_all_drawn() -> None:
    drawn, cpu = run(frame_cost=0.005, arrivals_hz=30, share=0.45, seconds=10)
    assert drawn >= 299 and cpu / 10 < 0.45


@pytest.mark.parametrize("cost", [0.016, 0.030, 0.100])
def test_costly_frames_are_dropped_to_keep_the_share(cost: float) -> None:
    drawn, cpu = run(frame_cost=cost, arrivals_hz=30, share=0.45, seconds=20)
    assert cpu / 20 <= 0.45 + cost / 20  # within the share, give or take the frame in flight
    assert drawn >= min(20 * 30, int(20 * 0.45 / cost)) * 0.95  # and no more frames dropped than the share needs


def test_a_pause_buys_only_a_short_burst() -> None:
    clocks = Clocks()
    budget = FrameBudget(0.5, wall=lambda: clocks.wall, cpu=lambda: clocks.cpu)
    assert budget.wait() == 0.0
    clocks.wall = 60.0  # a minute with no frames
    budget.charge(0.5)  # then frames worth 0.5 s of CPU at once
    assert budget.wait() == pytest.approx(0.5)  # the reserve covered 0.25 s of it; 0.25 s is owed at 0.5/s


def test_each_panel_is_charged_only_its_own_frames() -> None:
    """Two panels in one process: the heavy one's frames overdraw its account, never its neighbour's (before,
    every panel was charged the whole process's CPU, so one heavy topic held every other panel back)."""
    clocks = Clocks()
    heavy = FrameBudget(0.45, wall=lambda: clocks.wall, cpu=lambda: clocks.cpu)
    light = FrameBudget(0.45, wall=lambda: clocks.wall, cpu=lambda: clocks.cpu)
    light_drawn = 0
    for tick in range(1, 101):  # ten seconds: a 1 s frame on the heavy panel whenever it may, a 10 Hz light one
        clocks.wall = tick / 10
        if heavy.wait() == 0.0:
            with heavy.spending():
                clocks.cpu += 1.0
        if light.wait() == 0.0:
            with light.spending():
                clocks.cpu += 0.002
            light_drawn += 1
    assert light_drawn == 100
    assert heavy.spent <= 10 * 0.45 + 1.0


def test_the_cpu_of_other_threads_is_not_charged() -> None:
    budget = FrameBudget(0.45)
    done = threading.Event()

    def spin() -> None:
        end = time.process_time() + 0.3
        while time.process_time() < end:
            pass
        done.set()

    with budget.spending():
        worker = threading.Thread(target=spin)
        worker.start()
        done.wait()
        worker.join()
    assert budget.spent < 0.1  # the other thread's 0.3 s is not this panel's


def test_share_must_be_a_fraction_of_a_core() -> None:
    with pytest.raises(ValueError):
        FrameBudget(0)
    with pytest.raises(ValueError):
        FrameBudget(1.5)


def test_what_no_panel_accounts_for_is_shared_by_the_panels_drawing() -> None:
    """Composing and writing the screen is nobody's frame: one panel alone pays all of it (the viewer as a whole
    stays within the share, as when the process's CPU was charged), two drawing panels half each, an idle
    panel none; each panel's own frames stay its own."""
    clocks = Clocks()
    process = [0.0]
    shared = SharedCost(cpu=lambda: process[0])
    camera, heavy, idle = (FrameBudget(0.45, wall=lambda: clocks.wall, cpu=lambda: clocks.cpu, shared=shared)
                           for _ in range(3))

    def frame(budget: FrameBudget, own: float, screen: float) -> None:
        with budget.spending():
            clocks.cpu += own
            process[0] += own
        process[0] += screen  # Textual composing and writing afterwards: charged to no panel by itself

    clocks.wall = 1.0
    frame(camera, 0.002, 0.010)
    assert camera.balance() == pytest.approx(0.45 * 0.5 - 0.012)  # alone: the whole viewer's cost
    clocks.wall = 1.1
    frame(camera, 0.002, 0.010)
    frame(heavy, 0.300, 0.010)
    before = {id(b): b.balance() for b in (camera, heavy, idle)}
    clocks.wall = 1.2
    frame(heavy, 0.300, 0.020)
    camera.balance()
    earned = 0.1 * 0.45
    assert heavy.balance() == pytest.approx(min(before[id(heavy)] + earned, 0.225) - 0.300 - 0.010)
    assert camera.balance() == pytest.approx(min(before[id(camera)] + earned, 0.225) - 0.010)
    assert idle.balance() == pytest.approx(min(before[id(idle)] + earned, 0.225))
