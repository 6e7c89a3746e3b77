"""A layered left-to-right layout on a character grid (Sugiyama style), fast and stable.

Steps: break cycles (depth-first, reversing back edges), assign layers
(longest path, then sources pulled next to their first successor), add a
dummy vertex per layer an edge skips, order each layer with barycenter sweeps
that keep the ordering with the fewest crossings, place vertices vertically
by isotonic regression towards their neighbours (pool adjacent violators),
then route every edge through the channel between two layers on its own
vertical track (tracks shared by edges whose spans do not overlap).

Everything is deterministic: the same input gives the same layout.  A
:class:`LayoutHint` taken from a previous layout seeds cycle breaking and
layer order, so a small change to the graph moves little else.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, NamedTuple, Sequence

__all__ = ["Box", "Segment", "Arrow", "Layout", "LayoutHint", "layered_layout", "back_edges", "count_crossings"]

#: Rows between two boxes of one layer.
ROW_GAP = 1
#: Vertices (dummies included) above which fewer ordering sweeps are made, to stay well under a second.
BIG_GRAPH = 8000
#: Extra columns of every channel between two layers (lead-in, lead-out and arrow head).
CHANNEL_MARGIN = 3


class Box(NamedTuple):
    """A vertex's rectangle: top-left corner ``(x, y)``, ``w`` columns by ``h`` rows."""

    id: str
    x: int
    y: int
    w: int
    h: int

    @property
    def center_row(self) -> int:
        """The row where edges leave and enter."""
        return self.y + self.h // 2


class Segment(NamedTuple):
    """A horizontal or vertical piece of the edge with index ``edge`` (inclusive ends)."""

    x0: int
    y0: int
    x1: int
    y1: int
    edge: int


class Arrow(NamedTuple):
    """An arrow head at ``(x, y)``; ``left`` when it points left (a reversed edge's real target)."""

    x: int
    y: int
    edge: int
    left: bool = False


@dataclass(frozen=True)
class LayoutHint:
    """Where vertices were last time: layer index and vertical centre (seeds the next layout)."""

    rank: Mapping[str, int] = field(default_factory=dict)
    position: Mapping[str, float] = field(default_factory=dict)


@dataclass
class Layout:
    """Boxes, edge segments and arrow heads on a ``width`` x ``height`` grid.

    ``edges`` lists the input edges (deduplicated, no self loops) in the
    order segment and arrow ``edge`` indices refer to.
    """

    boxes: dict[str, Box]
    segments: list[Segment]
    arrows: list[Arrow]
    edges: list[tuple[str, str]]
    width: int
    height: int
    ranks: dict[str, int]
    crossings: int

    def hint(self) -> LayoutHint:
        """A hint that reproduces this layout's order for a similar graph."""
        return LayoutHint(dict(self.ranks), {k: float(b.y) for k, b in self.boxes.items()})


def layered_layout(sizes: Mapping[str, tuple[int, int]], edges: Sequence[tuple[str, str]],
                   hint: LayoutHint | None = None, *, sweeps: int = 6) -> Layout:
    """Lay out vertices of ``sizes`` (id -> (width, height)) with directed ``edges`` left to right."""
    hint = hint or LayoutHint()
    ids, index, unique = _ordered(sizes, edges, hint)
    n = len(ids)
    pairs = [(index[a], index[b]) for a, b in unique]

    reversed_flags = _break_cycles(n, pairs)
    dag = [(b, a) if rev else (a, b) for (a, b), rev in zip(pairs, reversed_flags)]
    rank = _assign_layers(n, dag)

    # Dummy vertices: one per layer an edge crosses.
    heights = [sizes[v][1] for v in ids]
    widths = [sizes[v][0] for v in ids]
    chains: list[list[int]] = []
    total = n
    for tail, head in dag:
        chain = [tail]
        for r in range(rank[tail] + 1, rank[head]):
            rank.append(r)
            heights.append(1)
            widths.append(0)
            chain.append(total)
            total += 1
        chain.append(head)
        chains.append(chain)
    succ: list[list[int]] = [[] for _ in range(total)]
    pred: list[list[int]] = [[] for _ in range(total)]
    for chain in chains:
        for u, v in zip(chain, chain[1:]):
            succ[u].append(v)
            pred[v].append(u)

    layers_count = (max(rank) + 1) if total else 0
    layers: list[list[int]] = [[] for _ in range(layers_count)]
    for v in _initial_order(total, n, succ, pred, rank, ids, hint):
        layers[rank[v]].append(v)
    if total > BIG_GRAPH:
        sweeps = min(sweeps, 4)
    layers, crossings = _order_layers(layers, succ, pred, sweeps)

    ys = _place_rows(layers, heights, succ, pred)
    return _route(ids, layers, ys, widths, heights, rank, chains, unique, reversed_flags, crossings)


