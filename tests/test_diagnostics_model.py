"""The diagnostics store and tree without a master: levels, staleness, history, filters, bounds and both formats."""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import pytest

from rostui.models.diagnostics.detail import detail_lines, summary_text
from rostui.models.diagnostics.levels import ERROR, OK, STALE, WARN, level_name, parse_level
from rostui.models.diagnostics.store import AGGREGATED, FLAT, MAX_HISTORY, DiagnosticsStore, StatusTable
from rostui.models.diagnostics.tree import Filter, counts, flat_rows, format_rosdiagnostic, format_tree, tree_rows


def status(name: str, level: int, message: str = "", hardware_id: str = "", **values: str) -> Any:
    """A DiagnosticStatus-shaped object."""
    return SimpleNamespace(name=name, level=level, message=message, hardware_id=hardware_id,
                           values=[SimpleNamespace(key=k, value=v) for k, v in values.items()])


ROBOT = [
    status("/Sensors", OK, "OK"),
    status("/Sensors/laser", OK, "Scanning", "robot-1", frequency="10.0"),
    status("/Power", ERROR, "Error"),
    status("/Power/battery", ERROR, "Charge low", "robot-1", voltage="10.9"),
    status("/Motors/left/motor", WARN, "Running hot", temperature="71.5"),
]


def robot_store(at: float = 100.0) -> DiagnosticsStore:
    store = DiagnosticsStore()
    store.take(AGGREGATED, ROBOT, at, stamp=at)
    return store


def test_the_aggregators_paths_make_a_tree_with_groups_it_did_not_publish() -> None:
    store = robot_store()
    rows = tree_rows(store.aggregated, 100.5, store.stale_after)
    assert [(row.label, level_name(row.level)) for row in rows] == [
        ("Motors", "WARN"), ("└─ left", "WARN"), ("   └─ motor", "WARN"),
        ("Power", "ERROR"), ("└─ battery", "ERROR"),
        ("Sensors", "OK"), ("└─ laser", "OK")]
    assert rows[0].record is None and rows[1].record is None  # groups made from the paths
    assert counts(rows) == {"WARN": 1, "ERROR": 2, "OK": 2}


def test_a_status_not_heard_for_five_seconds_is_stale_and_its_history_counts_repeats() -> None:
    store = robot_store(100.0)
    store.take(AGGREGATED, [status("/Power/battery", ERROR, "Charge low", voltage="10.8")], 101.0)
    store.take(AGGREGATED, [status("/Power/battery", WARN, "Charging", voltage="11.5")], 102.0)
    rows = tree_rows(store.aggregated, 106.5, store.stale_after)
    levels = {row.name: row.level for row in rows}
    assert levels["/Power/battery"] == WARN and levels["/Sensors/laser"] == STALE
    assert levels["/Power"] == STALE  # its own status is stale, whatever its children say
    record = store.aggregated.get("/Power/battery")
    assert record is not None
    assert [(h.level, h.message, h.times) for h in record.history] == [(ERROR, "Charge low", 2), (WARN, "Charging", 1)]
    battery = next(row for row in rows if row.name == "/Power/battery")
    lines = detail_lines(battery, rows, 106.5)
    assert lines[1] == "WARN · Charging" and "voltage  11.5" in lines[3]
    assert lines[-2:] == [lines[-2], lines[-1]] and "ERROR  Charge low ×2" in lines[-1]
    laser = next(row for row in rows if row.name == "/Sensors/laser")
    assert detail_lines(laser, rows, 106.5)[1].startswith("STALE (it said OK; nothing came for 6.5 s)")


def test_a_filter_keeps_the_groups_above_what_it_shows() -> None:
    store = robot_store()
    rows = tree_rows(store.aggregated, 100.0, store.stale_after, Filter(WARN))
    assert [row.name for row in rows] == ["/Motors", "/Motors/left", "/Motors/left/motor", "/Power", "/Power/battery"]
    rows = tree_rows(store.aggregated, 100.0, store.stale_after, Filter(0, "batt"))
    assert [row.name for row in rows] == ["/Power", "/Power/battery"]
    assert tree_rows(store.aggregated, 100.0, store.stale_after, Filter(0, "Batt")) == []  # a capital: case counts
    assert [row.name for row in tree_rows(store.aggregated, 100.0, store.stale_after, Filter(0, "l[ae]"))] == [
        "/Motors", "/Motors/left", "/Motors/left/motor", "/Sensors", "/Sensors/laser"]  # the full name is searched
    assert tree_rows(store.aggregated, 100.0, store.stale_after, Filter(0, "[")) == []  # half-typed: plain text


def test_the_flat_topic_lists_names_in_order() -> None:
    store = DiagnosticsStore()
    store.take(FLAT, [status("driver: b", WARN, "hot"), status("driver: a", OK, "fine")], 1.0)
    rows = flat_rows(store.flat, 1.0, store.stale_after)
    assert [(row.label, row.message) for row in rows] == [("driver: a", "fine"), ("driver: b", "hot")]
    assert format_tree(rows) == "[OK]   driver: a: fine\n[WARN] driver: b: hot"
    assert summary_text(FLAT, False, counts(rows)) == \
        "/diagnostics flat (no aggregator) · 1 WARN, 1 OK"


def test_the_rosdiagnostic_format_prints_leaves_the_worst_first() -> None:
    store = robot_store(0.0)
    text = format_rosdiagnostic(store.aggregated, Filter(WARN), detail=True)
    lines = text.splitlines()
    assert lines[0] == "=" * 69 and lines[1].startswith("Diagnostics generated on: 1970-01-01 ") and lines[-1] == "=" * 69
    assert [line for line in lines[3:-1] if not line.startswith("    ")] == [
        "[ ERROR ] /Power/battery - Charge low", "[ WARN  ] /Motors/left/motor - Running hot"]
    assert "    hardware_id: robot-1" in lines and "    - voltage: 10.9" in lines
    coloured = format_rosdiagnostic(store.aggregated, Filter(OK), color=True)
    assert "[ \033[92m OK  \033[0m ] /Sensors/laser - Scanning" in coloured


def test_whatever_a_publisher_sends_the_store_stays_bounded() -> None:
    table = StatusTable(limit=100)
    for n in range(1000):
        table.take([status(f"/flood/{n}", n % 4, "x" * 5000, **{f"k{i}": "v" for i in range(300)})], float(n))
    assert len(table) == 100 and table.dropped == 900
    kept = table.get("/flood/999")
    assert kept is not None and len(kept.message) <= 1000 and len(kept.values) == 200
    for n in range(500):
        table.take([status("/flood/999", n % 2, str(n))], 2000.0 + n)
    assert len(table.get("/flood/999").history) == MAX_HISTORY  # type: ignore[union-attr]
    odd = StatusTable()
    odd.take([status("/odd", 200, "a level no version defines")], 0.0)
    rows = tree_rows(odd, 0.0, 5.0, Filter(ERROR))
    assert [(row.name, level_name(row.level)) for row in rows] == [("/odd", "level 200")]


@pytest.mark.parametrize("text, level", [("ok", OK), ("WARN", WARN), ("warning", WARN), ("2", ERROR), ("stale", STALE)])
def test_levels_by_name_or_number(text: str, level: int) -> None:
    assert parse_level(text) == level


def test_an_unknown_level_names_the_choices() -> None:
    with pytest.raises(ValueError, match="choose ok, warn, error or stale"):
        parse_level("bad")
