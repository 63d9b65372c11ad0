"""The scheme at every position of the page, its point letters placed for all positions together.

Each position's scheme is drawn by the sheets' own drawing, `velplan.views.mechanism.scheme_steps`,
which stops at each `place_letters` call it needs. Here the drawings of all positions run in
step, and the calls they wait on are answered together (`place_together`): letter k of every
call in one pass, with numpy over all of them, and shapely asked per call only what depends on
that call's own lines (its tree of obstacles, of thin lines, the letters it placed before).
The choices are `place_letters`' own: the same candidates, costs and tests in the same order,
and a letter with no clear spot near its point (a leader) goes through `place_letters`' own
steps.
"""

from __future__ import annotations

from typing import Generator

import numpy as np
import shapely

from velplan.views.base import View
from velplan.views.letters import (
    _MARGIN_MM, _REACH, _TILED, _TURN_MM, _UNITS, GAPS_MM, LEADER_GAPS_MM, SAME_POINT_MM, SOFT_MM,
    _beyond, _centred, _settle)
from velplan.views.mechanism import LetterRequest


def draw_together(steps: list[Generator[LetterRequest, tuple, View]]) -> list[View]:
    """The views the `scheme_steps` generators draw, run in step: the letter requests pending
    at each step answered together (`place_together`)."""
    views: list[View | None] = [None] * len(steps)
    pending = {}
    for k, g in enumerate(steps):
        try:
            pending[k] = next(g)
        except StopIteration as done:
            views[k] = done.value
    while pending:
        keys = list(pending)
        answers = place_together([pending[k] for k in keys])
        pending = {}
        for k, answer in zip(keys, answers):
            try:
                pending[k] = steps[k].send(answer)
            except StopIteration as done:
                views[k] = done.value
    return views  # type: ignore[return-value]


class _Call:
    """One `place_letters` call's state: its trees, the boxes taken, what it placed so far."""

    def __init__(self, request: LetterRequest):
        texts, anchors, points, obstacles = request.args
        kw = request.kwargs
        if set(kw) - {"thin", "taken", "soft_mm"}:
            raise ValueError(f"place_together answers thin, taken and soft_mm only, not {sorted(kw)}")
        self.texts, self.anchors = list(texts), list(anchors)
        shapes = [g for g in obstacles if g is not None and not g.is_empty]
        self.shapes = shapes
        self.tree = shapely.STRtree(shapes) if shapes else None
        self.number = 0
        self.taken = list(kw.get("taken", ()))
        self.thin = [g for g in kw.get("thin", ()) if not g.is_empty]
        self.soft = shapely.STRtree(self.thin) if self.thin else None
        self.soft_mm = float(kw.get("soft_mm", SOFT_MM))
        allp = np.asarray(points, float).reshape(-1, 2)
        self.allp = allp[np.all(np.isfinite(allp), axis=1)]
        self.out: list = []
        self.leaders: list = []


def place_together(requests: list[LetterRequest]) -> list[tuple[list, list]]:
    """`place_letters(*r.args, **r.kwargs)` for each request (keyword arguments ``thin``,
    ``taken`` and ``soft_mm`` only), the same letters and leaders, letter k of every call placed in one pass."""
    calls = [_Call(r) for r in requests]
    together = _Obstacles(calls)
    for k in range(max([len(c.texts) for c in calls] + [0])):
        _place_kth([c for c in calls if len(c.texts) > k], k, together)
    return [(c.out, c.leaders) for c in calls]


class _Obstacles:
    """The obstacles and the thin lines of all the calls, each kind in one array with its
    envelopes, a call's own a run of it (``start[k]:stop[k]`` of call k)."""

    def __init__(self, calls: list[_Call]):
        for k, call in enumerate(calls):
            call.number = k
        self.hard = _Shapes([c.shapes for c in calls])
        self.thin = _Shapes([c.thin for c in calls])


