"""The adaptive busy-poll: dense traffic keeps the loop turning for one window, sparse traffic never does."""

from __future__ import annotations

import asyncio

import pytest

from rostui.core.node.busypoll import BusyPoll, IdleGauge, busy_poll_for, window_from_env


class FakeClock:
    """A clock the test moves by hand (seconds)."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


async def turns(loop_spins: BusyPoll, clock: FakeClock, step: float, limit: int = 1000) -> int:
    """Let the loop run, moving the clock by ``step`` per turn; how many turns the spin lasted."""
    n = 0
    while loop_spins.spinning and n < limit:
        clock.now += step
        await asyncio.sleep(0)
        n += 1
    return n


def test_sparse_traffic_never_spins() -> None:
    async def main() -> None:
        clock = FakeClock()
        poll = BusyPoll(asyncio.get_running_loop(), 250e-6, clock)
        for _ in range(5):
            poll.traffic()
            assert not poll.spinning
            clock.now += 1e-3  # a 1 kHz stream: gaps longer than the window
    asyncio.run(main())


def test_dense_traffic_spins_for_one_window_then_sleeps() -> None:
    async def main() -> None:
        clock = FakeClock()
        poll = BusyPoll(asyncio.get_running_loop(), 250e-6, clock)
        poll.traffic()
        clock.now += 50e-6
        poll.traffic()
        assert poll.spinning
        # 10 µs per turn: the spin ends once 250 µs have passed since the last arrival.
        n = await turns(poll, clock, 10e-6)
        assert not poll.spinning
        assert 20 <= n <= 30
    asyncio.run(main())


def test_each_turn_of_the_spin_gives_the_cpu_away_first() -> None:
    async def main() -> None:
        clock = FakeClock()
        given: list[float] = []
        poll = BusyPoll(asyncio.get_running_loop(), 250e-6, clock, give_way=lambda: given.append(clock.now))
        poll.traffic()
        clock.now += 50e-6
        poll.traffic()
        assert given == []  # nothing is given away before the spin's first turn
        n = await turns(poll, clock, 10e-6)
        assert not poll.spinning
        assert len(given) == n  # one for each turn the spin lasted, the turn that ended it included
        assert given == sorted(set(given))  # once a turn
    asyncio.run(main())


def test_a_spinning_node_yields_by_default() -> None:
    import os

    async def main() -> None:
        poll = BusyPoll(asyncio.get_running_loop(), 250e-6)
        assert poll._give_way is os.sched_yield
    asyncio.run(main())


def test_each_dense_arrival_extends_the_spin() -> None:
    async def main() -> None:
        clock = FakeClock()
        poll = BusyPoll(asyncio.get_running_loop(), 250e-6, clock)
        poll.traffic()
        for _ in range(10):
            clock.now += 100e-6
            poll.traffic()
            await asyncio.sleep(0)
            assert poll.spinning
        n = await turns(poll, clock, 10e-6)
        assert 20 <= n <= 30
    asyncio.run(main())


@pytest.mark.parametrize("text,seconds", [(None, 250e-6), ("", 250e-6), ("0", 0.0), ("100", 100e-6),
                                          ("-5", 0.0), ("fast", 0.0)])
def test_window_from_env(monkeypatch: pytest.MonkeyPatch, text: str | None, seconds: float) -> None:
    if text is None:
        monkeypatch.delenv("ROSTUI_BUSY_POLL_US", raising=False)
    else:
        monkeypatch.setenv("ROSTUI_BUSY_POLL_US", text)
    assert window_from_env() == pytest.approx(seconds)


def test_zero_window_means_no_busy_poll() -> None:
    loop = asyncio.new_event_loop()
    try:
        assert busy_poll_for(loop, 0.0) is None
        assert isinstance(busy_poll_for(loop, 1e-4), BusyPoll)
    finally:
        loop.close()


def write_loadavg(path, running: int) -> None:
    """A /proc/loadavg saying ``running`` threads are runnable now (the reader among them)."""
    path.write_text(f"0.50 0.40 0.30 {running}/321 4242\n")


def calm(tmp_path):
    """A /proc/loadavg of a machine where only the reader runs."""
    path = tmp_path / "loadavg"
    write_loadavg(path, 1)
    return str(path)


def write_stat(path, idle_ticks: int) -> None:
    """A /proc/stat whose first line has ``idle_ticks`` idle and 0 iowait ticks."""
    path.write_text(f"cpu  500 0 100 {idle_ticks} 0 0 0 0 0 0\ncpu0 1 2 3 4 5 6 7 8 9 10\n")


def test_idle_gauge_says_no_when_no_cpu_is_spare(tmp_path) -> None:
    stat = tmp_path / "stat"
    clock, own = FakeClock(), [0.0]
    write_stat(stat, 1000)
    gauge = IdleGauge(period=0.5, path=str(stat), own_cpu=lambda: own[0], clock=clock, loadavg_path=calm(tmp_path))
    write_stat(stat, 100_000)
    assert not gauge.spare()  # no whole period seen yet: no spin, whatever the machine does
    write_stat(stat, 1000)
    clock.now += 1.0
    write_stat(stat, 1000 + 30)  # 0.3 s idle in 1 s, ticks of 1/100 s
    own[0] += 0.2
    assert not gauge.spare()
    clock.now += 1.0
    write_stat(stat, 1030 + 90)  # 0.9 s idle + 0.2 s own use: more than one CPU spare
    own[0] += 0.2
    assert gauge.spare()


def test_idle_gauge_resamples_only_once_per_period(tmp_path) -> None:
    stat = tmp_path / "stat"
    clock = FakeClock()
    write_stat(stat, 0)
    gauge = IdleGauge(period=0.5, path=str(stat), own_cpu=lambda: 0.0, clock=clock, loadavg_path=calm(tmp_path))
    clock.now += 1.0
    write_stat(stat, 10)
    assert not gauge.spare()
    write_stat(stat, 10_000)
    clock.now += 0.1
    assert not gauge.spare()  # still the old sample
    clock.now += 0.5
    assert gauge.spare()


def test_a_crowded_machine_gets_no_spin_even_where_the_spin_itself_looks_like_a_spare_cpu(tmp_path) -> None:
    """A busy loop on each of two cores, and ping and pong spinning: the machine shows no idle time, but each
    process's own spin counts as spare; only the count of runnable threads tells the cores are taken."""
    stat, loadavg = tmp_path / "stat", tmp_path / "loadavg"
    clock = FakeClock()
    write_stat(stat, 0)
    write_loadavg(loadavg, 4)  # two busy loops, the other side's spin and this reader
    gauge = IdleGauge(period=0.5, path=str(stat), own_cpu=lambda: clock.now, clock=clock,
                      loadavg_path=str(loadavg), cpus=2)
    for _ in range(300):  # 1.5 s of dense traffic asking; only one count per CROWD_STEP is read
        clock.now += 0.005
        gauge.spare()
    assert not gauge.spare(), "no idle time but a whole CPU of our own: spare by idle time alone"
    write_loadavg(loadavg, 2)  # the busy loops gone: the other side's spin and this reader
    for _ in range(250):  # a whole period of calm counts after the mixed one
        clock.now += 0.005
        gauge.spare()
    assert gauge.spare()


