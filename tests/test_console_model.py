"""The console's model: bounded ring, filtered rows, pause buffer, counters.

The model is checked against the obvious slow answer (keep everything in a
list, filter with a comprehension) after random sequences of operations.
"""

from __future__ import annotations

import random

import pytest

from rostui.core.log.rosout_read import RosoutEntry
from rostui.models.console.filters import ALL_LEVELS, FilterError, FilterSpec, HighlightRule, compile_filter
from rostui.models.console.model import ConsoleModel

NODES = ["/talker", "/listener", "/ns/cam", "/rosout"]
LEVELS = [1, 2, 2, 2, 4, 8, 16]


def entry(n: int, level: int = 2, node: str = "/talker", message: str | None = None) -> RosoutEntry:
    """A message with stamp n seconds."""
    return RosoutEntry(n * 1_000_000_000, level, node, message if message is not None else f"message {n}",
                       "talker.py", 10, "talk", ("/rosout",))


def random_entries(rng: random.Random, start: int, count: int) -> list[RosoutEntry]:
    """Messages of random level and node; some mention 'Boom'."""
    return [entry(n, rng.choice(LEVELS), rng.choice(NODES), f"{'Boom ' if rng.random() < 0.2 else ''}m{n}")
            for n in range(start, start + count)]


def test_ring_keeps_the_newest_and_counts_the_dropped() -> None:
    """With capacity 5, ten messages leave the last five, numbered 5..9; five dropped."""
    model = ConsoleModel(5)
    model.ingest([entry(n) for n in range(10)])
    assert [seq for seq, _ in model.shown()] == [5, 6, 7, 8, 9]
    assert [e.message for _, e in model.shown()] == [f"message {n}" for n in range(5, 10)]
    assert (len(model), model.kept, model.dropped, model.received) == (5, 5, 5, 10)
    assert model.level_counts[2] == 5
    with pytest.raises(IndexError):
        model.entry(4)


def test_min_level_keeps_nothing_below_it() -> None:
    """Below min_level nothing is kept (a DEBUG flood cannot push out a WARN)."""
    model = ConsoleModel(3, min_level=4)
    model.ingest([entry(0, 4)] + [entry(n, 1) for n in range(1, 100)] + [entry(100, 8)])
    assert [e.level for _, e in model.shown()] == [4, 8]
    assert (model.below_level, model.dropped) == (99, 0)
    model.set_min_level(1)
    model.ingest([entry(101, 1)])
    assert [e.level for _, e in model.shown()] == [4, 8, 1]


def test_a_level_min_level_cannot_rank_is_kept() -> None:
    """Levels outside DEBUG..FATAL (0, 3, 200) are kept whatever min_level says."""
    model = ConsoleModel(10, min_level=8)
    model.ingest([entry(0, 0), entry(1, 3), entry(2, 200), entry(3, 4)])
    assert [e.level for _, e in model.shown()] == [0, 3, 200]
    assert model.below_level == 1


def test_pause_buffers_new_messages_and_resume_shows_them() -> None:
    """Paused: rows frozen, new messages wait (counted); resume shows them in order."""
    model = ConsoleModel(100)
    model.ingest([entry(n) for n in range(3)])
    version = model.version
    model.pause()
    model.ingest([entry(n) for n in range(3, 7)])
    assert (len(model), model.pending, model.version) == (3, 4, version)
    assert model.resume() == 4
    assert [seq for seq, _ in model.shown()] == list(range(7))
    assert (model.pending, model.received) == (0, 7)


def test_pause_buffer_is_bounded_too() -> None:
    """The pause buffer holds at most ``capacity`` messages; overflow counts as dropped."""
    model = ConsoleModel(4)
    model.pause()
    model.ingest([entry(n) for n in range(10)])
    assert (model.pending, model.dropped) == (4, 6)
    model.resume()
    assert [e.message for _, e in model.shown()] == [f"message {n}" for n in range(6, 10)]