class _Shapes:
    """Geometries of many calls in one array, with their envelopes, and per call a row of its
    geometries' indices and envelopes (NaN past its last: NaN meets nothing)."""

    def __init__(self, per_call: list[list]):
        self.geoms = np.array([g for gs in per_call for g in gs], dtype=object)
        self.bounds = shapely.bounds(self.geoms).reshape(-1, 4)
        most = max([len(g) for g in per_call] + [1])
        self.index = np.zeros((len(per_call), most), dtype=int)
        self.rows = np.full((4, len(per_call), most), np.nan)  # xmin, ymin, xmax, ymax
        start = 0
        for k, gs in enumerate(per_call):
            self.index[k, :len(gs)] = np.arange(start, start + len(gs))
            self.rows[:, k, :len(gs)] = self.bounds[start:start + len(gs)].T
            start += len(gs)

    def meeting(self, boxes: np.ndarray, calls: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The pairs (box, geometry) of each box (bounds (k, 4)) and the geometries of its own
        call (`calls`: each box's call) whose envelopes meet; the geometries whose envelope
        lies within the box flagged (a box meets them for sure)."""
        x0, y0, x1, y1 = self.rows[:, calls]  # (k, most) each
        b = boxes.T[:, :, None]
        i, m = np.nonzero((b[0] <= x1) & (b[2] >= x0) & (b[1] <= y1) & (b[3] >= y0))
        g, c = self.bounds[self.index[calls[i], m]], boxes[i]
        inside = (c[:, 0] <= g[:, 0]) & (c[:, 2] >= g[:, 2]) & (c[:, 1] <= g[:, 1]) & (c[:, 3] >= g[:, 3])
        return i, self.index[calls[i], m], inside

    def blocked(self, boxes: np.ndarray, calls: np.ndarray) -> np.ndarray:
        """Whether each box (bounds (k, 4)) meets a geometry of its call: the answer of the
        call's tree's "intersects" query, the exact tests in rounds, the geometry whose
        envelope the box covers most first, a box leaving at its first hit."""
        i, j, inside = self.meeting(boxes, calls)
        hit = np.zeros(len(boxes), dtype=bool)
        hit[i[inside]] = True
        keep = ~hit[i]
        i, j = i[keep], j[keep]
        if not len(i):
            return hit
        a, g = boxes[i], self.bounds[j]
        covered = ((np.minimum(a[:, 2], g[:, 2]) - np.maximum(a[:, 0], g[:, 0]))
                   * (np.minimum(a[:, 3], g[:, 3]) - np.maximum(a[:, 1], g[:, 1]))
                   / np.maximum((g[:, 2] - g[:, 0]) * (g[:, 3] - g[:, 1]), 1e-12))
        order = np.lexsort((-covered, i))
        i, j = i[order], j[order]
        made = np.empty(len(boxes), dtype=object)
        fresh = np.ones(len(boxes), dtype=bool)
        while len(i):  # each round tests the first candidate left of each box not yet hit
            first = np.empty(len(i), dtype=bool)
            first[0] = True
            np.not_equal(i[1:], i[:-1], out=first[1:])
            now = i[first]
            new = now[fresh[now]]
            made[new], fresh[new] = shapely.box(*boxes[new].T), False
            hit[now[shapely.intersects(self.geoms[j[first]], made[now])]] = True
            rest = ~first & ~hit[i]
            i, j = i[rest], j[rest]
        return hit

    def crossings(self, boxes: np.ndarray, calls: np.ndarray) -> np.ndarray:
        """How many geometries of its call each box (bounds (k, 4)) meets."""
        i, j, inside = self.meeting(boxes, calls)
        test = ~inside
        if test.any():
            inside[test] = shapely.intersects(self.geoms[j[test]], shapely.box(*boxes[i[test]].T))
        return np.bincount(i[inside], minlength=len(boxes))


def _place_kth(calls: list[_Call], k: int, together: _Obstacles) -> None:
    """Letter k of each call: the first `_choose` of `place_letters` for all at once, the rest
    (a letter with no clear spot near its point) as `place_letters` does it."""
    rows = []
    for c in calls:
        p = np.asarray(c.anchors[k], float)
        text = c.texts[k]
        centred, offset, half = _centred(text)
        wanted = np.asarray(text.position, float) - p
        wanted = wanted / np.hypot(*wanted) if np.hypot(*wanted) > 1e-9 else np.array([0.7071, 0.7071])
        others = c.allp[np.hypot(*(c.allp - p).T) > SAME_POINT_MM]
        rows.append((c, text, p, centred, offset, half, wanted, others))
    found = _first_choices(rows, together)
    for (c, text, p, centred, offset, half, wanted, others), hit in zip(rows, found):
        led = hit is None
        if led:
            hit = _beyond(p, wanted, half, others, c.tree, c.taken, c.soft, GAPS_MM, LEADER_GAPS_MM, c.soft_mm)
        _settle(text, centred, offset, hit, p if led else None, c.taken, c.out, c.leaders, "labels")

def _candidates(rows) -> tuple[np.ndarray, np.ndarray]:
    """`velplan.views.letters._candidates` of every row at `GAPS_MM`, the same sums: centres
    (r, n, 2) and costs (r, n)."""
    gaps = GAPS_MM
    half = np.array([r[5] for r in rows])
    point = np.array([r[2] for r in rows])
    reach = _REACH[None, :, 0] * half[:, 0, None] + _REACH[None, :, 1] * half[:, 1, None]
    turn = np.array([np.arccos(np.clip(_UNITS @ r[6], -1.0, 1.0)) for r in rows])
    g = np.repeat(np.asarray(gaps, float), len(_UNITS))
    tiled = _TILED.get(len(gaps))
    if tiled is None:
        tiled = _TILED[len(gaps)] = np.tile(_UNITS, (len(gaps), 1))
    centres = point[:, None, :] + tiled[None] * (g[None, :] + np.tile(reach, (1, len(gaps))))[..., None]
    return centres, g[None, :] + _TURN_MM * np.tile(turn, (1, len(gaps)))


def _nearest(centres: np.ndarray, rows) -> np.ndarray:
    """`velplan.views.letters._own_nearest` of candidates (r, s, 2) of every row, the same
    sums: another point missing from a row stands at infinity (nearer nothing)."""
    most = max(len(r[7]) for r in rows)
    pts = np.full((len(rows), 1 + most, 2), np.inf)
    for a, r in enumerate(rows):
        pts[a, 0] = r[2]
        pts[a, 1:1 + len(r[7])] = r[7]
    half = np.array([r[5] for r in rows])
    dx = np.maximum(np.abs(pts[:, None, :, 0] - centres[:, :, None, 0]) - half[:, None, None, 0], 0.0)
    dy = np.maximum(np.abs(pts[:, None, :, 1] - centres[:, :, None, 1]) - half[:, None, None, 1], 0.0)
    dist = np.hypot(dx, dy)
    if most == 0:
        return np.ones(centres.shape[:2], dtype=bool)
    return dist[..., 1:].min(axis=2) > dist[..., 0] + _MARGIN_MM


#: Candidates examined a stage at a time, the cheapest first (`velplan.views.letters._STAGES`,
#: finer: most letters find a clear spot among their few cheapest). The choice is the same at
#: any stages: the least (cost, index) of the clear candidates, as `_choose` makes it.
STAGES = (4, 12, 36, 96)


def _first_choices(rows, together: _Obstacles) -> list:
    """For each row, `_choose` at `GAPS_MM` with its own point nearest: the centre and the
    padded box chosen, or None; the stages of `_choose` run for all rows at once."""
    centres, base = _candidates(rows)
    n = centres.shape[1]
    order = np.lexsort((np.broadcast_to(np.arange(n), base.shape), base), axis=-1)
    best: list = [None] * len(rows)  # (cost, index, padded box)
    for start, stop in zip((0, *STAGES), (*STAGES, n)):
        if start >= n:
            break
        live = [a for a in range(len(rows)) if best[a] is None or not best[a][0] < base[a, order[a, start]]]
        if not live:
            break
        idx = np.sort(order[live, start:min(stop, n)], axis=1)
        c = centres[np.array(live)[:, None], idx]
        ok = _nearest(c, [rows[a] for a in live])
        for a, hit in zip(live, _stage([rows[a] for a in live], c, idx, ok, base[np.array(live)[:, None], idx],
                                       together)):
            if hit is not None and (best[a] is None or hit[:2] < best[a][:2]):
                best[a] = hit
    return [None if b is None else (centres[a, b[1]], b[2]) for a, b in enumerate(best)]


def _box_bounds(c: np.ndarray, half: np.ndarray, pad: float) -> np.ndarray:
    """Bounds (k, 4) of the `_boxes` of candidates (k, 2) of many rows at once, each row's half
    sizes (k, 2): the coordinates `shapely.box` is given."""
    return np.column_stack([c[:, 0] - half[:, 0] - pad, c[:, 1] - half[:, 1] - pad,
                            c[:, 0] + half[:, 0] + pad, c[:, 1] + half[:, 1] + pad])


def _stage(rows, c, idx, ok, cost, together: _Obstacles) -> list:
    """One stage of `_choose` for each row, its candidates (r, s, 2) and their indices, nearness
    `ok` and costs (r, s) known: the best clear candidate's (cost, index, padded box), or None.
    The boxes of all rows are tested together, each against its own call's shapes."""
    half = np.array([r[5] for r in rows])
    number = np.array([r[0].number for r in rows])
    at, col = np.nonzero(ok)
    padded = _box_bounds(c[at, col], (1.12 * half)[at], 0.4)  # rendered glyphs run wider than the estimate
    keep = ~together.hard.blocked(padded, number[at])
    taken = _Shapes([r[0].taken for r in rows])
    here = np.flatnonzero(keep)
    keep[here] = ~taken.blocked(padded[here], at[here])
    ok = ok.copy()
    ok[at, col] = keep
    at, col, padded = at[keep], col[keep], padded[keep]
    first = np.searchsorted(at, np.arange(len(rows) + 1))
    cost = cost.copy()
    crossed = together.thin.crossings(_box_bounds(c[at, col], half[at], 0.2), number[at])
    out: list[tuple[float, int] | None] = []
    chosen = []
    for r, row in enumerate(rows):
        call, mine = row[0], slice(first[r], first[r + 1])
        if first[r] == first[r + 1]:
            out.append(None)
            continue
        cost[r, ok[r]] += call.soft_mm * crossed[mine]
        j = int(np.argmin(np.where(ok[r], cost[r], np.inf)))
        out.append((float(cost[r, j]), int(idx[r, j])))
        chosen.append(first[r] + int(ok[r, :j].sum()))
    boxes = iter(shapely.box(*padded[chosen].T).tolist() if chosen else ())
    return [None if hit is None else (*hit, next(boxes)) for hit in out]
