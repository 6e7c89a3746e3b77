#!/usr/bin/env python3
"""`rostui graph` on big graphs: layout time, per-keystroke filter time, search time.

Two synthetic graphs of 1000 nodes and 2000 topics (no master needed; the
app's pipeline is the same for live data):

- ``pipeline``: 20 robots (namespaces), each a chain of stages (drivers ->
  perception -> planning -> control) where stage k publishes what stage k+1
  subscribes to, plus diagnostics nobody reads, a few feedback loops and
  topics shared between robots, as real systems have;
- ``random``: every topic has a random publisher and 0-3 random subscribers
  in the same robot: a stress case with long cycles and many crossings.

For each graph and each view it measures, as the median of ``--repeat`` runs:
``view`` (build_view: view + filters, what runs on every keystroke),
``layout`` (layered_layout) and ``draw`` (canvas index + the first 60 rows),
then the per-keystroke cost of typing an include and an exclude regex, a
fuzzy search and each toggle, and a live refresh after one node appears
(layout seeded with the previous layout's hint).  Targets: layout + draw
under 1 s, every keystroke under 50 ms.

Peers, measured in the same run when installed: Graphviz ``dot`` (the
layout engine rqt_graph uses) on the same DOT text, and grandalf's
SugiyamaLayout (in a subprocess with a time limit).

    .venv/bin/python bench/bench_graph.py [--repeat 5] [--peer-timeout 120] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Callable

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from rostui.apps.graph.app import lay_out  # noqa: E402
from rostui.apps.graph.canvas import draw, layout_view  # noqa: E402
from rostui.models.graph.dot import to_dot  # noqa: E402
from rostui.models.graph.model import RosGraph  # noqa: E402
from rostui.models.graph.search import fuzzy_rank  # noqa: E402
from rostui.models.graph.view import FilterError, GraphOptions, ViewMode, build_view  # noqa: E402

NODES, TOPICS, ROBOTS = 1000, 2000, 20
STAGES = ("driver", "perception", "planning", "control")


def pipeline_graph(seed: int = 1) -> RosGraph:
    """1000 nodes, 2000 topics: per robot a four-stage pipeline with diagnostics, feedback and shared topics."""
    rng = random.Random(seed)
    pubs: dict[str, list[str]] = {}
    subs: dict[str, list[str]] = {}
    per_robot = NODES // ROBOTS
    topics_per_robot = TOPICS // ROBOTS
    for r in range(ROBOTS):
        ns = f"/robot{r}"
        nodes = [f"{ns}/{STAGES[i * len(STAGES) // per_robot]}_{i}" for i in range(per_robot)]
        stage_of = {n: i * len(STAGES) // per_robot for i, n in enumerate(nodes)}
        by_stage = [[n for n in nodes if stage_of[n] == s] for s in range(len(STAGES))]
        for t in range(topics_per_robot):
            topic = f"{ns}/topic_{t}"
            publisher = rng.choice(nodes)
            pubs[topic] = [publisher]
            stage = stage_of[publisher]
            kind = rng.random()
            if kind < 0.25:  # diagnostics and debug outputs: nobody subscribes
                subs[topic] = []
            elif kind < 0.30 and stage > 0:  # feedback to an earlier stage
                subs[topic] = [rng.choice(by_stage[stage - 1])]
            elif stage + 1 < len(STAGES):
                subs[topic] = rng.sample(by_stage[stage + 1], rng.randint(1, 3))
            else:  # the last stage's commands go out to the drivers of the same robot
                subs[topic] = [rng.choice(by_stage[0])]
        shared = f"/shared/map_{r}"
        pubs[shared] = [f"{ns}/planning_{per_robot // 2}"]
        subs[shared] = [f"/robot{(r + 1) % ROBOTS}/planning_{per_robot // 2 + 1}"]
    return RosGraph.build(pubs, subs)


def random_graph(seed: int = 1) -> RosGraph:
    """1000 nodes, 2000 topics: random publisher and 0-3 random subscribers within one robot's nodes."""
    rng = random.Random(seed)
    nodes = [f"/robot{i % ROBOTS}/node_{i}" for i in range(NODES)]
    by_robot = [[n for k, n in enumerate(nodes) if k % ROBOTS == r] for r in range(ROBOTS)]
    pubs: dict[str, list[str]] = {}
    subs: dict[str, list[str]] = {}
    for i in range(TOPICS):
        local = by_robot[i % ROBOTS]
        topic = f"/robot{i % ROBOTS}/topic_{i}"
        pubs[topic] = [rng.choice(local)]
        subs[topic] = [rng.choice(local) for _ in range(rng.randint(0, 3))]
    return RosGraph.build(pubs, subs)


#: Columns the app's drawing has in an 80-column terminal (edge labels are chosen to fit them).
APP_WIDTH = 79

#: CPU milliseconds of the last :func:`median_ms` (median over its runs).
LAST_CPU_MS = [0.0]


