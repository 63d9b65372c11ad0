"""Point letters kept by their points: each letter goes to the nearest free spot round its own
point where that point stays the nearest of all the drawing's points to it — never to a free
spot farther out that reads as another point's letter. Where no such spot is free, the letter
stands a little farther out, clear, and a thin leader joins it to its point.

>>> from velplan.render.scene import Text
>>> points = [(0.0, 0.0), (6.0, 0.0)]
>>> texts = [Text((3.0, 0.0), "A", "t", 3.5), Text((3.0, 0.0), "B", "t", 3.5)]
>>> placed, leaders = place_letters(texts, points, points)
>>> [round(label_box(t).distance(shapely.Point(p)), 1) for t, p in zip(placed, points)]
[1.0, 1.2]
>>> [label_box(t).distance(shapely.Point(p)) < label_box(t).distance(shapely.Point(q))
...  for t, p, q in zip(placed, points, points[::-1])]
[True, True]
"""

from __future__ import annotations

import dataclasses
from typing import Sequence

import numpy as np
import shapely

from velplan.render.layout import label_box
from velplan.render.scene import Polyline, Text

#: Gaps tried between a letter's box and its point, nearest first, mm.
GAPS_MM = (1.0, 1.6, 2.3, 3.0, 3.8, 4.6, 5.3)
#: Gaps of a letter with a leader, mm: beyond the crowd round its point.
LEADER_GAPS_MM = (6.5, 8.0, 9.5, 11.0, 12.5)
#: Directions tried round a point (every 15°).
_DIRECTIONS = np.radians(np.arange(0.0, 360.0, 15.0))
#: Millimetres of gap one radian off the wanted direction is worth.
_TURN_MM = 1.2
#: Millimetres of gap a thin line across a letter is worth.
SOFT_MM = 1.5
#: Two points nearer than this are one point for the letters (a coincident joint), mm.
SAME_POINT_MM = 0.3
#: A letter's own point must be nearer than any other by this, mm.
_MARGIN_MM = 0.3
#: How far from its point a letter without a leader may stand where the drawing asks it
#: (`place_letters`' `near_mm`): within the teacher's 6 mm, with a margin, mm.
NEAR_MM = 5.5


def _centred(text: Text) -> tuple[Text, np.ndarray, np.ndarray]:
    """`text` anchored at its middle, with its box's centre offset from its position and its
    half sizes, mm (read only: made once per text, size and type)."""
    key = (text.text, text.layer, text.size_mm, text.rotation_deg, text.width_factor)
    hit = _CENTRED.get(key)
    if hit is None:
        t = dataclasses.replace(text, anchor="middle", baseline="middle", position=(0.0, 0.0))
        x0, y0, x1, y1 = label_box(t).bounds
        offset, half = np.array([0.5 * (x0 + x1), 0.5 * (y0 + y1)]), np.array([0.5 * (x1 - x0), 0.5 * (y1 - y0)])
        offset.flags.writeable = half.flags.writeable = False
        if len(_CENTRED) >= 4096:
            _CENTRED.clear()
        hit = _CENTRED[key] = (t, offset, half)
    return hit


_CENTRED: dict[tuple, tuple[Text, np.ndarray, np.ndarray]] = {}


#: Unit vectors of `_DIRECTIONS`, their absolute values, and per number of gaps the vectors
#: repeated once a gap (made once).
_UNITS = np.column_stack([np.cos(_DIRECTIONS), np.sin(_DIRECTIONS)])
_REACH = np.abs(_UNITS)
_TILED: dict[int, np.ndarray] = {}


def _candidates(point, wanted, half, gaps) -> tuple[np.ndarray, np.ndarray]:
    """Box centres round `point` (mm) at each of `gaps` in every direction, and the cost of
    each: its gap plus the turn from the `wanted` direction, mm."""
    u = _UNITS
    reach = _REACH[:, 0] * half[0] + _REACH[:, 1] * half[1]
    turn = np.arccos(np.clip(u @ wanted, -1.0, 1.0))
    g = np.repeat(np.asarray(gaps, float), len(u))
    tiled = _TILED.get(len(gaps))
    if tiled is None:
        tiled = _TILED[len(gaps)] = np.tile(u, (len(gaps), 1))
    centres = point + tiled * (g + np.tile(reach, len(gaps)))[:, None]
    return centres, g + _TURN_MM * np.tile(turn, len(gaps))


