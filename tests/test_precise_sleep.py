"""The bag transport's sleep: one sleep to the moment, no spin (the spin cost a player 45 µs of CPU a message)."""

from __future__ import annotations

from rostui.core.bag.precise_sleep import lower_timer_slack, sleep_until


class FakeTime:
    """A clock whose sleeps wake ``late`` seconds after they were asked to end; each reading moves it by ``tick``."""

    def __init__(self, late: float, tick: float = 1e-7) -> None:
        self.now = 100.0
        self.late = late
        self.tick = tick
        self.reads = 0
        self.slept: list[float] = []

    def clock(self) -> float:
        self.reads += 1
        self.now += self.tick
        return self.now

    def sleep(self, seconds: float) -> None:
        self.slept.append(seconds)
        self.now += seconds + self.late


def test_it_sleeps_once_to_the_moment_and_reads_the_clock_once() -> None:
    fake = FakeTime(late=60e-6)
    moment = fake.now + 0.0025
    sleep_until(moment, fake.clock, fake.sleep)
    assert len(fake.slept) == 1 and abs(fake.slept[0] - 0.0025) < 1e-6
    assert fake.reads == 1  # no spin: a spinning wait reads the clock thousands of times
    assert fake.now >= moment


def test_a_moment_already_passed_returns_without_sleeping() -> None:
    fake = FakeTime(late=0.0)
    sleep_until(fake.now - 1.0, fake.clock, fake.sleep)
    assert fake.slept == []


def test_the_timer_slack_can_be_lowered_here() -> None:
    assert lower_timer_slack() is True
