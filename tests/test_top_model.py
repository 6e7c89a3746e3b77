"""`rostui top`'s rows without a master: order, units, the --once table, and which processes it will not signal."""

from __future__ import annotations

import asyncio
import os

import pytest

from rostui.models.top import NodeRow, StopRefused, TopSource, format_bytes, format_rows, sort_rows
from rostui.tools.usage import ProcessSample

ROWS = [
    NodeRow("/b", "http://here:1/", "here", True, 10, ProcessSample(5.0, 300 * 2 ** 20, 4, 2, "b")),
    NodeRow("/a", "http://here:2/", "here", True, 11, ProcessSample(50.0, 20 * 2 ** 20, 9, 1, "a")),
    NodeRow("/c", "http://far:3/", "far", False, 12, None),
    NodeRow("/d", "http://here:4/", "here", True, None, None, "no answer to getPid (TimeoutError)"),
]


def test_orders() -> None:
    assert [row.name for row in sort_rows(ROWS, "cpu")] == ["/a", "/b", "/c", "/d"]
    assert [row.name for row in sort_rows(ROWS, "memory")] == ["/b", "/a", "/c", "/d"]
    assert [row.name for row in sort_rows(ROWS, "name")] == ["/a", "/b", "/c", "/d"]


def test_units_and_the_table() -> None:
    assert [format_bytes(n) for n in (812 * 1024, 25_300_000, 3 * 2 ** 30)] == ["812K", "24.1M", "3.0G"]
    assert format_rows(sort_rows(ROWS, "name")).splitlines() == [
        "NODE  PID  CPU%     MEM  THREADS  CONNS  WHERE",
        "/a     11  50.0   20.0M        9      1  here",
        "/b     10   5.0  300.0M        4      2  here",
        "/c     12     -       -        -      -  remote (far)",
        "/d      -     -       -        -      -  here: no answer to getPid (TimeoutError)",
    ]


@pytest.mark.parametrize("which", ["remote", "no pid", "this process", "init"])
def test_what_is_never_signalled(which: str) -> None:
    row, why = {
        "remote": (ROWS[2], "/c does not run on this host: stop it where it runs"),
        "no pid": (ROWS[3], "/d does not run on this host: stop it where it runs"),
        "this process": (NodeRow("/me", "http://here:5/", "here", True, os.getpid(), None),
                         f"/me is pid {os.getpid()}: not stopped from here"),
        "init": (NodeRow("/init", "http://here:6/", "here", True, 1, None), "/init is pid 1: not stopped from here"),
    }[which]

    async def main() -> None:
        source = TopSource("http://127.0.0.1:9/")
        with pytest.raises(StopRefused) as raised:
            await source.stop(row)
        assert str(raised.value) == why
    asyncio.run(main())
