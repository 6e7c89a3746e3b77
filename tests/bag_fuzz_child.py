"""Runs every mutant of a fuzz manifest through the functions rostui's bag commands call, in this one process.

``python bag_fuzz_child.py MANIFEST AS_LIMIT`` reads a JSON list of ``{"path", "echo_count"}`` and, for each
file, drives four readers as their commands do: ``bag info`` (``run_info``), ``bag play`` (the bags opened as
``play`` opens them, then every message in the order it would publish them), ``topic echo -b -a`` (``echo_bag``)
and bag view's reader (its pre-check, ``load_index``, every message through its ``IndexSource``, and the
inspector's text of each topic's first message).  The address space is limited to AS_LIMIT bytes, so a runaway
allocation fails here instead of swapping the machine.

For each file and reader one JSON line goes to stdout: ``outcome`` is ``ok``, ``refused`` (the one line the
command would print, in ``line``) or ``crash`` (anything else: the traceback, in ``line``); ``cpu`` is the CPU
seconds it took.  Before each run its name is written to stderr, so a hang names its mutant.  The last line
gives the process's peak resident memory (/proc's ``VmHWM``: ``ru_maxrss`` would count the parent's too).
"""

from __future__ import annotations

import contextlib
import io
import json
import resource
import sys
import time
import traceback
from typing import Callable


def _said(err: str) -> str:
    """The command's own error lines in what it wrote to stderr (warnings, such as an MCAP schema's missing
    md5sum, are not refusals)."""
    return "".join(f"{line}\n" for line in err.splitlines() if line.startswith("rostui bag"))


def _info(path: str, _count: int) -> str:
    from rostui.cli.bag_cmd import run_info

    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = run_info([path], as_json=False)
    return _said(err.getvalue()) or err.getvalue() if code else ""


def _play(path: str, _count: int) -> str:
    from rostui.core.bag.files import merged_messages
    from rostui.core.bag.model import BagError
    from rostui.tools.bag.player import open_bags

    warnings: list[str] = []
    try:
        readers, _summaries = open_bags([path], warnings.append)
    except BagError as exc:
        return f"rostui bag play: {exc}\n"
    try:
        for _item in merged_messages(readers):
            pass
    except BagError as exc:
        return f"rostui bag play: {exc}\n"
    finally:
        for reader in readers:
            reader.close()
    return ""


def _echo(path: str, count: int) -> str:
    from rostui.tools.topic.bag_echo import echo_bag
    from rostui.tools.topic.common import TopicToolError
    from rostui.tools.topic.echo import EchoFormatter

    formatter = EchoFormatter("", from_bag=True, count=count or None)
    try:
        echo_bag(path, None, formatter, lambda _text: None)
    except TopicToolError as exc:
        return f"ERROR: {exc}\n"
    return ""


def _view(path: str, _count: int) -> str:
    from rostui.cli.bag_view_cmd import _check_bags
    from rostui.core.bag.index import IndexSource, load_index, message_yaml
    from rostui.core.bag.model import BagError

    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err):
            _check_bags([path])
    except SystemExit:
        return _said(err.getvalue()) or err.getvalue()
    try:
        index = load_index([path])
    except BagError as exc:
        return f"rostui bag view: {exc}\n"
    problems: list[str] = []
    try:
        source = IndexSource(index)
        while source.peek() is not None:
            source.advance()
        if source.problem:
            problems.append(source.problem)
        for topic in index.topics:
            index.density(topic, 80)
            position = index.message_at(topic, index.start_ns)
            if position is None:
                continue
            conn, _t, data = index.item(position)
            try:
                message_yaml(conn, data)
            except BagError:
                pass  # the inspector shows this line in place of the message
    except BagError as exc:
        problems.append(str(exc))
    finally:
        index.close()
    return f"{problems[-1]}\n" if problems else ""


READERS: dict[str, Callable[[str, int], str]] = {"info": _info, "play": _play, "echo": _echo, "view": _view}


def peak_rss_mb() -> float:
    """This process's peak resident memory in MB: /proc's VmHWM, which starts afresh at exec (ru_maxrss
    carries over the memory of the process that started this one)."""
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) for line in status if line.startswith("VmHWM:")) / 1024


def main() -> None:
    manifest, limit = sys.argv[1], int(sys.argv[2])
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    import rostui.core.bag.files  # noqa: F401  (imports before the first mutant, so its CPU is not counted)
    import rostui.core.msg  # noqa: F401

    with open(manifest) as f:
        items = json.load(f)
    for item in items:
        for victim, run in READERS.items():
            print(f"{victim} {item['path']}", file=sys.stderr, flush=True)
            start = time.process_time()
            try:
                said = run(item["path"], item.get("echo_count", 0))
                outcome = "refused" if said else "ok"
            except BaseException:  # every other way out is the finding
                said, outcome = traceback.format_exc(), "crash"
            print(json.dumps({"path": item["path"], "victim": victim, "outcome": outcome, "line": said,
                              "cpu": round(time.process_time() - start, 4)}), flush=True)
    print(json.dumps({"peak_rss_mb": round(peak_rss_mb(), 1)}), flush=True)


if __name__ == "__main__":
    main()