def back_edges(vertices: Sequence[str], edges: Sequence[tuple[str, str]],
               hint: LayoutHint | None = None) -> set[tuple[str, str]]:
    """The edges :func:`layered_layout` would draw backwards to break cycles, for the same vertices and hint."""
    ids, index, unique = _ordered(dict.fromkeys(vertices, (0, 0)), edges, hint or LayoutHint())
    flags = _break_cycles(len(ids), [(index[a], index[b]) for a, b in unique])
    return {edge for edge, flipped in zip(unique, flags) if flipped}


def _ordered(sizes: Mapping[str, tuple[int, int]], edges: Sequence[tuple[str, str]],
             hint: LayoutHint) -> tuple[list[str], dict[str, int], list[tuple[str, str]]]:
    """Vertex ids in the hint's order, their indices, and the edges deduplicated in that order (no loops)."""
    ids = sorted(sizes, key=lambda v: (hint.rank.get(v, 1 << 30), hint.position.get(v, 0.0), v))
    index = {v: i for i, v in enumerate(ids)}
    unique: list[tuple[str, str]] = []
    seen: set[tuple[int, int]] = set()
    for a, b in edges:
        if a == b or a not in index or b not in index:
            continue
        key = (index[a], index[b])
        if key not in seen:
            seen.add(key)
            unique.append((a, b))
    unique.sort(key=lambda e: (index[e[0]], index[e[1]]))
    return ids, index, unique


# ----------------------------------------------------------------------------- cycles and layers
def _break_cycles(n: int, pairs: list[tuple[int, int]]) -> list[bool]:
    """Which edges to reverse so that the graph has no cycle; only edges inside a cycle ever are.

    Within each strongly connected component, vertices are ordered by
    breadth-first distance from where the component is entered (then by
    index) and edges against that order are reversed: data keeps flowing
    left to right from where it enters, and a feedback loop adds one backward
    edge rather than a long chain.
    """
    out: list[list[int]] = [[] for _ in range(n)]
    for a, b in pairs:
        out[a].append(b)
    for targets in out:
        targets.sort()
    comp = _components(n, out)
    indeg = [0] * n
    entered: list[bool] = [False] * n
    for a, b in pairs:
        if comp[a] == comp[b]:
            indeg[b] += 1
        else:
            entered[b] = True
    members: dict[int, list[int]] = {}
    for v in range(n):
        members.setdefault(comp[v], []).append(v)
    dist = [0] * n
    for vs in members.values():
        if len(vs) == 1:
            continue
        for v in vs:
            dist[v] = -1
        roots = [v for v in vs if entered[v]] or [min(vs, key=lambda v: (indeg[v] - len(out[v]), v))]
        queue = list(roots)
        for v in roots:
            dist[v] = 0
        head = 0
        while head < len(queue):
            v = queue[head]
            head += 1
            for w in out[v]:
                if dist[w] < 0 and comp[w] == comp[v]:
                    dist[w] = dist[v] + 1
                    queue.append(w)
    return [comp[a] == comp[b] and (dist[b], b) <= (dist[a], a) for a, b in pairs]


