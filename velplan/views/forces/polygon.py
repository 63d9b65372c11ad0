"""A force polygon (plan of forces): the known vectors head to tail from the pole at a
standard μF (N/mm), then the two unknown reactions found where the lines of their known
directions meet (thin construction lines through the last vertex and through the pole); the
found vectors thick. Vertices are `ForcePolygon.vertices`. What a teacher cannot measure is
written instead of drawn: a vector shorter than SHORT_VECTOR_MM is listed as ≈ 0 with its
value under the polygon; a vector that would lie along another is drawn beside it; every
reaction is written with the equation it comes from (`reaction_equations`)."""

from __future__ import annotations

import numpy as np
import shapely

from velplan.analysis.numbering import position_index
from velplan.forces.agreement import ForceAnalysis
from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Circle, Polyline, Text
from velplan.render.shapes import text_extent
from velplan.render.style import SheetStyle
from velplan.views.base import View, bounds_of, make_view, unit
from velplan.notation import MINUS, number as _num
from velplan.views.forces.anchored import kept_leader
from velplan.views.forces.arrows import arrow_obstacle
from velplan.views.forces.common import (
    ForceSizes, Sketch, anchor_of, force_text, newton, newton_metre, note_lines, number_text,
    polygon_layers, slug, title_lines, unit_vector, xy)
from velplan.views.forces.equations import reaction_equations

#: Polygon vectors shorter than this are not drawn: they are listed as ≈ 0 with their
#: values under the polygon, and the chain passes over them by a thin line, mm.
SHORT_VECTOR_MM = 3.0
#: A vector that would lie on one drawn before it is drawn beside it, this far off, mm.
OFFSET_MM = 2.5
#: The style's arrowhead length, mm; a shorter vector gets a head of half its length.
_HEAD_MM = SheetStyle().arrow_length_mm
#: Construction lines run this far past the points they join, mm.
LINE_OVERRUN_MM = 8.0


def polygon_extent(poly, position: int) -> tuple[float, float]:
    """Width and height of the polygon's vertices at position number ``position`` (1…n) at
    μF = 1 N/mm, i.e. N."""
    verts = poly.vertices(1.0)
    z = np.asarray(verts[position_index(position, len(verts))])
    z = z[np.isfinite(z)]
    return float(np.ptp(z.real)), float(np.ptp(z.imag))


def polygon_view(fa: ForceAnalysis, group: str, position: int, *, mu_f: float, lang: Language = "ru",
                 sizes: ForceSizes = ForceSizes()) -> View:
    """The force polygon of `group` (or ``"crank"``) at position number ``position`` (1…n), at
    μF (N/mm).

    Returns
    -------
    View
        ``to_view`` maps polygon mm (pole at 0) to the view's mm; ``meta["vertices"]``
        holds the drawn vertices (complex, mm from the pole), ``meta["labels"]`` the vector
        labels in drawing order.
    """
    i, number = position_index(position, len(fa.kinematics)), position
    ks = fa.kinetostatics
    mech = ks.mechanism
    poly = ks.polygons[group]
    vec_layer, line_layer, text_layer = polygon_layers(number, group)
    z = np.asarray(poly.vertices(mu_f)[i])
    names = [n for n, _ in poly.vectors] + [n for n, _ in poly.closing_vectors]
    sk = Sketch()
    _draw_construction_lines(sk, poly, z, i, line_layer)
    drawn, small = _draw_vectors(sk, names, z, len(poly.vectors), vec_layer)
    sk.items.append(Circle((0.0, 0.0), 0.7, vec_layer, "thin", "solid"))
    texts = _vector_labels(drawn, sk, text_layer, sizes.label_mm)
    items = sk.items + texts
    head = (label("force_plan_crank", lang).format(name=mech.crank.link) if group == "crank"
            else label("force_plan_group", lang).format(name=group))
    items += title_lines(items, [
        (head, sizes.title_mm),
        (f"μF = {number_text(mu_f, lang)} {newton(lang)}/{unit('mm', lang)}", sizes.label_mm)],
        text_layer)
    x0, _, x1, _ = bounds_of(items)
    width = max(x1 - x0, 40.0)  # the notes no wider than the polygon and its title
    notes = (_small_lines(small, mu_f, lang, width, sizes.label_mm)
             + [part for r in _results(fa, group, number, lang)
                for part in _broken(r, width, sizes.label_mm)])
    items += note_lines(items, notes, sizes.label_mm, text_layer)
    return make_view(f"polygon-{number}-{slug(group)}", items, pad_mm=2.0, mu=None,
                     origin=(0.0, 0.0),
                     meta={"group": group, "number": number, "index": i, "mu_f": mu_f,
                           "vertices": tuple(complex(v) for v in z),
                           "labels": tuple(names),
                           "drawn": tuple(d[0] for d in drawn),
                           "small": tuple(small)})


