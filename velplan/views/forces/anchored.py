"""Labels kept by what they name: each label is moved, if it must, only to places where the
thing it names (a point, a force arrow, a couple's arc) stays the nearest of its kind to it
and within reach — never to a free spot that reads as another arrow's label.

>>> import shapely
>>> from velplan.render.scene import Polyline, Text
>>> arrows = [shapely.LineString([(0, 0), (20, 0)]), shapely.LineString([(0, 6), (20, 6)])]
>>> texts = [Text((10.0, 3.0), "F₁", "t", 3.5), Text((10.0, 3.0), "F₂", "t", 3.5)]
>>> placed = place_anchored(texts, arrows, ["force", "force"], [a.buffer(0.5) for a in arrows])
>>> [[round(label_box(t).distance(a), 1) for a in arrows] for t in placed]
[[0.6, 1.0], [6.7, 0.7]]
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import shapely

from velplan.render.layout import label_box
from velplan.render.scene import Polyline, Text
from velplan.render.shapes import text_depth, text_extent

#: A label farther than this from what it names does not read as its label, mm.
REACH_MM = 6.0
#: A box shrunk by this meets an obstacle (a line buffered by 0.6 mm) only where the line
#: itself enters the box: it runs through the letters, not by the box's edge, mm.
CORE_MM = 0.55
#: The gap kept between two labels, mm: closer, two labels read as one ("cF(MΦ₅)").
GAP_MM = 1.0


def _spots(text: Text, rings: int) -> list[tuple[float, float]]:
    """The label's own place, then rings of twelve places around it, half a letter apart."""
    x, y = text.position
    step = 0.5 * text.size_mm
    out = [(x, y)]
    for r in range(1, rings + 1):
        out += [(x + r * step * c, y + r * step * s) for c, s in _TWELVE]
    return out


#: The cosine and sine of the twelve directions 30° apart, computed once.
_TWELVE = tuple((math.cos(math.radians(30.0 * k)), math.sin(math.radians(30.0 * k))) for k in range(12))


def place_anchored(texts, anchors, kinds, obstacles=(), *, rings: int = 6,
                   reach: float = REACH_MM, leader_layer: str | None = None, lead=()) -> list:
    """Move labels, in order, clear of `obstacles` and of each other, each kept nearer to its
    own anchor than to any other anchor of its kind and within `reach` mm of it. Where no place
    is clear, the label takes the one nearest its anchor that overlaps no other label and has
    the fewest lines through its letters.

    Parameters
    ----------
    texts : sequence of Text
        The labels at their wanted places.
    anchors : sequence of shapely geometry
        What each label names (a point, a segment, an arc), mm.
    kinds : sequence of str
        The kind of each anchor; a label is compared with the anchors of its own kind.
    obstacles : iterable of shapely geometry
        What the labels keep off (lines, arrows, marks).
    leader_layer : str, optional
        Where a line would run through a label's letters at every place within reach, look
        farther out for a clear place and join the label to its anchor by a thin leader on
        this layer (the leaders follow the labels in the list).
    lead : collection of int
        The labels (by index) to set farther out with a leader wherever one finds a place:
        those of points too close together for a letter beside each to tell them apart.
    """
    shapes = [g for g in obstacles if g is not None and not g.is_empty]
    tree = shapely.STRtree(shapes) if shapes else None
    anchors = np.asarray(list(anchors), dtype=object)
    kinds = np.asarray(list(kinds))
    placed: list = []  # the placed labels' and leaders' keep-off areas
    taken = (placed, {})  # and those of them shrunk so far (`_shrunk`)
    out: list = []
    leaders: list = []
    for i, text in enumerate(texts):
        mates = np.flatnonzero((kinds == kinds[i]) & (np.arange(len(kinds)) != i))
        best = None
        if leader_layer is not None and i in lead:
            best = _led(text, anchors[i], rings, tree, taken, leaders, leader_layer)
        best = best or (_best_upright if text.rotation_deg == 0.0 else _best_each)(
            text, _spots(text, rings), anchors[i], anchors[mates], tree, taken, reach)
        if leader_layer is not None and (best[0] >= 100.0 or _run_through(best[2], tree, shapes)):
            best = _led(text, anchors[i], rings, tree, taken, leaders, leader_layer) or best
        out.append(best[1])
        placed.append(best[2].buffer(GAP_MM))
    return out + leaders


#: A line inside a label's box over this length (mm) runs through the label, by its edge or not.
THROUGH_MM = 1.0