def _components(n: int, out: list[list[int]]) -> list[int]:
    """Strongly connected component number of every vertex (Tarjan's algorithm, without recursion)."""
    index = [-1] * n
    low = [0] * n
    on_stack = [False] * n
    comp = [-1] * n
    stack: list[int] = []
    counter = 0
    count = 0
    for root in range(n):
        if index[root] >= 0:
            continue
        work = [(root, 0)]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack[root] = True
        while work:
            v, i = work[-1]
            if i < len(out[v]):
                work[-1] = (v, i + 1)
                w = out[v][i]
                if index[w] < 0:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack[w] = True
                    work.append((w, 0))
                elif on_stack[w] and index[w] < low[v]:
                    low[v] = index[w]
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                if low[v] < low[parent]:
                    low[parent] = low[v]
            if low[v] == index[v]:
                while True:
                    w = stack.pop()
                    on_stack[w] = False
                    comp[w] = count
                    if w == v:
                        break
                count += 1
    return comp


def _assign_layers(n: int, dag: list[tuple[int, int]]) -> list[int]:
    """Longest path from the sources; each source then moves next to its nearest successor."""
    succ: list[list[int]] = [[] for _ in range(n)]
    indeg = [0] * n
    for a, b in dag:
        succ[a].append(b)
        indeg[b] += 1
    rank = [0] * n
    order = [v for v in range(n) if indeg[v] == 0]
    head = 0
    while head < len(order):
        v = order[head]
        head += 1
        for w in succ[v]:
            if rank[v] + 1 > rank[w]:
                rank[w] = rank[v] + 1
            indeg[w] -= 1
            if indeg[w] == 0:
                order.append(w)
    pred: list[list[int]] = [[] for _ in range(n)]
    for a, b in dag:
        pred[b].append(a)
    _shorten_edges(order, succ, pred, rank)
    low = min(rank, default=0)
    return [r - low for r in rank]


def _shorten_edges(order: list[int], succ: list[list[int]], pred: list[list[int]], rank: list[int],
                   passes: int = 8) -> None:
    """Move vertices between their neighbours' layers to cut the total edge length (fewer dummies).

    Coordinate descent: each vertex goes to the median of its neighbours'
    layers, kept strictly after every predecessor and before every
    successor; a pass that moves nothing ends it.
    """
    for _ in range(passes):
        moved = False
        for v in order:
            ps, ss = pred[v], succ[v]
            if not ps and not ss:
                continue
            lo = max((rank[w] for w in ps), default=-(1 << 30)) + 1
            hi = min((rank[w] for w in ss), default=1 << 30) - 1
            around = sorted([rank[w] for w in ps] + [rank[w] for w in ss])
            mid = len(around) // 2
            target = around[mid] if len(around) % 2 else around[mid - 1]
            best = min(max(target, lo), hi)
            if best != rank[v] and _length(v, best, ps, ss, rank) < _length(v, rank[v], ps, ss, rank):
                rank[v] = best
                moved = True
        if not moved:
            break


def _length(v: int, r: int, ps: list[int], ss: list[int], rank: list[int]) -> int:
    return sum(r - rank[w] for w in ps) + sum(rank[w] - r for w in ss)


# ----------------------------------------------------------------------------- ordering
def _initial_order(total: int, n: int, succ: list[list[int]], pred: list[list[int]], rank: list[int],
                   ids: list[str], hint: LayoutHint) -> list[int]:
    """Vertices in a first order: hinted ones by their old position, then breadth first from the sources."""
    hinted = [v for v in range(n) if ids[v] in hint.position]
    hinted.sort(key=lambda v: (hint.position[ids[v]], v))
    seen = [False] * total
    order: list[int] = []
    for v in hinted:
        seen[v] = True
        order.append(v)
    for root in range(total):
        if seen[root] or pred[root]:
            continue
        seen[root] = True
        queue = [root]
        head = 0
        while head < len(queue):
            v = queue[head]
            head += 1
            for w in succ[v]:
                if not seen[w]:
                    seen[w] = True
                    queue.append(w)
        order.extend(queue)
    order.extend(v for v in range(total) if not seen[v])
    return order