def _draw_construction_lines(sk: Sketch, poly, z, i: int, layer: str) -> None:
    """The lines of the two unknown directions, through the last known vertex and through the
    pole, crossing where they meet."""
    if len(poly.closing) != 2 or not np.all(np.isfinite(z)):
        return
    m = len(poly.vectors)
    x = z[m + 1]
    for through, (_, d) in ((z[m], poly.closing[0]), (z[0], poly.closing[1])):
        u = complex(d[i])
        t = ((x - through) * u.conjugate()).real
        lo, hi = min(0.0, t) - LINE_OVERRUN_MM, max(0.0, t) + LINE_OVERRUN_MM
        seg = [xy(through + u * lo), xy(through + u * hi)]
        sk.items.append(Polyline(seg, layer, "thin"))
        sk.obstacles.append(shapely.LineString(seg).buffer(0.4))


def _draw_vectors(sk: Sketch, names, z, first_closing: int, layer: str) -> tuple[list, list]:
    """The vectors head to tail, the found ones thick; those shorter than SHORT_VECTOR_MM
    left out, the chain passing over each run of them by a thin line; a vector that would
    lie on one drawn before it (the crank's R₀₁ = −R₂₁) drawn beside it. Returns (label,
    tail, head, found) of the vectors drawn and (label, N) of those left out."""
    drawn: list[tuple[str, np.ndarray, np.ndarray, bool]] = []
    small: list[tuple[str, float]] = []
    finite = [xy(v) for v in z if np.isfinite(v)]
    centre = np.mean(finite, axis=0) if finite else np.zeros(2)
    gap_from = None
    for k, name in enumerate(names):
        a, b = xy(z[k]), xy(z[k + 1])
        if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            continue
        if np.hypot(*(b - a)) < SHORT_VECTOR_MM:
            small.append((name, k))
            gap_from = a if gap_from is None else gap_from
            continue
        if gap_from is not None:
            _bridge(sk, gap_from, a, layer)
            gap_from = None
        a, b = _beside(a, b, drawn, centre)
        found = k >= first_closing
        length = float(np.hypot(*(b - a)))
        head = None if length >= 2 * _HEAD_MM else 0.5 * length  # a head shorter than the shaft
        arrow = Arrow(a, b, layer, "thick" if found else "thin", head)
        sk.items.append(arrow)
        sk.obstacles.append(arrow_obstacle(arrow))
        drawn.append((name, a, b, found))
    if gap_from is not None and finite:
        _bridge(sk, gap_from, finite[-1], layer)
    return drawn, [(name, float(abs(z[k + 1] - z[k]))) for name, k in small]


def _bridge(sk: Sketch, a, b, layer: str) -> None:
    """A thin line over the vectors left out, from `a` to `b` (nothing where they meet)."""
    if np.hypot(*(b - a)) > 0.05:
        sk.items.append(Polyline([a, b], layer, "thin"))


def _beside(a, b, drawn, centre) -> tuple[np.ndarray, np.ndarray]:
    """(tail, head) of the vector a → b, moved OFFSET_MM aside (away from the other vector,
    or from `centre` where the two are collinear) where
    more than 3 mm of it would lie within 1 mm of a vector drawn before it and nearly along
    it (within 10° of a vector it meets, 1° of another)."""
    u = unit_vector(b - a)
    n = np.array([-u[1], u[0]])
    shaft = shapely.LineString([a, b])
    for _, c, d, _ in drawn:
        w = unit_vector(d - c)
        sine = abs(float(u[0] * w[1] - u[1] * w[0]))
        shared = min(np.hypot(*(p - q)) for p in (a, b) for q in (c, d)) < 0.1
        if (sine > (0.17 if shared else 0.02)
                or shaft.intersection(shapely.LineString([c, d]).buffer(1.0)).length <= 3.0):
            continue  # at an angle (10° from a neighbour, 1° from another), or apart
        other = float(((c + d) / 2 - a) @ n)
        off = other if abs(other) > 0.05 else -float(((a + b) / 2 - centre) @ n)
        # away from the other, else from the centre; where the centre lies on the line too (a
        # polygon of two opposite vectors), to the left of a → b, not where round-off says
        side = -1.0 if off > 0.05 else 1.0
        return a + side * OFFSET_MM * n, b + side * OFFSET_MM * n
    return a, b