def _boxes(centres, half, pad: float):
    return shapely.box(centres[:, 0] - half[0] - pad, centres[:, 1] - half[1] - pad,
                       centres[:, 0] + half[0] + pad, centres[:, 1] + half[1] + pad)


def _own_nearest(centres, half, point, others) -> np.ndarray:
    """Whether `point` is nearer each box (centred at `centres`, half sizes `half`, mm) than
    every one of `others` (by a margin): the distances of upright boxes in closed form."""
    if not len(others):
        return np.ones(len(centres), dtype=bool)
    pts = np.vstack([np.asarray(point, float)[None, :], np.asarray(others, float)])
    dx = np.maximum(np.abs(pts[None, :, 0] - centres[:, None, 0]) - half[0], 0.0)
    dy = np.maximum(np.abs(pts[None, :, 1] - centres[:, None, 1]) - half[1], 0.0)
    dist = np.hypot(dx, dy)
    return dist[:, 1:].min(axis=1) > dist[:, 0] + _MARGIN_MM


#: Candidates examined a stage at a time, the cheapest first: a stage is looked at only where
#: its cheapest could still beat (or tie) the best clear candidate found.
_STAGES = (24, 72)


def _within(centres, half, point, near: float | None) -> np.ndarray:
    """Whether each box (centred at `centres`, half sizes `half`, mm) lies within `near` mm of
    `point` (all of them where `near` is None): a wide box beside its point on a slant stands
    farther off than its gap along the slant."""
    if near is None:
        return np.ones(len(centres), dtype=bool)
    d = np.maximum(np.abs(centres - np.asarray(point, float)) - half, 0.0)
    return np.hypot(d[:, 0], d[:, 1]) <= near


#: How far a leader passes by the other points, mm (it would read as theirs).
LEADER_CLEAR_MM = 1.0


def _leaders_clear(centres, half, point, taken_boxes, others) -> np.ndarray:
    """Whether the leader from `point` to each box (centred at `centres`, half sizes `half`,
    mm; it ends 0.4 mm off the box, as `place_letters` draws it) keeps off the `taken` boxes
    and passes the `others` points by :data:`LEADER_CLEAR_MM` at least."""
    p = np.asarray(point, float)
    ends = np.clip(p, centres - half - 0.4, centres + half + 0.4)
    segments = shapely.linestrings(np.stack([np.broadcast_to(p, ends.shape), ends], axis=1))
    ok = np.ones(len(centres), dtype=bool)
    if taken_boxes is not None:
        ok &= ~shapely.intersects(segments[:, None], taken_boxes[None, :]).any(axis=1)
    if len(others):
        ok &= shapely.distance(segments, shapely.multipoints(np.asarray(others, float))) > LEADER_CLEAR_MM
    return ok


def _leader_inside(centres, half, point, taken_boxes) -> np.ndarray:
    """How long the leader from `point` to each box (centred at `centres`, half sizes `half`,
    mm; drawn as `_leaders_clear` takes it) runs inside the `taken` boxes, mm, a millimetre
    deeper than :data:`CORE_MM` inside one counted :data:`CORE_WEIGHT` times more (through a
    letter, not only by it)."""
    p = np.asarray(point, float)
    ends = np.clip(p, centres - half - 0.4, centres + half + 0.4)
    segments = shapely.linestrings(np.stack([np.broadcast_to(p, ends.shape), ends], axis=1))
    i, j = shapely.STRtree(taken_boxes).query(segments, predicate="intersects")
    inside = shapely.length(shapely.intersection(segments[i], taken_boxes[j]))
    inside += CORE_WEIGHT * shapely.length(shapely.intersection(segments[i], shapely.buffer(taken_boxes[j], -CORE_MM)))
    return np.bincount(i, weights=inside, minlength=len(centres))