def _run_through(box, tree, shapes) -> bool:
    """Whether a line kept off by a band of `shapes` (in `tree`) runs inside `box` over
    :data:`THROUGH_MM`: a label it grazes that far reads as crossed, though the edge's cost in
    `_stage_costs` let it stand there when nothing within reach was clear."""
    if tree is None:
        return False
    for j in tree.query(box, predicate="intersects").tolist():
        g = shapes[j]
        width = 2.0 * g.area / max(g.length, 1e-9)  # a band round a line: its width, about
        if 0.0 < width < 2.0 and g.intersection(box).area / width > THROUGH_MM:
            return True
    return False


def _shrunk(taken, j: int):
    """The placed area `j` of `taken` shrunk by GAP_MM + 0.1 mm, made once when first asked: a
    label over it puts text over text."""
    placed, shrunk = taken
    if j not in shrunk:
        shrunk[j] = placed[j].buffer(-GAP_MM - 0.1)
    return shrunk[j]


def _best_each(text: Text, spots, own_anchor, mate_anchors, tree, taken, reach: float):
    """`place_anchored`'s choice for `text` among `spots`, costed one spot at a time; `taken`
    is (the placed labels' areas, those shrunk so far): (cost, label there, its box)."""
    placed = taken[0]
    best = None
    for rank, spot in enumerate(spots):
        cand = dataclasses.replace(text, position=spot)
        box = label_box(cand)
        own = float(shapely.distance(box, own_anchor))
        others = shapely.distance(box, mate_anchors) if mate_anchors.size else np.array([np.inf])
        hits = len(tree.query(box, predicate="intersects")) if tree is not None else 0
        # a line through the letters is worse than one grazing the box's edge
        core = len(tree.query(box.buffer(-CORE_MM), predicate="intersects")) if hits else 0
        cost = (0.05 * rank + 30.0 * hits + 100.0 * core
                + 1000.0 * sum(box.intersects(b) for b in placed)
                + 4000.0 * sum(box.intersects(_shrunk(taken, j)) for j in range(len(placed)))
                + (1000.0 if own > reach or float(np.min(others)) <= own else 0.0))
        if best is None or cost < best[0]:
            best = (cost, cand, box)
        if cost < 0.05 * (rank + 1):  # free and by its own anchor: the nearest such
            break
    return best


#: Where the stages of an upright label's spots end, their costs computed a stage at a time:
#: its own place (most labels stay there), the first ring, the next two, the rest.
_STAGES = (1, 13, 37)


def _best_upright(text: Text, spots, own_anchor, mate_anchors, tree, taken, reach: float):
    """:func:`_best_each`'s choice for an upright label, its spots' costs computed a stage at a
    time with shapely's array functions (the same boxes, the same numbers in the same order)."""
    placed = np.array(taken[0], dtype=object)
    best = None
    bounds = [0, *(b for b in _STAGES if b < len(spots)), len(spots)]
    for start, stop in zip(bounds, bounds[1:]):
        boxes = _upright_boxes(text, np.array(spots[start:stop], float))
        costs = _stage_costs(boxes, start, own_anchor, mate_anchors, tree, taken, placed, reach,
                             np.inf if best is None else best[0])
        for j, cost in enumerate(costs.tolist()):
            rank = start + j
            if best is None or cost < best[0]:
                best = (cost, rank, boxes[j])
            if cost < 0.05 * (rank + 1):  # free and by its own anchor: the nearest such
                return best[0], dataclasses.replace(text, position=spots[best[1]]), best[2]
    return best[0], dataclasses.replace(text, position=spots[best[1]]), best[2]


def _stage_costs(boxes, start: int, own_anchor, mate_anchors, tree, taken, placed, reach: float,
                 best: float) -> np.ndarray:
    """The costs of a stage's `boxes` (ranks from `start`) as `_best_each` adds them up; a box a
    line meets whose cost without its lines through the letters (≥ 0) cannot beat `best` or a
    box before it in the stage costs inf (it would not be chosen either way)."""
    n = len(boxes)
    rank = np.arange(start, start + n)
    own = shapely.distance(boxes, own_anchor)
    others = (shapely.distance(boxes[:, None], mate_anchors[None, :]).min(axis=1) if mate_anchors.size
              else np.full(n, np.inf))
    hits = np.zeros(n, int) if tree is None else np.bincount(tree.query(boxes, predicate="intersects")[0], minlength=n)
    crossed = over = 0
    if placed.size:
        meets = shapely.intersects(boxes[:, None], placed[None, :])
        crossed = meets.sum(axis=1)
        # a placed area's shrunk copy lies inside it: only those met can be overlapped
        near = [_shrunk(taken, j) for j in np.flatnonzero(meets.any(axis=0)).tolist()]
        if near:
            over = shapely.intersects(boxes[:, None], np.array(near, dtype=object)[None, :]).sum(axis=1)
    far = np.where((own > reach) | (others <= own), 1000.0, 0.0)
    least = 0.05 * rank + 30.0 * hits + 1000.0 * crossed + 4000.0 * over + far  # rounding keeps it ≤ the cost
    # the best a box meets on its turn is at most the least cost of the clear boxes before it
    before = np.minimum.accumulate(np.concatenate([[best], np.where(hits == 0, least, np.inf)[:-1]]))
    grazed = np.flatnonzero(hits)
    grazed = grazed[(least[grazed] < before[grazed]) | (least[grazed] < 0.05 * (rank[grazed] + 1))]
    core = np.zeros(n, int)  # a line through the letters costs more than one by the edge
    if grazed.size:
        cores = shapely.buffer(boxes[grazed], -CORE_MM, quad_segs=16)  # as Polygon.buffer(-CORE_MM)
        core[grazed] = np.bincount(tree.query(cores, predicate="intersects")[0], minlength=grazed.size)
    costs = 0.05 * rank + 30.0 * hits + 100.0 * core + 1000.0 * crossed + 4000.0 * over + far
    passed_over = hits > 0
    passed_over[grazed] = False
    return np.where(passed_over, np.inf, costs)