def test_clear_forgets_but_numbering_goes_on() -> None:
    """After clear no rows; the next message gets the next number."""
    model = ConsoleModel(4)
    model.ingest([entry(n) for n in range(6)])
    model.clear()
    assert (len(model), model.kept, sum(model.level_counts.values())) == (0, 0, 0)
    model.ingest([entry(6), entry(7)])
    assert [seq for seq, _ in model.shown()] == [6, 7]
    model.ingest([entry(n) for n in range(8, 14)])
    assert [seq for seq, _ in model.shown()] == [10, 11, 12, 13]


def test_filters_match_a_brute_force_answer_after_random_operations() -> None:
    """Random ingest / filter / clear / pause sequences: rows == filter(all kept messages)."""
    rng = random.Random(7)
    specs = [
        FilterSpec(),
        FilterSpec(levels=frozenset({4, 8, 16})),
        FilterSpec(include_nodes=frozenset({"/talker", "/ns/cam"})),
        FilterSpec(exclude_nodes=frozenset({"/rosout"})),
        FilterSpec(search="boom"),
        FilterSpec(search=r"^Boom m\d*7$", regex=True),
        FilterSpec(levels=frozenset({2}), exclude_nodes=frozenset({"/listener"}), search="m1"),
    ]
    model = ConsoleModel(300)
    everything: list[RosoutEntry] = []
    waiting: list[RosoutEntry] = []
    start = 0
    for _ in range(300):
        op = rng.random()
        if op < 0.6:
            batch = random_entries(rng, start, rng.randint(0, 60))
            start += len(batch)
            model.ingest(batch)
            (waiting if model.paused else everything).extend(batch)
        elif op < 0.8:
            model.set_filter(rng.choice(specs))
        elif op < 0.85:
            model.clear()
            everything = everything[:0]
            start_after_clear = model.end
            assert start_after_clear == model.first
        elif op < 0.95:
            if model.paused:
                model.resume()
                everything.extend(waiting[-model.capacity:])
                waiting = []
            else:
                model.pause()
        kept = everything[-model.kept:] if model.kept else []
        match = compile_filter(model.spec) or (lambda e: True)
        assert [e for _, e in model.shown()] == [e for e in kept if match(e)]
        seqs = [seq for seq, _ in model.shown()]
        assert seqs == sorted(seqs) and all(model.first <= s < model.end for s in seqs)
        for row, seq in enumerate(seqs[:5]):
            assert model.row_of(seq) == row and model.seq_at(row) == seq


def test_bad_regex_raises_and_leaves_the_model_as_it_was() -> None:
    """set_filter with an invalid regex raises FilterError; rows and spec stay."""
    model = ConsoleModel(10)
    model.ingest([entry(n) for n in range(4)])
    model.set_filter(FilterSpec(search="message 1"))
    with pytest.raises(FilterError, match=r"bad regular expression '\(unclosed'"):
        model.set_filter(FilterSpec(search="(unclosed", regex=True))
    assert model.spec == FilterSpec(search="message 1")
    assert [e.message for _, e in model.shown()] == ["message 1"]


def test_text_search_ignores_case_and_regex_does_not() -> None:
    """Plain text matches in any case; a regex is used as written."""
    model = ConsoleModel(10)
    model.ingest([entry(0, message="Motor OVERHEAT"), entry(1, message="motor ok")])
    model.set_filter(FilterSpec(search="motor"))
    assert len(model) == 2
    model.set_filter(FilterSpec(search="^Motor", regex=True))
    assert [e.message for _, e in model.shown()] == ["Motor OVERHEAT"]


def test_toggles_and_highlight_rules() -> None:
    """Level and node toggles flip; include and exclude of one node are exclusive; rules match messages."""
    spec = FilterSpec().toggle_level(1).toggle_level(2)
    assert spec.levels == ALL_LEVELS - {1, 2}
    assert spec.toggle_level(1).levels == ALL_LEVELS - {2}
    spec = spec.toggle_include("/a")
    assert spec.include_nodes == {"/a"}
    spec = spec.toggle_exclude("/a")
    assert (spec.include_nodes, spec.exclude_nodes) == (frozenset(), {"/a"})
    assert spec.without_nodes().exclude_nodes == frozenset()
    rule = HighlightRule("over", regex=False)
    assert rule.matches(entry(0, message="Motor OVERHEAT")) and not rule.matches(entry(1, message="fine"))
    with pytest.raises(FilterError):
        HighlightRule("[", regex=True)