#: A leader this far inside a taken box (a letter's, padded) runs through the letter itself, mm…
CORE_MM = 1.0
#: …and its length there counts this many times more.
CORE_WEIGHT = 4.0


def _choose(point, wanted, half, others, tree, taken, gaps, need_nearest: bool, soft=None,
            weight: float = SOFT_MM, near: float | None = None, leader: bool = False, through: float = 0.0):
    """The cheapest candidate centre clear of the obstacles (`tree`) and of the `taken` boxes
    (and, if `need_nearest`, nearer its own point than any other and within `near` mm of it;
    if `leader`, with its leader clear of the `taken` boxes and the `others` points), each line of `soft` (a tree of
    thin lines) across it costing `weight` mm, each mm of its leader inside the `taken` boxes
    `through` mm: its centre and box, or None. Of equal costs,
    the first candidate (`_candidates`' order) wins."""
    centres, base = _candidates(point, wanted, half, gaps)
    n = len(centres)
    order = np.lexsort((np.arange(n), base))  # by cost, then by place in the candidates
    taken_boxes = np.array(taken) if taken else None
    best = None  # (cost, index, padded box)
    for start, stop in zip((0, *_STAGES), (*_STAGES, n)):
        if start >= n:
            break
        if best is not None and best[0] < base[order[start]]:
            break  # every later candidate costs more than the best clear one
        idx = np.sort(order[start:min(stop, n)])
        c = centres[idx]
        # the cheap tests first (in closed form), shapely's only on the candidates they pass
        ok = (_own_nearest(c, half, point, others) & _within(c, half, point, near) if need_nearest
              else np.ones(len(idx), dtype=bool))
        if not ok.any():
            continue
        padded = _boxes(c[ok], 1.12 * half, 0.4)  # rendered glyphs run wider than the estimate
        keep = np.ones(len(padded), dtype=bool)
        if tree is not None:
            keep &= ~_blocked(tree, padded)
        if taken_boxes is not None and keep.any():  # the boxes still clear alone are tested on
            rows = np.flatnonzero(keep)
            keep[rows] = ~shapely.intersects(padded[rows, None], taken_boxes[None, :]).any(axis=1)
        if leader and keep.any():
            rows = np.flatnonzero(keep)
            keep[rows] = _leaders_clear(c[ok][rows], half, point, taken_boxes, others)
        padded = padded[keep]
        ok[ok] = keep
        if not ok.any():
            continue
        cost = base[idx]
        if soft is not None:  # the lines across the clear boxes (the others are not chosen)
            crossed = soft.query(_boxes(c[ok], half, 0.2), predicate="intersects")[0]
            cost = cost.copy()
            cost[ok] += weight * np.bincount(crossed, minlength=int(ok.sum()))
        if through and taken_boxes is not None:  # a leader through another letter, the less the better
            cost = cost.copy()
            cost[ok] += through * _leader_inside(c[ok], half, point, taken_boxes)
        j = int(np.argmin(np.where(ok, cost, np.inf)))
        if best is None or (cost[j], idx[j]) < (best[0], best[1]):
            best = (float(cost[j]), int(idx[j]), padded[int(ok[:j].sum())])
    if best is None:
        return None
    return centres[best[1]], best[2]