def _order_layers(layers: list[list[int]], succ: list[list[int]], pred: list[list[int]],
                  sweeps: int) -> tuple[list[list[int]], int]:
    """Barycenter sweeps down and up; keep the ordering with the fewest crossings."""
    pos = [0] * (max((v for layer in layers for v in layer), default=-1) + 1)

    def number(layer: list[int]) -> None:
        for i, v in enumerate(layer):
            pos[v] = i

    for layer in layers:
        number(layer)
    best = [list(layer) for layer in layers]
    best_cross = _total_crossings(layers, succ, pos)
    for sweep in range(sweeps):
        downward = sweep % 2 == 0
        sequence = range(1, len(layers)) if downward else range(len(layers) - 2, -1, -1)
        for li in sequence:
            layer = layers[li]
            neighbours = pred if downward else succ
            keys = []
            for v in layer:
                adj = neighbours[v]
                if adj:
                    keys.append((sum(pos[w] for w in adj) / len(adj), pos[v], v))
                else:
                    keys.append((float(pos[v]), pos[v], v))
            keys.sort()
            layers[li] = [k[2] for k in keys]
            number(layers[li])
        if downward and sweep + 1 < sweeps:
            continue  # judge each down-and-up pair as one step: counting is the costly part
        cross = _total_crossings(layers, succ, pos)
        if cross < best_cross:
            best_cross = cross
            best = [list(layer) for layer in layers]
        if best_cross == 0:
            break
    return best, best_cross


def _total_crossings(layers: list[list[int]], succ: list[list[int]], pos: list[int]) -> int:
    total = 0
    for li in range(len(layers) - 1):
        pairs = [(pos[v], pos[w]) for v in layers[li] for w in succ[v]]
        total += count_crossings(pairs, len(layers[li + 1]))
    return total


def count_crossings(pairs: list[tuple[int, int]], south_size: int) -> int:
    """Crossings between two layers whose edges join positions ``(north, south)`` (accumulator tree)."""
    if len(pairs) < 2:
        return 0
    pairs.sort()
    first = 1
    while first < south_size:
        first <<= 1
    tree = [0] * (2 * first)
    first -= 1
    crossings = 0
    for _, south in pairs:
        index = south + first
        tree[index] += 1
        while index > 0:
            if index % 2:
                crossings += tree[index + 1]
            index = (index - 1) >> 1
            tree[index] += 1
    return crossings