def _vector_labels(drawn, sk: Sketch, layer: str, size: float) -> list[Text]:
    """A label for each drawn vector beside its middle on the free side (else nearer an
    end, farther out, or on the other side), nearer its own vector than any other; the
    shortest vectors, with the fewest places, labelled first. Where every place near a
    vector is crossed, its label stands farther out with a thin leader (the leaders follow
    the labels in the list)."""
    segments = [shapely.LineString([a, b]) for _, a, b, _ in drawn]
    pts = [p for _, a, b, _ in drawn for p in (a, b)]
    centre = np.mean(pts, axis=0) if pts else np.zeros(2)
    tree = shapely.STRtree(sk.clear_of())
    boxes: list = []
    texts: dict[int, Text] = {}
    leaders: list[Polyline] = []
    for idx in sorted(range(len(drawn)), key=lambda j: segments[j].length):
        name, a, b, _ = drawn[idx]
        best = None
        for rank, text, box in _label_spots(name, a, b, centre, layer, size):
            cost = _spot_cost(rank, box, idx, segments, tree, boxes)
            if best is None or cost < best[0]:
                best = (cost, text, box)
            if cost < rank + 1:  # clean: no later place (of a higher rank) can be better
                break
        if best[0] >= 100.0:  # crossed or crowded everywhere near: beyond the crowd, with a leader
            best = _led_label(name, a, b, centre, layer, size, tree, boxes, leaders) or best
        texts[idx] = best[1]
        boxes.append(best[2].buffer(1.5))
    return [texts[j] for j in range(len(drawn))] + leaders


#: The gaps (mm) tried for a vector's label with a leader, where no place near it is clear.
LEADER_GAPS_MM = (6.5, 8.0, 10.0, 12.0, 14.0, 17.0, 20.0)


def _led_label(name: str, a, b, centre, layer: str, size: float, tree, boxes, leaders: list):
    """The first place farther out, clear of the lines and the labels, for the label of
    vector a → b: (0, label, box), its leader from the vector appended to `leaders`; None
    where none is clear."""
    for _, text, box in _label_spots(name, a, b, centre, layer, size, LEADER_GAPS_MM):
        if len(tree.query(box, predicate="intersects")) or any(box.intersects(o) for o in boxes):
            continue
        t = float(np.clip(shapely.LineString([a, b]).project(box.centroid, normalized=True), 0.3, 0.7))
        at = a + t * (b - a)
        near = shapely.shortest_line(box.buffer(0.4), shapely.Point(at)).coords[0]
        line = shapely.LineString([at, near])
        if any(line.intersects(o.buffer(-1.2)) for o in boxes):
            continue  # a leader through another label
        leaders.append(Polyline((tuple(at.tolist()), (near[0], near[1])), layer, "thin"))
        boxes.append(line.buffer(0.8))  # the later labels keep off it
        return 0.0, text, box
    return _ringed_label(name, a, b, layer, size, tree, boxes, leaders)


#: The distances (mm) from a vector's middle of the places tried all round it for its label
#: with a leader, where none beside it is clear; the directions tried at each, 15° apart.
RING_MM = (7.0, 9.0, 11.0, 13.0, 16.0, 19.0, 23.0, 28.0)
_RING_DIRECTIONS = tuple((np.cos(np.radians(15.0 * k)), np.sin(np.radians(15.0 * k))) for k in range(24))


def _ringed_label(name: str, a, b, layer: str, size: float, tree, boxes, leaders: list):
    """The clear place all round the middle of vector a → b (a short vector in a crowd, whose
    sides are crossed everywhere) whose leader from the vector crosses the fewest lines, the
    nearest of those: (0, label, box), its leader appended to `leaders`; None where none is
    clear."""
    mid, seg = (a + b) / 2, shapely.LineString([a, b])
    best = None
    for r in RING_MM:
        for c, s in _RING_DIRECTIONS:
            text = Text(tuple((mid + r * np.array([c, s])).tolist()), force_text(name), layer, size,
                        "middle", "middle")
            box = label_box(text)
            if len(tree.query(box, predicate="intersects")) or any(box.intersects(o) for o in boxes):
                continue
            t = float(np.clip(seg.project(box.centroid, normalized=True), 0.3, 0.7))
            at = a + t * (b - a)
            near = shapely.shortest_line(box.buffer(0.4), shapely.Point(at)).coords[0]
            line = shapely.LineString([at, near])
            if any(line.intersects(o.buffer(-1.2)) for o in boxes):
                continue  # a leader through another label
            start = shapely.Point(at)  # the lines at its start (its own vector's) not counted
            cost = 10.0 * sum(not tree.geometries[j].intersects(start)
                              for j in tree.query(line, predicate="intersects")) + r
            if best is None or cost < best[0]:
                best = (cost, text, box, line)
        if best is not None and best[0] <= r:  # no line crossed: no farther place is better
            break
    return kept_leader(best, leaders, boxes, layer, 0.8)