def _blocked(tree, boxes) -> np.ndarray:
    """Whether each of `boxes` meets a geometry of `tree` (a shapely STRtree): the answer of the
    tree's "intersects" query with fewer exact tests. A box's candidates (the geometries whose
    envelopes meet it) are tested in rounds, the one whose envelope the box covers most
    first; a box leaves at its first hit."""
    hit = np.zeros(len(boxes), dtype=bool)
    i, j = tree.query(boxes)
    if not len(i):
        return hit
    a, b = shapely.bounds(boxes)[i], shapely.bounds(tree.geometries)[j]
    covered = ((np.minimum(a[:, 2], b[:, 2]) - np.maximum(a[:, 0], b[:, 0]))
               * (np.minimum(a[:, 3], b[:, 3]) - np.maximum(a[:, 1], b[:, 1]))
               / np.maximum((b[:, 2] - b[:, 0]) * (b[:, 3] - b[:, 1]), 1e-12))
    order = np.lexsort((-covered, i))
    i, j = i[order], j[order]
    geoms = tree.geometries
    while len(i):  # each round tests the first candidate left of each box not yet hit
        first = np.empty(len(i), dtype=bool)
        first[0] = True
        np.not_equal(i[1:], i[:-1], out=first[1:])
        now = i[first]
        hit[now[shapely.intersects(geoms[j[first]], boxes[now])]] = True
        rest = ~first & ~hit[i]
        i, j = i[rest], j[rest]
    return hit


def place_letters(texts: Sequence[Text], anchors, points, obstacles=(), *, taken=(), thin=(),
                  leader_layer: str = "labels", gaps: Sequence[float] = GAPS_MM,
                  leader_gaps: Sequence[float] = LEADER_GAPS_MM,
                  near_mm: float | None = None, soft_mm: float = SOFT_MM) -> tuple[list[Text], list[Polyline]]:
    """Place point letters, in order, each by its own point.

    Parameters
    ----------
    texts : sequence of Text
        The letters at their wanted places (the direction from the point to it is preferred).
    anchors : sequence of (x, y)
        Each letter's own point, mm.
    points : sequence of (x, y)
        Every point of the drawing a letter could be taken to name, mm.
    obstacles : iterable of shapely geometry
        What the letters keep off (lines, symbols).
    taken : iterable of shapely geometry
        Boxes of labels already placed.
    thin : iterable of shapely geometry
        Thin lines a letter may cross where it must, the fewer the better.
    gaps, leader_gaps : sequence of float
        The gaps (mm) between a letter's box and its point tried without a leader, nearest
        first, and those of a letter with a leader.
    near_mm : float, optional
        How far from its point (box to point) a letter without a leader may stand, mm (e.g.
        :data:`NEAR_MM`); by default as far as `gaps` take it.
    soft_mm : float
        The millimetres of gap a thin line across a letter is worth.

    Returns
    -------
    (letters, leaders)
        The letters, and a thin leader for each letter that had to stand beyond the crowd
        round its point.
    """
    shapes = [g for g in obstacles if g is not None and not g.is_empty]
    tree = shapely.STRtree(shapes) if shapes else None
    taken = list(taken)
    thin = [g for g in thin if not g.is_empty]
    soft = shapely.STRtree(thin) if thin else None
    allp = np.asarray(points, float).reshape(-1, 2)
    allp = allp[np.all(np.isfinite(allp), axis=1)]
    out, leaders = [], []
    for text, anchor in zip(texts, anchors):
        p = np.asarray(anchor, float)
        centred, offset, half = _centred(text)
        wanted = np.asarray(text.position, float) - p
        wanted = wanted / np.hypot(*wanted) if np.hypot(*wanted) > 1e-9 else np.array([0.7071, 0.7071])
        others = allp[np.hypot(*(allp - p).T) > SAME_POINT_MM]
        found = _choose(p, wanted, half, others, tree, taken, gaps, True, soft, soft_mm, near=near_mm)
        led = found is None
        if led:
            found = _beyond(p, wanted, half, others, tree, taken, soft, gaps, leader_gaps, soft_mm)
        _settle(text, centred, offset, found, p if led else None, taken, out, leaders, leader_layer)
    return out, leaders