def _upright_boxes(text: Text, xy: np.ndarray) -> np.ndarray:
    """The boxes of upright `text` at the places `xy` (n, 2), mm: `label_box`'s polygons, the
    same numbers computed as `text_box` computes them."""
    width = text_extent(text.text, text.size_mm)[0] * text.width_factor
    x0 = -width * _ANCHOR_SHARE[text.anchor]
    below, top = text_depth(text.text, text.size_mm)
    x1, y0 = x0 + width, -below
    ox, oy = xy[:, 0], xy[:, 1] - _DROP_SHARE[text.baseline] * text.size_mm
    corners = np.empty((len(xy), 4, 2))
    corners[:, 0, 0] = corners[:, 3, 0] = ox + x0
    corners[:, 1, 0] = corners[:, 2, 0] = ox + x1
    corners[:, 0, 1] = corners[:, 1, 1] = oy + y0
    corners[:, 2, 1] = corners[:, 3, 1] = oy + top
    return shapely.polygons(corners)


_ANCHOR_SHARE = {"start": 0.0, "middle": 0.5, "end": 1.0}
_DROP_SHARE = {"baseline": 0.0, "middle": 0.5, "top": 1.0}


def _led(text: Text, anchor, rings: int, tree, taken, leaders: list, layer: str):
    """The first clear place for `text` beyond `rings` rings (out to three times as far) whose
    leader from `anchor` crosses no placed label and no drawn line (else the one whose leader
    crosses the fewest lines), its leader appended to `leaders` and kept off by the later
    labels: (0, label, box), or None."""
    placed = taken[0]
    best = None
    spots = _spots(text, 3 * rings)[1 + 12 * rings:]
    boxes = (_upright_boxes(text, np.array(spots, float)) if text.rotation_deg == 0.0
             else np.array([label_box(dataclasses.replace(text, position=p)) for p in spots], dtype=object))
    clear = np.ones(len(spots), bool)  # off the lines and the placed labels, found at once
    if tree is not None:
        clear[tree.query(boxes, predicate="intersects")[0]] = False
    if placed:
        clear &= ~shapely.intersects(boxes[:, None], np.array(placed, dtype=object)[None, :]).any(axis=1)
    for k in np.flatnonzero(clear).tolist():
        cand, box = dataclasses.replace(text, position=spots[k]), boxes[k]
        line = shapely.shortest_line(anchor, box.buffer(0.4))
        if (any(line.intersects(_shrunk(taken, j)) for j in range(len(placed)))
                or any(line.intersects(shapely.LineString(other.points)) for other in leaders)):
            continue  # through a label, or across another leader
        # the lines it meets (or runs along) beyond 1.5 mm from the anchor, where they leave it
        tail = line.difference(shapely.Point(line.coords[0]).buffer(1.5))
        crossed = 0 if tree is None or tail.is_empty else len(tree.query(tail, predicate="intersects"))
        if best is None or crossed < best[0]:
            best = (crossed, cand, box, line)
        if crossed == 0:
            break
    return kept_leader(best, leaders, placed, layer, 0.6)


def kept_leader(best, leaders: list, taken: list, layer: str, clear_mm: float):
    """The label of `best` ((cost, label, box, leader line) or None) with its leader: the leader
    drawn thin on `layer` into `leaders` and kept off by `clear_mm` mm (`taken`); (0, label,
    box), or None."""
    if best is None:
        return None
    _, text, box, line = best
    (x0, y0), (x1, y1) = line.coords
    leaders.append(Polyline(((x0, y0), (x1, y1)), layer, "thin"))
    taken.append(line.buffer(clear_mm))
    return 0.0, text, box
