"""Force arrows of a conventional length, placed as a draughtsman would: from their point or
into it, lengthened where that keeps them and their labels off what is already drawn."""

from __future__ import annotations

import numpy as np
import shapely

from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Text
from velplan.views.forces.common import anchor_of

#: Lengths tried for an arrow, in conventional lengths, the shortest first.
LENGTHS = (1.0, 1.6, 2.2, 2.8)
#: A force that would run along a link is drawn parallel to it, this far aside, mm.
BESIDE_MM = 2.0


def place_arrows(entries, length: float, obstacles=(), points=(), texts=(), *,
                 layer: str = "labels", size: float = 3.5, beside: bool = False) -> list[tuple]:
    """Force arrows of a conventional length at their points, each drawn either from its
    point (tail there) or into it (head there), and lengthened when that keeps it — and its
    label — off what is already drawn (links, other arrows, other points), as a draughtsman
    would; with `beside`, one that would still run along a link there is drawn beside it,
    parallel, BESIDE_MM off (a gravity force on a vertical link). Forces at one point in one
    direction are drawn along one line from it, each longer than the one before, so that
    every head shows.

    Parameters
    ----------
    entries : sequence of (point, unit direction, label)
        Points and directions in mm.
    length : float
        Conventional length, mm.
    obstacles : iterable of shapely geometry
        What the shafts should not run along.
    points : iterable of (x, y)
        Points the shafts should keep clear of (other than their own), mm.
    texts : iterable of Text
        Labels already written, which the new labels should keep clear of.
    layer, size : str, float
        Layer and text height of the labels.

    Returns
    -------
    list of (start, end, Text)
        The arrow and its label, beyond its free end.
    """
    fixed_parts = [o for o in obstacles if o is not None]
    marks = [np.asarray(q, float) for q in points]
    rings = [shapely.Point(q).buffer(2.5) for q in marks]  # each mark's keep-off ring, made once
    drawn: list[tuple] = []  # (point, direction, orientation, span, geometry)
    boxes = [label_box(t).buffer(0.5) for t in texts]
    out: dict[int, tuple] = {}
    for idx in _stacking_order(entries):
        p, u, text = entries[idx]
        p, u = np.asarray(p, float), np.asarray(u, float)
        near = [ring for q, ring in zip(marks, rings) if np.hypot(*(q - p)) > 1.0]
        # a force with an opposite one at its point leaves the side it points away from to it
        facing = any(np.hypot(*(np.asarray(q, float) - p)) < 0.5
                     and float(np.asarray(w, float) @ u) < -0.995 for q, w, _ in entries)
        a, b, k, span, tag = _best_arrow(p, u, text, length, fixed_parts + near, drawn, boxes,
                                         layer, size, beside, facing)
        out[idx] = (a, b, tag)
        drawn.append((p, u, k, span, shapely.LineString([a, b]).buffer(0.8)))
        boxes.append(label_box(tag).buffer(0.5))
    return [out[idx] for idx in range(len(entries))]


def _stacking_order(entries) -> list[int]:
    """Indices of `entries`, those that share a point and a direction with others first (they
    stack along one line), so that a lone opposite force finds the other side taken."""
    pts = [np.asarray(e[0], float) for e in entries]
    dirs = [np.asarray(e[1], float) for e in entries]
    mates = [sum(1 for q, w in zip(pts, dirs) if np.hypot(*(q - p)) < 0.5 and float(w @ u) > 0.995)
             for p, u in zip(pts, dirs)]
    return sorted(range(len(entries)), key=lambda j: (-mates[j], j))