def _beyond(p, wanted, half, others, tree, taken, soft, gaps, leader_gaps, soft_mm: float = SOFT_MM):
    """A letter's place with a leader, where none is clear near its point: beyond the crowd,
    the leader off the other letters where it can be; then, crowded all round, off the other
    letters over the fewest lines: its centre and box, or None."""
    found = None
    # a leader through another letter reads as that letter's: past the other points by less,
    # then farther out, before through it
    none = np.empty((0, 2))
    for passed, clear_leader, gaps_out in ((others, True, leader_gaps), (none, True, leader_gaps),
                                           (none, True, _farther(leader_gaps)), (others, False, leader_gaps)):
        if found is None and gaps_out:
            found = _choose(p, wanted, half, passed, tree, taken, gaps_out, False, soft, soft_mm,
                            leader=clear_leader, through=0.0 if clear_leader else THROUGH_MM)
    for clear_leader in (True, False):
        if found is None:
            found = _choose(p, wanted, half, others, None, taken, (*gaps, *leader_gaps), False, tree, 20.0,
                            leader=clear_leader)
    return found


#: Millimetres of gap a millimetre of a leader inside another letter's box is worth, where
#: every leader runs through one: the least through it.
THROUGH_MM = 5.0
#: Beyond the last leader gap, the gaps (as its multiples) tried where no leader is clear nearer.
FARTHER = (1.25, 1.5, 1.8)


def _farther(leader_gaps: Sequence[float]) -> tuple[float, ...]:
    """The gaps beyond `leader_gaps` where a letter whose leader crosses another letter at
    every nearer place looks for a clear one (:data:`FARTHER` of the last), mm."""
    return tuple(leader_gaps[-1] * f for f in FARTHER) if len(leader_gaps) else ()


def _settle(text, centred, offset, found, led_from, taken, out, leaders, leader_layer) -> None:
    """Record a letter: where `found` put it (as given where nothing did), its box taken, and
    its leader from the point `led_from` (None: no leader), which the later letters keep off."""
    if found is None:
        out.append(text)
        return
    centre, padded = found
    placed = dataclasses.replace(centred, position=tuple((centre - offset).tolist()))
    taken.append(padded)
    out.append(placed)
    if led_from is not None:
        p = led_from
        near = shapely.shortest_line(label_box(placed).buffer(0.4), shapely.Point(p)).coords[0]
        leaders.append(Polyline(((float(p[0]), float(p[1])), (near[0], near[1])), leader_layer, "thin"))
        taken.append(shapely.LineString(leaders[-1].points).buffer(0.3))


#: Gaps tried round a label that a line crosses (`step_aside`), mm: it stays by what it names.
ASIDE_GAPS_MM = (0.3, 1.0, 1.8, 2.6)


def step_aside(texts: Sequence[Text], obstacles, *, taken=(), gaps: Sequence[float] = ASIDE_GAPS_MM) -> list[Text]:
    """`texts` (placed already: a link's number, ω) with each one whose box meets one of
    `obstacles` (lines, symbols) moved to the cheapest spot round its place clear of them and
    of the `taken` boxes and the other texts (its box `gaps` off its old centre, nearest and
    least turned first); one with no such spot stays. No leader: it stays by what it names.

    >>> import shapely
    >>> t = Text((0.0, 0.0), "1", "labels", 3.5, "middle", "middle")
    >>> (moved,) = step_aside([t], [shapely.LineString([(-5, 0), (5, 0)]).buffer(0.4)])
    >>> label_box(moved).intersects(shapely.LineString([(-5, 0), (5, 0)]).buffer(0.4))
    False
    """
    shapes = [g for g in obstacles if g is not None and not g.is_empty]
    if not shapes:
        return list(texts)
    tree = shapely.STRtree(shapes)
    out = list(texts)
    boxes = [label_box(t) for t in out]
    for k, text in enumerate(out):
        if text.rotation_deg != 0.0 or not len(tree.query(boxes[k], predicate="intersects")):
            continue
        centred, offset, half = _centred(text)
        p = np.asarray(boxes[k].centroid.coords[0])
        others = [*taken, *(b.buffer(0.4) for j, b in enumerate(boxes) if j != k)]
        found = _choose(p, np.array([0.7071, 0.7071]), half, (), tree, others, gaps, False)
        if found is not None:
            out[k] = dataclasses.replace(centred, position=tuple((found[0] - offset).tolist()))
            boxes[k] = label_box(out[k])
    return out