def _label_spots(name: str, a, b, centre, layer: str, size: float, gaps=(0.8, 2.0, 3.5, 5.0),
                 along=(0.5, 0.38, 0.62, 0.26, 0.74, 0.15, 0.85)):
    """(rank, label, its box) of the places tried for the label of vector a → b, the best
    first: the box's edge nearest the vector one of `gaps` (mm) from it, at the fractions
    `along` of its length."""
    u = unit_vector(b - a)
    n = np.array([-u[1], u[0]])
    out = 1.0 if float(((a + b) / 2 - centre) @ n) >= 0 else -1.0
    text = force_text(name)
    shapes = {}  # anchor → the box's corners about the text's point
    rank = 0
    for gap in gaps:
        for t in along:
            for side in (out, -out):
                m = side * n
                anchor = anchor_of(m)
                if anchor not in shapes:
                    shapes[anchor] = np.asarray(label_box(Text(
                        (0.0, 0.0), text, layer, size, anchor, "middle")).exterior.coords)
                corners = shapes[anchor]
                at = a + t * (b - a) + m * (gap + float(np.max(-(corners @ m))))
                yield (rank, Text(at, text, layer, size, anchor, "middle"),
                       shapely.Polygon(corners + at))
                rank += 1


def _spot_cost(rank: int, box, idx: int, segments, tree, boxes) -> float:
    """How bad a label's place is: over labels placed before it (worst: text over text),
    nearer another vector than its own or farther than 6 mm from it, over lines and arrows,
    crowding the labels placed before it; then its rank."""
    own = box.distance(segments[idx])
    other = min((g.distance(box) for j, g in enumerate(segments) if j != idx), default=np.inf)
    return (rank + 100.0 * len(tree.query(box, predicate="intersects"))
            + 1000.0 * sum(box.intersects(o) for o in boxes)
            + 5000.0 * sum(box.intersects(o.buffer(-1.2)) for o in boxes)
            + (1000.0 if own > 6.0 or other <= own else 0.0))


def _broken(line: str, width: float, size: float) -> list[str]:
    """An equation wider than `width` mm at `size` broken before its result:
    "R₃₅ = −(R₀₅ + P + G₅ + Φ₅) =" and "= 8449 Н"."""
    if text_extent(line, size)[0] <= width or line.count(" = ") < 2:
        return [line]
    head, result = line.rsplit(" = ", 1)
    return [head + " =", "= " + result]


def _small_lines(small, mu_f: float, lang: Language, width: float, size: float) -> list[str]:
    """The vectors left out of the drawing, with their values: "≈ 0 …: G₃ = 58,9 Н; …", in
    lines no wider than `width` mm at `size`."""
    if not small:
        return []
    head = label("force_small", lang).format(mm=number_text(SHORT_VECTOR_MM, lang),
                                             unit=unit("mm", lang))
    values = [f"{force_text(name)} = {_num(mu_f * mm, lang) if mm > 1e-6 else 0} {newton(lang)}"
              for name, mm in small]
    lines, line = [], head
    for v in values:
        if text_extent(f"{line}; {v};", size)[0] > width:
            lines.append(line if line == head else line + ";")
            line = v
        else:
            line = (head + ("" if head.endswith("：") else " ") + v if line == head
                    else f"{line}; {v}")
    return lines + [line]


def _results(fa: ForceAnalysis, group: str, number: int, lang: Language) -> list[str]:
    """The results read off the polygon, each with the equation it comes from: an outer
    reaction as the sum of its components, an inner one (and the crank's R₀₁) from the
    equilibrium of its link; M_b for the crank."""
    ks = fa.kinetostatics
    results = []
    for e in reaction_equations(fa, group, number):
        rhs = ""
        if e.terms:
            total = " + ".join(force_text(t) for t in e.terms)
            rhs = (MINUS + (f"({total})" if len(e.terms) > 1 else total)) if e.negated else total
            rhs += " = "
        results.append(f"{force_text(e.label)} = {rhs}{_num(e.value, lang)} {newton(lang)}")
    if group == "crank":
        i = position_index(number, len(fa.kinematics))
        results.append(f"{label('symbol_balancing_moment', lang)} = "
                       f"{_num(float(ks.balancing_moment[i]), lang)} {newton_metre(lang)} "
                       f"({label('method_kinetostatics', lang)})")
    return results
