"""An enlarged detail (выносной элемент, ГОСТ 2.305) of a plan whose images crowd round its pole
while one of its vectors runs far out: the region round the pole drawn again at a larger scale,
its own scale stated, and the region marked on the plan by a thin circle and its numeral.

A plan is crowded round its pole (:func:`crowd_near_pole`) where at least
:data:`CROWD_COUNT` images lie within :data:`CROWD_MM` of the pole (or a quarter of the plan's
reach) at the plan's scale while the plan spans at least three times the region's radius: one
scale cannot serve it (the jaw crusher's acceleration plans: pa about 166 mm on A1, every other
point within 15 mm of π).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import shapely

from velplan.options import Language
from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Circle, Polyline, Primitive, Text
from velplan.views.base import View, bounds_of, make_view, shift
from velplan.notation import number as number_text
from velplan.views.plan import PlanSizes, layer_names, plan_title, plan_view

#: Images within this distance of the pole, mm at the plan's scale, make up its crowd.
CROWD_MM = 15.0
#: Images in the crowd that make a detail worth drawing.
CROWD_COUNT = 3
#: Enlargements of a detail (ГОСТ 2.302), the largest first.
FACTORS: tuple[float, ...] = (5.0, 4.0, 2.5, 2.0)
#: The numerals of a sheet's details, in turn.
NUMERALS: tuple[str, ...] = ("I", "II", "III", "IV", "V", "VI", "VII", "VIII")
NUMERAL = NUMERALS[0]


def crowd_near_pole(images, extent_mm: float, reach_mm: float | None = None) -> tuple[complex, float] | None:
    """(centre, radius) of the region (plan mm at the plan's scale, the pole at 0) that holds the
    crowd round the pole of a plan with `images` (target → plan mm, complex) `extent_mm` across,
    or None where no crowd calls for a detail. The crowd: the images within
    :data:`CROWD_MM` of the pole, or a quarter of the farthest image's distance where that is
    more (or within `reach_mm`, where given: a tighter crowd, whose detail may be drawn larger);
    images on the pole itself, or within a millimetre of one another, count once; the
    region: the circle round the box of the crowd and the pole, 3 mm wider for the letters."""
    z = np.array([complex(v) for v in images.values()], dtype=complex)
    z = z[np.isfinite(z)]
    if not len(z):
        return None
    reach = max(CROWD_MM, float(np.max(np.abs(z))) / 4.0) if reach_mm is None else reach_mm
    z = z[(np.abs(z) > 0.5) & (np.abs(z) <= reach)]
    if len(set(np.round(z).tolist())) < CROWD_COUNT:  # distinct places (np.unique would import numpy.ma)
        return None
    x0, x1 = min(0.0, float(np.min(z.real))), max(0.0, float(np.max(z.real)))
    y0, y1 = min(0.0, float(np.min(z.imag))), max(0.0, float(np.max(z.imag)))
    radius = 0.5 * math.hypot(x1 - x0, y1 - y0) + 3.0
    return (complex(0.5 * (x0 + x1), 0.5 * (y0 + y1)), radius) if extent_mm >= 3.0 * radius else None


def _clipped(p: Primitive, window: shapely.Polygon) -> list[Primitive]:
    """The part of `p` inside `window`: a text or a dot whole or not at all, a line cut at the
    window's edge, an arrow kept with its head where its head is inside (else its shaft)."""
    if isinstance(p, Text):
        return [p] if window.contains(label_box(p)) else []
    if isinstance(p, Circle):
        return [p] if window.contains(shapely.Point(p.centre)) else []
    if isinstance(p, Arrow):
        inside = window.intersection(shapely.LineString([p.start, p.end]))
        if inside.is_empty or inside.length < 1e-6:
            return []
        a, b = np.asarray(inside.coords[0]), np.asarray(inside.coords[-1])
        if window.contains(shapely.Point(p.end)):
            start = a if np.hypot(*(a - p.end)) > np.hypot(*(b - p.end)) else b
            return [replace(p, start=tuple(start))]
        return [Polyline(((float(a[0]), float(a[1])), (float(b[0]), float(b[1]))), p.layer, p.line)]
    if isinstance(p, Polyline):
        inside = window.intersection(shapely.LineString(p.points))
        parts = getattr(inside, "geoms", [inside])
        return [Polyline(tuple((float(x), float(y)) for x, y in g.coords), p.layer, p.line) for g in parts
                if not g.is_empty and g.geom_type == "LineString" and g.length > 1e-6]
    return []


def _letters_inside(full: View, items: list[Primitive], window: shapely.Polygon) -> tuple[set[str], list[Primitive]]:
    """(the letters of the plan `full`, at the detail's scale, whose images lie inside the
    `window`, those letters placed again inside it by their images with their leaders): by
    `place_letters`, clear of the drawn `items` (the plan's lines cut at the window, but its
    letters) and of the window's edge, each nearest its own image, else with a thin leader
    (the plan placed them for the whole plan: cut at the window, some would stand out of it, or
    nearer another image). One that finds no room inside is left out."""
    from velplan.plans.text import label_of
    from velplan.notation import subscript
    from velplan.views.letters import place_letters

    at: dict[str, list[np.ndarray]] = {}
    for target, z in full.meta["images"].items():
        if np.isfinite(z):
            at.setdefault(subscript(label_of(target)), []).append(np.asarray(full.to_view((z.real, z.imag)), float))
    letters, anchors = [], []
    for t in (p for p in full.primitives if isinstance(p, Text)):
        own = [xy for part in t.text.split(", ") for xy in at.get(part, []) if window.contains(shapely.Point(xy))]
        if own:
            letters.append(t)
            anchors.append(own[0])
    if not letters:
        return set(), []
    names = {t.text for t in letters}
    points = [xy for xys in at.values() for xy in xys if window.contains(shapely.Point(xy))]
    # every line is hard, the thin construction lines too (as the plan's own letters keep off
    # them): a letter crosses one only where no spot, with a leader or without, is clear
    hard = [shapely.LineString([p.start, p.end]) for p in items if isinstance(p, Arrow)]
    hard += [shapely.LineString(p.points) for p in items if isinstance(p, Polyline)]
    hard += [shapely.Point(p.centre).buffer(p.radius + 0.3) for p in items if isinstance(p, Circle)]
    hard.append(window.envelope.buffer(30.0).difference(window))  # the letters stay inside the circle
    others = [label_box(t).buffer(0.4) for t in items if isinstance(t, Text) and t.text not in names]
    placed, leaders = place_letters(letters, anchors, points, hard, taken=others, leader_layer=letters[0].layer)
    out: list[Primitive] = [t for t in placed if window.contains(label_box(t))]
    return names, out + [ld for ld in leaders if window.contains(shapely.Point(ld.points[1]))]


def detail_view(res, number: int, region: tuple[complex, float], factor: float, *,
                lang: Language = "ru", sizes: PlanSizes = PlanSizes(), numeral: str = NUMERAL,
                beside: bool = False) -> View:
    """The `region` (centre, radius: plan mm at the plan's scale, `crowd_near_pole`) of the
    plan of `res` at position number `number`, drawn `factor` times larger (its scale μ/factor
    written under the numeral and the enlargement, ``"I (4:1)"``, above the circle or, with
    `beside`, right of its top: a lower view), cut at a thin circle; the view's origin is the
    pole."""
    big, full, centre, r, inside = _enlarged(res, number, region, factor, lang, sizes)
    pole = np.asarray(full.origin)
    _, line_layer, text_layer = layer_names(full.meta["kind"], number)
    items = list(inside)
    items.append(Circle(tuple(centre), r, line_layer, "thin"))
    items += _titles(big, number, centre, r, factor, numeral, beside, lang, sizes, text_layer)
    return make_view(f"detail-{full.meta['kind']}-{number}", items, pad_mm=2.0, origin=tuple(pole),
                     meta={"kind": full.meta["kind"], "number": number, "scale": big.scale,
                           "factor": factor, "region": region})


def _titles(big, number: int, centre, r: float, factor: float, numeral: str, beside: bool, lang: Language,
            sizes: PlanSizes, text_layer: str) -> list[Text]:
    """The detail's two title lines, the numeral with its enlargement and the plan's scale,
    above its circle (centre, radius `r`, mm) or, with `beside`, right of its top."""
    x, top = centre[0] - r, centre[1] + r
    if beside:  # right of the circle's top
        x, top = centre[0] + r + 3.0, top - 3.0 - 1.5 * sizes.label_mm
    return [Text((x, top + 3.0 + 1.5 * sizes.label_mm), f"{numeral} ({number_text(factor, lang)}:1)",
                 text_layer, sizes.title_mm),
            Text((x, top + 3.0), plan_title(big, number, lang)[1], text_layer, sizes.label_mm)]


def least_detail_size(res, number: int, region: tuple[complex, float], factor: float, *,
                      lang: Language = "ru", sizes: PlanSizes = PlanSizes(), numeral: str = NUMERAL,
                      beside: bool = False) -> tuple[float, float]:
    """A lower bound of the width and height (mm) of `detail_view` with these arguments, known
    without drawing the plan: the box of its circle and its title lines, padded as the view
    is (all else it draws only adds to that box), less a micrometre for rounding."""
    big = res.at_scale(res.scale / factor)
    r = region[1] * factor
    x0, y0, x1, y1 = bounds_of([Circle((0.0, 0.0), r, "labels", "thin"),
                                *_titles(big, number, (0.0, 0.0), r, factor, numeral, beside, lang, sizes, "labels")])
    return x1 - x0 + 4.0 - 1e-6, y1 - y0 + 4.0 - 1e-6


#: The last detail drawn by `_enlarged`: ((its arguments), what it drew), or None.
_LAST_ENLARGED: list = [None]


def _enlarged(res, number: int, region: tuple[complex, float], factor: float, lang: Language, sizes: PlanSizes):
    """(the plan at μ/`factor`, its view, the circle's centre and radius there, mm, what
    `detail_view` draws inside it) — the same for a title above the circle and beside it, so
    kept for the next call with the same arguments (a sheet tries both in turn)."""
    args = (number, region, factor, lang, sizes)
    last = _LAST_ENLARGED[0]
    if last is not None and last[0][0] is res and last[0][1:] == args:
        return last[1]
    big = res.at_scale(res.scale / factor)
    full = plan_view(big, number, lang=lang, sizes=sizes, title=False)
    pole = np.asarray(full.origin)
    centre = pole + factor * np.array([region[0].real, region[0].imag])
    r = region[1] * factor
    window = shapely.Point(centre).buffer(r, quad_segs=32)
    items = [q for p in full.primitives for q in _clipped(p, window)]
    letters, placed = _letters_inside(full, items, window)
    inside = tuple(q for q in items if not (isinstance(q, Text) and q.text in letters)) + tuple(placed)
    drawn = (big, full, centre, r, inside)
    _LAST_ENLARGED[0] = ((res, *args), drawn)
    return drawn


def marked(view: View, region: tuple[complex, float], size_mm: float,
           numeral: str = NUMERAL) -> tuple[View, tuple[float, float]] | None:
    """(the plan `view` with its detail's `region` (`crowd_near_pole`) marked — a thin circle
    and the numeral outside it where no letter nor line is —, the shift of its drawing in
    the new box, mm): place it that much lower and to the left to keep the drawing where it was;
    None where the circle would cross a text of the plan outside the region."""
    kind, number = view.meta["kind"], view.meta["number"]
    _, line_layer, text_layer = layer_names(kind, number)
    radius_mm = region[1]
    cx, cy = view.origin[0] + region[0].real, view.origin[1] + region[0].imag
    disk = shapely.Point(cx, cy).buffer(radius_mm)
    if any(label_box(t).intersects(disk) for t in view.primitives
           if isinstance(t, Text) and ("(" in t.text or "=" in t.text or "≈" in t.text)):
        return None  # the circle would cross a text outside the region (a title, a scale, the ≈ 0 list)
    ink = ([label_box(t) for t in view.primitives if isinstance(t, Text)]
           + [shapely.LineString([p.start, p.end]) for p in view.primitives if isinstance(p, Arrow)]
           + [shapely.LineString(p.points) for p in view.primitives  # a line beside "II" reads "III"
              if isinstance(p, Polyline) and len(p.points) >= 2])
    numerals = [Text((cx + (radius_mm + 1.0) * math.cos(a), cy + (radius_mm + 1.0) * math.sin(a)), numeral,
                     text_layer, size_mm, "start" if math.cos(a) > 0.1 else "end" if math.cos(a) < -0.1 else "middle",
                     "baseline" if math.sin(a) > 0 else "top")
                for a in np.radians([45, 135, -45, -135, 90, -90, 0, 180, 30, 60, 120, 150, -30, -60, -120, -150])]
    mark = _first_clear(numerals, ink, 0.5)
    items = view.primitives + (Circle((cx, cy), radius_mm, line_layer, "thin"), mark)
    x0, y0, x1, y1 = bounds_of(items)
    dx, dy = max(-x0, 0.0), max(-y0, 0.0)  # the box grows where the circle or the numeral leave it
    return replace(view, primitives=tuple(shift(p, dx, dy) for p in items),
                   origin=(view.origin[0] + dx, view.origin[1] + dy),
                   width_mm=max(view.width_mm, x1) + dx, height_mm=max(view.height_mm, y1) + dy), (dx, dy)


#: How far the polygon of a buffer may stand off its exact distance, mm (its arcs are chords —
#: 2 % of the distance at 8 segments a quarter — and GEOS simplifies the input by 1 % of it).
_RIM_MM = 0.05


def _first_clear(texts: list[Text], ink: list, pad_mm: float) -> Text:
    """The first of `texts` whose box keeps off ``shapely.union_all(ink).buffer(pad_mm)`` (the
    first text where none does): decided by each box's exact distance from the ink, the buffer
    made only where a box stands within :data:`_RIM_MM` of its rim (the same answer; the
    union's buffer costs tens of milliseconds a plan)."""
    tree = shapely.STRtree(ink)
    grown = None
    for t in texts:
        box = label_box(t)
        near = tree.query(box, predicate="dwithin", distance=pad_mm + _RIM_MM)
        if not len(near):
            return t
        with np.errstate(divide="ignore", invalid="ignore"):  # a line of one point repeated
            nearest = float(shapely.distance(box, tree.geometries[near]).min())
        if nearest < pad_mm - _RIM_MM:
            continue
        if grown is None:
            grown = shapely.union_all(ink).buffer(pad_mm)
        if not box.intersects(grown):
            return t
    return texts[0]


__all__ = ["CROWD_COUNT", "CROWD_MM", "FACTORS", "NUMERALS", "crowd_near_pole", "detail_view", "least_detail_size",
           "marked"]