def _best_arrow(p, u, text: str, length: float, lines: list, drawn: list, boxes: list,
                layer: str, size: float, beside: bool = False, facing: bool = False) -> tuple:
    """(start, end, orientation, span, label) of the arrow at `p` along `u` that runs least
    along `lines` and the arrows `drawn` and keeps its label clear, shorter ones preferred."""
    best = None
    side = np.array([-u[1], u[0]]) * BESIDE_MM
    fixed = np.array(lines, dtype=object)
    shapes: dict = {}  # a label's box about its point, by anchor
    # every part of a cost is ≥ 0: a candidate whose cost without the parts not yet known
    # cannot beat the best is passed over unmeasured (the same choice, sooner)
    for step, mult in enumerate(LENGTHS):
        if best is not None and 3.0 * step >= best[0] - 1e-9:
            break  # each longer arrow costs 3 more: none of the rest can win
        span = length * mult
        arrows = [geom for q, w, kk, sp, geom in drawn
                  if not (np.hypot(*(q - p)) < 0.5 and float(w @ u) > 0.995 and kk == 0
                          and span >= sp + 0.45 * length)]
        # an opposite force at the same point: along it, one of the two heads would be lost
        arrows += [geom for q, w, kk, sp, geom in drawn
                   if np.hypot(*(q - p)) < 0.5 and float(w @ u) < -0.995] * 3
        moving = np.array(arrows, dtype=object)
        crowd = np.array(lines + arrows + boxes, dtype=object)
        for k, (a0, b0) in enumerate(((p, p + u * span), (p - u * span, p))):
            along = 0.0
            for shift, extra in ((0.0, 0.0), (1.0, 4.0), (-1.0, 4.0))[:3 if beside else 1]:
                if shift and along <= 0.3 * span:
                    break  # on its point it runs along no link: not beside it
                a, b = a0 + shift * side, b0 + shift * side
                turn = (0.01 + (20.0 if facing else 0.0)) * k
                if (best is not None and (shift or not beside)
                        and 0.0 + 3.0 * step + 0.0 + 0.0 + turn + extra >= best[0] - 1e-9):
                    continue  # (on its point beside the links, its run along them is still wanted)
                shaft = shapely.LineString([a, b])
                over = _run_along(shaft, fixed)
                along = along if shift else over
                if shift and over > 0.3 * span:
                    continue  # beside the point only where that clears it
                if best is not None and over + 3.0 * step + 0.0 + 0.0 + turn + extra >= best[0] - 1e-9:
                    continue
                over += 3.0 * _run_along(shaft, moving)
                free, out_dir = (b, u) if k == 0 else (a, -u)
                near = a + (p - a0)  # the shaft's point level with the force's point
                for spot, tag in enumerate(_label_spots(near, free, out_dir, text, layer, size)):
                    if best is not None and over + 3.0 * step + 0.0 + 0.8 * spot + turn + extra >= best[0] - 1e-9:
                        break  # the later spots cost more still
                    if tag.anchor not in shapes:
                        shapes[tag.anchor] = np.asarray(label_box(Text(
                            (0.0, 0.0), text, layer, size, tag.anchor, "middle")).exterior.coords)
                    box = shapely.Polygon(shapes[tag.anchor] + np.asarray(tag.position, float))
                    crowded = bool(crowd.size) and bool(shapely.intersects(box, crowd).any())
                    cost = over + 3.0 * step + (5.0 if crowded else 0.0) + 0.8 * spot + turn + extra
                    if best is None or cost < best[0] - 1e-9:
                        best = (cost, a, b, k, span, tag)
    return best[1:]


def _run_along(shaft, shapes) -> float:
    """How far `shaft` runs inside the `shapes` (an array of geometries), mm, summed."""
    if not shapes.size:
        return 0.0
    hit = shapes[shapely.intersects(shaft, shapes)]
    return float(shapely.length(shapely.intersection(shaft, hit)).sum()) if hit.size else 0.0


def arrow_obstacle(a: Arrow):
    """What an arrow's shaft covers, or None for an arrow of no length."""
    if a.length < 1e-9:
        return None
    return shapely.LineString([a.start, a.end]).buffer(0.6)


def _label_spots(point, free, u, text: str, layer: str, size: float) -> list[Text]:
    """Where an arrow's label may go: beyond its free end, else beside the shaft near the
    free end (at most 3 mm back from it), on either side."""
    point, free = np.asarray(point, float), np.asarray(free, float)
    out = [_end_label(free, u, text, layer, size)]
    near = free - u * min(0.3 * float(np.hypot(*(free - point))), 3.0)
    for side in (1.0, -1.0):
        n = side * np.array([-u[1], u[0]])
        out.append(Text(near + n * (1.0 + 0.6 * size), text, layer, size, anchor_of(n), "middle"))
    return out


def _end_label(at, u, text: str, layer: str, size: float) -> Text:
    """A label beyond the free end `at` of an arrow pointing along `u` there."""
    gap = 1.0 + (0.55 * size if anchor_of(u) == "middle" else 0.3 * size)
    return Text(np.asarray(at, float) + u * gap, text, layer, size, anchor_of(u), "middle")
