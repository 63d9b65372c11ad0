"""Labels kept by what they name: each label is moved, if it must, only to places where the
thing it names (a point, a force arrow, a couple's arc) stays the nearest of its kind to it
and within reach — never to a free spot that reads as another arrow's label.

>>> import shapely
>>> from velplan.render.scene import Text
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
from velplan.render.scene import Text
from velplan.render.shapes import DESCENDER_DEPTH, text_extent

#: A label farther than this from what it names does not read as its label, mm.
REACH_MM = 6.0


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
                   reach: float = REACH_MM) -> list[Text]:
    """Move labels, in order, clear of `obstacles` and of each other, each kept nearer to its
    own anchor than to any other anchor of its kind and within `reach` mm of it.

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
    """
    shapes = [g for g in obstacles if g is not None and not g.is_empty]
    tree = shapely.STRtree(shapes) if shapes else None
    anchors = np.asarray(list(anchors), dtype=object)
    kinds = np.asarray(list(kinds))
    placed: list = []
    out = []
    for i, text in enumerate(texts):
        mates = np.flatnonzero((kinds == kinds[i]) & (np.arange(len(kinds)) != i))
        if text.rotation_deg == 0.0:
            best = _best_upright(text, _spots(text, rings), anchors[i], anchors[mates], tree, placed, reach)
            out.append(best[1])
            placed.append(best[2].buffer(0.5))
            continue
        best = None
        for rank, spot in enumerate(_spots(text, rings)):
            cand = dataclasses.replace(text, position=spot)
            box = label_box(cand)
            own = float(shapely.distance(box, anchors[i]))
            others = shapely.distance(box, anchors[mates]) if mates.size else np.array([np.inf])
            hits = len(tree.query(box, predicate="intersects")) if tree is not None else 0
            cost = (0.05 * rank + 100.0 * hits
                    + 1000.0 * sum(box.intersects(b) for b in placed)
                    + (1000.0 if own > reach or float(np.min(others)) <= own else 0.0))
            if best is None or cost < best[0]:
                best = (cost, cand, box)
            if cost < 0.05 * (rank + 1):  # free and by its own anchor: the nearest such
                break
        out.append(best[1])
        placed.append(best[2].buffer(0.5))
    return out


#: Where the stages of an upright label's spots end, their costs computed a stage at a time:
#: its own place (most labels stay there), the first ring, the next two, the rest.
_STAGES = (1, 13, 37)


def _best_upright(text: Text, spots, own_anchor, mate_anchors, tree, placed, reach: float):
    """`place_anchored`'s choice for an upright label, its spots' costs computed a stage at a
    time with shapely's array functions (the same numbers as one spot at a time):
    (cost, label there, its box)."""
    width, _ = text_extent(text.text, text.size_mm)
    x0 = -width * _ANCHOR_SHARE[text.anchor]
    x1, y0 = x0 + width, -DESCENDER_DEPTH * text.size_mm
    drop = _DROP_SHARE[text.baseline] * text.size_mm
    best = None
    bounds = [0, *(b for b in _STAGES if b < len(spots)), len(spots)]
    for start, stop in zip(bounds, bounds[1:]):
        xy = np.array(spots[start:stop], float)
        ox, oy = xy[:, 0], xy[:, 1] - drop  # as `text_box` places an upright label's box
        boxes = shapely.polygons(np.stack([np.column_stack([ox + x0, oy + y0]), np.column_stack([ox + x1, oy + y0]),
                                           np.column_stack([ox + x1, oy + text.size_mm]),
                                           np.column_stack([ox + x0, oy + text.size_mm])], axis=1))
        n = stop - start
        own = shapely.distance(boxes, own_anchor)
        others = (shapely.distance(boxes[:, None], mate_anchors[None, :]).min(axis=1) if mate_anchors.size
                  else np.full(n, np.inf))
        hits = (np.bincount(tree.query(boxes, predicate="intersects")[0], minlength=n) if tree is not None
                else np.zeros(n, int))
        crossed = (shapely.intersects(boxes[:, None], np.array(placed, dtype=object)[None, :]).sum(axis=1)
                   if placed else np.zeros(n, int))
        far = np.where((own > reach) | (others <= own), 1000.0, 0.0)
        costs = 0.05 * np.arange(start, stop) + 100.0 * hits + 1000.0 * crossed + far
        for j, cost in enumerate(costs.tolist()):
            rank = start + j
            if best is None or cost < best[0]:
                best = (cost, rank, boxes[j])
            if cost < 0.05 * (rank + 1):  # free and by its own anchor: the nearest such
                return best[0], dataclasses.replace(text, position=spots[best[1]]), best[2]
    return best[0], dataclasses.replace(text, position=spots[best[1]]), best[2]


_ANCHOR_SHARE = {"start": 0.0, "middle": 0.5, "end": 1.0}
_DROP_SHARE = {"baseline": 0.0, "middle": 0.5, "top": 1.0}