def median_ms(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """Median wall time of ``fn`` in ms over ``repeat`` calls, and its last result (CPU time in LAST_CPU_MS)."""
    times, cpu = [], []
    result = None
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        result = fn()
        times.append((time.perf_counter() - start) * 1000.0)
        cpu.append((time.process_time() - start_cpu) * 1000.0)
    LAST_CPU_MS[0] = statistics.median(cpu)
    return statistics.median(times), result


def keystrokes(graph: RosGraph, base: GraphOptions, field: str, text: str) -> list[float]:
    """ms of build_view after each character of ``text`` typed into ``field`` (bad partial patterns too)."""
    out, cpu = [], []
    for i in range(1, len(text) + 1):
        options = base.with_(**{field: text[:i]})
        start, start_cpu = time.perf_counter(), time.process_time()
        try:
            build_view(graph, options)
        except FilterError:  # half-typed pattern: the app shows the error and keeps the last view
            pass
        out.append((time.perf_counter() - start) * 1000.0)
        cpu.append((time.process_time() - start_cpu) * 1000.0)
    LAST_CPU_MS[0] = max(cpu)
    return out


def measure_graph(name: str, graph: RosGraph, repeat: int) -> dict[str, Any]:
    """Every measurement for one graph."""
    result: dict[str, Any] = {"graph": name, "nodes": len(graph.nodes()), "topics": len(graph.topics()), "views": {}}
    for mode in ViewMode:
        options = GraphOptions(view=mode)
        view_ms, view = median_ms(lambda: build_view(graph, options), repeat)
        view_cpu = LAST_CPU_MS[0]
        # what the app does: Nodes only gets topic labels on its edges, the widest that fit 80 columns
        layout_ms, (layout, laid) = median_ms(
            lambda: lay_out(view, None, APP_WIDTH, labelled=options.view is ViewMode.NODES), repeat)
        layout_cpu = LAST_CPU_MS[0]

        def first_screen() -> Any:
            canvas = draw(view, layout, laid.labels)
            for y in range(min(60, canvas.height)):
                canvas.row(y)
            return canvas

        draw_ms, _ = median_ms(first_screen, repeat)
        draw_cpu = LAST_CPU_MS[0]
        result["views"][mode.value] = {
            "vertices": len(view.vertices), "edges": len(view.edges), "view_ms": view_ms, "layout_ms": layout_ms,
            "draw_ms": draw_ms, "total_ms": view_ms + layout_ms + draw_ms, "crossings": layout.crossings,
            "total_cpu_ms": view_cpu + layout_cpu + draw_cpu,
            "width": layout.width, "height": layout.height,
        }
    base = GraphOptions(view=ViewMode.ALL)
    typing = {}
    typing_cpu = {}
    for field, text in (("include", "robot1/perception"), ("exclude", "topic_1[0-9]|diag")):
        key = f"{field} {text!r}"
        typing[key] = keystrokes(graph, base, field, text)
        typing_cpu[key] = LAST_CPU_MS[0]
    toggles = {}
    for flag in ("hide_debug", "hide_dead_sinks", "hide_leaf_topics", "group_namespaces"):
        toggles[flag] = median_ms(lambda flag=flag: build_view(graph, base.with_(**{flag: not getattr(base, flag)})),
                                  repeat)[0]
    names = [*graph.nodes(), *graph.topics()]
    search = [median_ms(lambda q=q: fuzzy_rank(q, names, limit=1), repeat)[0]
              for q in ("r", "ro", "rob", "robot1", "robot1/pl", "robot1/plan")]
    view = build_view(graph, base)
    before = layout_view(view)
    grown_subs = {t: list(n) for t, n in graph.subscribers.items()}
    first_topic = graph.topics()[0]
    grown_subs[first_topic] = [*grown_subs.get(first_topic, []), "/robot0/new_listener"]
    grown = build_view(RosGraph.build(dict(graph.publishers), grown_subs), base)
    refresh_ms, _ = median_ms(lambda: layout_view(grown, before.hint()), repeat)
    result.update({
        "keystroke_ms": {k: {"max": max(v), "median": statistics.median(v), "max_cpu": typing_cpu[k]}
                         for k, v in typing.items()},
        "toggle_ms": toggles, "search_ms_max": max(search), "refresh_with_hint_ms": refresh_ms,
    })
    return result


def graphviz_ms(graph: RosGraph, timeout: float) -> dict[str, Any]:
    """Graphviz dot (rqt_graph's layout engine) on the same views; seconds, or why not."""
    dot = shutil.which("dot")
    if dot is None:
        return {"skipped": "Graphviz dot not installed (apt-get install graphviz)"}
    out: dict[str, Any] = {}
    for mode in ViewMode:
        text = to_dot(build_view(graph, GraphOptions(view=mode)))
        start = time.perf_counter()
        try:
            subprocess.run([dot, "-Tplain"], input=text, capture_output=True, text=True, timeout=timeout,
                           check=True)
            out[mode.value] = (time.perf_counter() - start) * 1000.0
        except subprocess.TimeoutExpired:
            out[mode.value] = f"did not finish in {timeout:g} s"
    return out


GRANDALF_SCRIPT = """
import json, sys, time
from grandalf.graphs import Edge, Graph, Vertex
from grandalf.layouts import SugiyamaLayout
data = json.load(open(sys.argv[1]))
vs = {v: Vertex(v) for v in data["vertices"]}
class View: w, h = 20, 3
for v in vs.values(): v.view = View()
start = time.perf_counter()
g = Graph(list(vs.values()), [Edge(vs[a], vs[b]) for a, b in data["edges"]])
for component in g.C:
    layout = SugiyamaLayout(component)
    layout.init_all()
    layout.draw(1)
print((time.perf_counter() - start) * 1000.0)
"""


def grandalf_ms(graph: RosGraph, python: str, timeout: float) -> dict[str, Any]:
    """grandalf's SugiyamaLayout on the Nodes/Topics (all) view, in a subprocess with a time limit."""
    check = subprocess.run([python, "-c", "import grandalf"], capture_output=True)
    if check.returncode != 0:
        return {"skipped": f"grandalf not importable by {python} (pip install grandalf, or --grandalf-python)"}
    view = build_view(graph, GraphOptions(view=ViewMode.ALL))
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump({"vertices": list(view.vertices), "edges": list(view.edges)}, f)
    try:
        done = subprocess.run([python, "-c", GRANDALF_SCRIPT, f.name], capture_output=True, text=True,
                              timeout=timeout)
        return {"all": float(done.stdout.strip())} if done.returncode == 0 else {"error": done.stderr[-300:]}
    except subprocess.TimeoutExpired:
        return {"all": f"did not finish in {timeout:g} s"}
    finally:
        Path(f.name).unlink()


def report(results: list[dict[str, Any]]) -> None:
    """Print the tables and the verdicts."""
    for r in results:
        print(f"\n== {r['graph']}: {r['nodes']} nodes, {r['topics']} topics")
        print(f"{'view':8} {'vertices':>8} {'edges':>6} {'view ms':>8} {'layout ms':>9} {'draw ms':>8} "
              f"{'total ms':>9} {'(cpu ms)':>9} {'crossings':>9}  grid")
        for mode, v in r["views"].items():
            print(f"{mode:8} {v['vertices']:8d} {v['edges']:6d} {v['view_ms']:8.1f} {v['layout_ms']:9.1f} "
                  f"{v['draw_ms']:8.1f} {v['total_ms']:9.1f} {v['total_cpu_ms']:9.1f} {v['crossings']:9d}  "
                  f"{v['width']}x{v['height']}")
        for what, k in r["keystroke_ms"].items():
            print(f"typing {what}: max {k['max']:.1f} ms (CPU {k['max_cpu']:.1f} ms), "
                  f"median {k['median']:.1f} ms per keystroke")
        print("toggles: " + ", ".join(f"{k} {v:.1f} ms" for k, v in r["toggle_ms"].items()))
        print(f"fuzzy search over {r['nodes'] + r['topics']} names: max {r['search_ms_max']:.1f} ms per keystroke")
        print(f"live refresh (one node more, seeded layout): {r['refresh_with_hint_ms']:.1f} ms")
        worst_total = max(v["total_ms"] for v in r["views"].values())
        worst_cpu = max(v["total_cpu_ms"] for v in r["views"].values())
        worst_key = max([k["max"] for k in r["keystroke_ms"].values()] + list(r["toggle_ms"].values())
                        + [r["search_ms_max"]])
        print(f"target layout+draw < 1000 ms: {'OK' if worst_total < 1000 else 'MISSED'} ({worst_total:.0f} ms wall, "
              f"{worst_cpu:.0f} ms CPU); "
              f"keystroke < 50 ms: {'OK' if worst_key < 50 else 'MISSED'} ({worst_key:.1f} ms)")
        for peer in ("graphviz", "grandalf"):
            if peer in r:
                print(f"{peer}: {r[peer]}")
                ours = r["views"]["all"]["layout_ms"]
                theirs = r[peer].get("all")
                if isinstance(theirs, float):
                    print(f"  ratio {peer}/rostui on Nodes/Topics (all): {theirs / ours:.1f}x")


def main() -> int:
    """Run the benchmark."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per measurement (median is reported)")
    parser.add_argument("--peer-timeout", type=float, default=120.0, help="seconds a peer may take per layout")
    parser.add_argument("--grandalf-python", default=sys.executable, help="a Python that can import grandalf")
    parser.add_argument("--no-peers", action="store_true", help="skip Graphviz and grandalf")
    parser.add_argument("--json", help="write the results to this file")
    args = parser.parse_args()
    results = []
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())} on {os.cpu_count()} CPUs "
          "(wall times grow with load; CPU times do not)")
    for name, graph in (("pipeline", pipeline_graph()), ("random", random_graph())):
        r = measure_graph(name, graph, args.repeat)
        if not args.no_peers:
            r["graphviz"] = graphviz_ms(graph, args.peer_timeout)
            r["grandalf"] = grandalf_ms(graph, args.grandalf_python, args.peer_timeout)
        results.append(r)
    report(results)
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
