"""The bag transport's sleeper: it learns how late its sleeps wake and spins only what is left."""

from __future__ import annotations

from rostui.core.bag.precise_sleep import MAX_EARLY, PreciseSleeper, lower_timer_slack


class FakeTime:
    """A clock whose sleeps wake ``late`` seconds after they were asked to end; each reading moves it by ``tick``."""

    def __init__(self, late: float, tick: float = 1e-7) -> None:
        self.now = 100.0
        self.late = late
        self.tick = tick
        self.reads = 0

    def clock(self) -> float:
        self.reads += 1
        self.now += self.tick
        return self.now

    def sleep(self, seconds: float) -> None:
        self.now += seconds + self.late


def spin_reads(fake: FakeTime, sleeper: PreciseSleeper, moment: float) -> int:
    """How many clock readings ``sleep_until(moment)`` makes (the spin is what makes many); checks it returned at
    the moment, not before."""
    before = fake.reads
    sleeper.sleep_until(moment)
    assert fake.now >= moment
    return fake.reads - before


def test_it_returns_at_the_moment_and_learns_to_spin_little() -> None:
    fake = FakeTime(late=60e-6)
    sleeper = PreciseSleeper(fake.clock, fake.sleep)
    assert sleeper.early == MAX_EARLY  # nothing learnt yet: the longest spin
    first = spin_reads(fake, sleeper, fake.now + 0.0025)
    for _ in range(20):
        spin_reads(fake, sleeper, fake.now + 0.0025)
    assert abs(sleeper.early - 60e-6) < 1e-6  # it sleeps until 60 µs before, as its sleeps wake 60 µs late
    later = spin_reads(fake, sleeper, fake.now + 0.0025)
    assert later < first / 10


def test_a_late_wake_up_returns_at_once_and_spins_nothing() -> None:
    fake = FakeTime(late=0.005)  # a busy machine: the sleep wakes well after the moment
    sleeper = PreciseSleeper(fake.clock, fake.sleep)
    moment = fake.now + 0.001
    sleeper.sleep_until(moment)
    assert fake.now > moment
    assert sleeper.early == MAX_EARLY  # a wake-up later than the bound is not chased


def test_a_moment_already_passed_returns_without_sleeping() -> None:
    fake = FakeTime(late=0.0)
    slept: list[float] = []
    sleeper = PreciseSleeper(fake.clock, slept.append)
    sleeper.sleep_until(fake.now - 1.0)
    assert slept == []


def test_the_timer_slack_can_be_lowered_here() -> None:
    assert lower_timer_slack() is True