# ----------------------------------------------------------------------------- rows
def _place_rows(layers: list[list[int]], heights: list[int], succ: list[list[int]],
                pred: list[list[int]], rounds: int = 4) -> list[int]:
    """Vertical positions: every layer packed, then pulled towards its neighbours' centres."""
    ys = [0] * len(heights)
    offsets: list[list[int]] = []
    for layer in layers:
        acc = 0
        offs = []
        prev_dummy = False
        for i, v in enumerate(layer):
            dummy = heights[v] == 1
            if i:
                acc += 0 if (dummy and prev_dummy) else ROW_GAP
            offs.append(acc)
            ys[v] = acc
            acc += heights[v]
            prev_dummy = dummy
        offsets.append(offs)

    def centre(v: int) -> float:
        return ys[v] + heights[v] // 2

    for r in range(rounds):
        downward = r % 2 == 0
        sequence = range(len(layers)) if downward else range(len(layers) - 1, -1, -1)
        for li in sequence:
            layer = layers[li]
            if not layer:
                continue
            targets = []
            for v in layer:
                adj = (pred[v] + succ[v]) if r == rounds - 1 else (pred[v] if downward else succ[v])
                if adj:
                    cs = sorted(centre(w) for w in adj)
                    mid = len(cs) // 2
                    c = cs[mid] if len(cs) % 2 else (cs[mid - 1] + cs[mid]) / 2
                    targets.append(c - heights[v] // 2)
                else:
                    targets.append(float(ys[v]))
            offs = offsets[li]
            fitted = _isotonic([t - o for t, o in zip(targets, offs)])
            for v, z, o in zip(layer, fitted, offs):
                ys[v] = int(round(z)) + o
    low = min(ys) if ys else 0
    return [y - low for y in ys]


def _isotonic(values: list[float]) -> list[float]:
    """The non-decreasing sequence closest to ``values`` in least squares (pool adjacent violators)."""
    blocks: list[list[float]] = []  # [mean, weight]
    for v in values:
        blocks.append([v, 1.0])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            m2, w2 = blocks.pop()
            m1, w1 = blocks[-1]
            blocks[-1] = [(m1 * w1 + m2 * w2) / (w1 + w2), w1 + w2]
    out: list[float] = []
    for mean, weight in blocks:
        out.extend([mean] * int(weight))
    return out


# ----------------------------------------------------------------------------- routing
def _route(ids: list[str], layers: list[list[int]], ys: list[int], widths: list[int], heights: list[int],
           rank: list[int], chains: list[list[int]], edges: list[tuple[str, str]], reversed_flags: list[bool],
           crossings: int) -> Layout:
    n = len(ids)
    layer_w = [max((widths[v] for v in layer), default=0) for layer in layers]
    for li, layer in enumerate(layers):
        if layer_w[li] == 0 and layer:
            layer_w[li] = 1  # a layer of dummies only: a short horizontal run

    def row(v: int) -> int:
        return ys[v] + heights[v] // 2

    # Each hop u->w between adjacent layers belongs to u's bus in channel rank[u].
    buses: dict[int, list[int]] = {}
    hop_edges: dict[tuple[int, int], list[int]] = {}
    for k, chain in enumerate(chains):
        for u, w in zip(chain, chain[1:]):
            targets = buses.setdefault(u, [])
            if w not in targets:
                targets.append(w)
            hop_edges.setdefault((u, w), []).append(k)
    channel_tracks: list[dict[int, int]] = [dict() for _ in layers]
    channel_w: list[int] = []
    for li in range(len(layers)):
        spans = []
        for u in layers[li]:
            bus = buses.get(u)
            if not bus:
                continue
            rows = [row(u)] + [row(w) for w in bus]
            lo, hi = min(rows), max(rows)
            if lo != hi:
                spans.append((lo, hi, u))
        spans.sort()
        ends: list[int] = []  # last row used by each track
        for lo, hi, u in spans:
            for t, end in enumerate(ends):
                if end < lo:
                    ends[t] = hi
                    channel_tracks[li][u] = t
                    break
            else:
                channel_tracks[li][u] = len(ends)
                ends.append(hi)
        channel_w.append(len(ends) + CHANNEL_MARGIN)
    layer_x: list[int] = []
    x = 0
    for li in range(len(layers)):
        layer_x.append(x)
        x += layer_w[li] + (channel_w[li] if li < len(layers) - 1 else 0)
    width = x

    boxes: dict[str, Box] = {}
    for v in range(n):
        boxes[ids[v]] = Box(ids[v], layer_x[rank[v]], ys[v], widths[v], heights[v])
    segments: list[Segment] = []
    arrows: list[Arrow] = []
    # Dummies: a horizontal run through their layer.
    for k, chain in enumerate(chains):
        for d in chain[1:-1]:
            li = rank[d]
            segments.append(Segment(layer_x[li], ys[d], layer_x[li] + layer_w[li] - 1, ys[d], k))
    for (u, w), ks in hop_edges.items():
        li = rank[u]
        cx = layer_x[li] + layer_w[li]
        end_x = layer_x[li + 1] - 1
        start_x = (layer_x[li] + widths[u]) if u < n else cx
        yu, yw = row(u), row(w)
        track = channel_tracks[li].get(u)
        for k in ks:
            if track is None:
                segments.append(Segment(start_x, yu, end_x, yu, k))
            else:
                tx = cx + 1 + track
                segments.append(Segment(start_x, yu, tx, yu, k))
                segments.append(Segment(tx, min(yu, yw), tx, max(yu, yw), k))
                segments.append(Segment(tx, yw, end_x, yw, k))
            chain = chains[k]
            if reversed_flags[k]:
                if u == chain[0]:
                    arrows.append(Arrow(start_x, yu, k, left=True))
            elif w == chain[-1]:
                arrows.append(Arrow(end_x, yw, k))
    height = max((ys[v] + heights[v] for v in range(len(ys))), default=0)
    ranks = {ids[v]: rank[v] for v in range(n)}
    return Layout(boxes, segments, arrows, list(edges), width, height, ranks, crossings)