def test_runnable_threads_are_counted_at_most_every_crowd_step(tmp_path) -> None:
    stat, loadavg = tmp_path / "stat", tmp_path / "loadavg"
    clock = FakeClock()
    write_stat(stat, 0)
    write_loadavg(loadavg, 1)
    gauge = IdleGauge(period=0.5, path=str(stat), own_cpu=lambda: clock.now, clock=clock,
                      loadavg_path=str(loadavg), cpus=2)
    clock.now += 0.004
    gauge.spare()  # one calm count, at the start
    write_loadavg(loadavg, 9)
    for _ in range(100):  # 100 asks within the same step: none is counted
        clock.now += 0.00001
        gauge.spare()
    write_loadavg(loadavg, 1)
    clock.now += 0.6
    assert gauge.spare(), "two calm counts decide the period: the crowded asks between them were not counted"


def test_an_unreadable_loadavg_leaves_the_idle_time_to_decide(tmp_path) -> None:
    stat = tmp_path / "stat"
    clock = FakeClock()
    write_stat(stat, 0)
    gauge = IdleGauge(period=0.5, path=str(stat), own_cpu=lambda: 0.0, clock=clock,
                      loadavg_path=str(tmp_path / "missing"))
    clock.now += 1.0
    write_stat(stat, 150)
    assert gauge.spare()


def test_unreadable_stat_always_allows(tmp_path) -> None:
    gauge = IdleGauge(path=str(tmp_path / "missing"))
    assert gauge.spare()


def test_busy_machine_stops_dense_traffic_from_spinning(tmp_path) -> None:
    async def main() -> None:
        stat = tmp_path / "stat"
        clock = FakeClock()
        write_stat(stat, 0)
        gauge = IdleGauge(period=0.5, path=str(stat), own_cpu=lambda: 0.0, clock=clock, loadavg_path=calm(tmp_path))
        clock.now += 1.0
        write_stat(stat, 5)  # 0.05 CPU idle
        poll = BusyPoll(asyncio.get_running_loop(), 250e-6, clock, gauge)
        poll.traffic()
        clock.now += 50e-6
        poll.traffic()
        assert not poll.spinning
    asyncio.run(main())

