"""Views of the machine dynamics (`velplan.dynamics`): curves over the crank's travel,
Wittenbauer's energy–mass diagram with its tangents, the flywheel's section with its
dimensions and the table of results.

Every view draws arrays it is given (`Dynamics.curves`, `Dynamics.table`, a `Wittenbauer`
of the chosen size); nothing here solves. Layers: ``"dynamics"`` (curves and axes),
``"dynamics-lines"`` (construction lines: tangents, projections), ``"dynamics-labels"``
(text), ``"flywheel"`` and ``"table"``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
import shapely

from velplan.analysis.numbering import position_number
from velplan.notation import MINUS
from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Primitive, Text
from velplan.render.shapes import DESCENDER_DEPTH
from velplan.render.style import LineType
from velplan.views.base import (
    View, axis_numbers_clear, fixed, indexed, make_view, number, place_labels, power_of_ten, unit)
from velplan.views.diagram import standard_up
from velplan.views.forces.anchored import place_anchored
from velplan.views.table import grid_table, table_title

LAYER, LINES, LABELS = "dynamics", "dynamics-lines", "dynamics-labels"

KL_OFFSET_MM = -10.0
"""Where the dimension of Wittenbauer's segment kl runs, from the ΔT axis, mm."""


@dataclass(frozen=True)
class Series:
    """One curve of a panel: values at the panel's travels, its line and its name."""

    values: np.ndarray
    line: LineType
    name: str


@dataclass(frozen=True)
class DynamicsSizes:
    """Text heights, mm."""

    title_mm: float = 3.5
    label_mm: float = 2.5


def nice_step(span: float, count: int = 5) -> float:
    """A 1, 2, 2.5 or 5 × 10ᵏ step that divides ``span`` into about ``count`` parts."""
    if not span > 0:
        return 1.0
    raw = span / count
    e = math.floor(math.log10(raw))
    for m in (1.0, 2.0, 2.5, 5.0, 10.0):
        if m * 10.0**e >= raw * (1 - 1e-12):
            return m * 10.0**e
    return 10.0 ** (e + 1)


def _ticks(lo: float, hi: float, step: float) -> np.ndarray:
    k0, k1 = math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9)
    return np.arange(k0, k1 + 1) * step


def curve_panel(name: str, travel: np.ndarray, series: Sequence[Series], *, cycle: float,
                positions: int, length_mm: float, height_mm: float, title: str,
                ordinate: str, unit_text: str, lang: Language, sizes: DynamicsSizes = DynamicsSizes(),
                base: float = 0.0, notes: Sequence[str] = (), marks: Sequence[tuple[float, float, str]] = (),
                base_label: str = "", mu: float | None = None, mu_symbol: str = "μ", names: bool = True,
                measured: bool = False) -> View:
    """Curves over the crank's travel, as a diagram of a course sheet.

    Parameters
    ----------
    travel : ndarray
        Crank travel from position 1 of the curves' points, rad (0 … ``cycle``).
    series : sequence of Series
        The curves; the ordinate of a value v is (v − ``base``)/μ.
    cycle : float
        Travel the φ axis spans, rad (its length is ``length_mm``: μφ = cycle/length).
    positions : int
        Positions per turn marked (and numbered) on the φ axis.
    height_mm : float
        Largest span of the ordinates, mm: μ is the standard scale keeping it within.
    mu : float, optional
        The ordinate's scale, units per mm, instead of the one ``height_mm`` gives.
    base : float
        The value on the φ axis (ω_m for the speed, else 0), units of the values.
    base_label : str
        What the φ axis is labelled with where it meets the ordinate axis when ``base`` is
        not 0 (``"ω_{m}"``; the value of ``base`` when empty). The ticks are round values of
        the ordinate itself (8.2, 8.3, …), not steps from ``base``.
    marks : sequence of (travel rad, value, text)
        Points marked with a dot and a label (the extremes of ω).
    names : bool
        Whether the curves and the marks are named (a panel only measured while a layout is
        sought goes without: placing the names is most of its cost).
    mu_symbol : str
        The ordinate scale's symbol (``"μ_{M}"``).
    measured : bool
        A trial only measured: each curve stands as the diagonal of its box (the same size,
        scale and meta as the drawing, without carrying every point of the curves through).

    A thin curve that never leaves the φ axis, or another curve, by more than
    :data:`COINCIDE_MM` is not drawn: it is listed under the title as ≈ 0, or named with the
    curve it lies on ("M_{r} ≈ M_{Fc}"). Each curve's name stands where the curve is farthest
    from the other lines, nearer to it than to any other curve, or joined to it by a leader.
    """
    top_v, low_v = _extent(series, base)
    mu = mu or ordinate_scale(series, base, height_mm)
    series, merged_notes = _merged(series, base, mu, unit_text, lang)
    notes = list(notes) + merged_notes
    mu_phi = cycle / length_mm
    L = length_mm
    top, bottom = max(top_v / mu, 5.0), min(low_v / mu, 0.0)
    items: list[Primitive] = []
    size = sizes.label_mm
    items.append(Arrow((0.0, 0.0), (L + 8.0, 0.0), LAYER, "thin", 3.0, 1.0))
    items.append(Arrow((0.0, bottom - 3.0), (0.0, top + 6.0), LAYER, "thin", 3.0, 1.0))
    items.append(Text((L + 9.0, -1.0), "φ", LABELS, size, "start", "top"))
    # the ordinate's name centred over its arrow's tip, clear of the curves and their names:
    # the axis needs no margin for it beyond its ticks' numbers
    items.append(Text((0.0, top + 7.0), f"{ordinate}, {unit_text}", LABELS, size, "middle", "baseline"))
    # positions on the φ axis
    count = int(round(positions * cycle / (2 * math.pi)))
    every = max(1, int(math.ceil(positions / 12)))
    for k in range(count + 1):
        x = k * L / count
        items.append(Polyline([(x, -1.0), (x, 1.0)], LAYER, "thin"))
        if k % every == 0:
            items.append(Text((x, -1.8), str(position_number(k % positions)), LABELS, 0.8 * size if size > 2.5 else size,
                              "middle", "top"))
    # ordinate ticks at round values of the ordinate, clear of the φ axis's own label
    items += _ordinate_ticks(bottom, top, mu, base, base_label, lang, size)
    # the curves
    lines, named, curves = [], [], []
    x = np.asarray(travel, float) / mu_phi
    for s in series:
        v = np.asarray(s.values, float)
        ok = np.isfinite(v)
        if ok.sum() < 2:
            continue
        xy = np.column_stack([x[ok], (v[ok] - base) / mu])
        curves.append((Polyline(xy, LAYER, s.line), xy))
        items.append(curves[-1][0])
        lines.append(shapely.LineString(xy))
        if s.name:
            named.append((s.name, xy, len(lines) - 1))
    axes = [shapely.LineString([(0, 0), (L + 8, 0)]), shapely.LineString([(0, bottom - 3), (0, top + 6)])]
    # each curve named where it stands apart from the other lines, the extremes of ω at their dots
    dots = [(t / mu_phi, (v - base) / mu, text) for t, v, text in marks]
    items = axis_numbers_clear(items, [np.asarray(ln.coords) for ln in lines])
    if measured:  # the same bounds: a box's corners are the curve's least and greatest x and y
        boxes = {id(p): Polyline([tuple(xy.min(axis=0).tolist()), tuple(xy.max(axis=0).tolist())], p.layer, p.line)
                 for p, xy in curves}
        items = [boxes.get(id(p), p) for p in items]
    if names:
        items = _named(items, lines, named, dots, axes, L, size)
    else:
        items += [Circle((px, py), 0.7, LAYER, "thin", "solid") for px, py, _ in dots]
    # title, scales and notes above the plot
    per_mm = f"({unit_text})/{unit('mm', lang)}" if "/" in unit_text else f"{unit_text}/{unit('mm', lang)}"
    scale = (f"{mu_symbol} = {number(mu, lang)} {per_mm};  μ_{{φ}} = {number(mu_phi, lang)} "
             f"{unit('rad/mm', lang)} ({number(math.degrees(mu_phi), lang, 3)}°/{unit('mm', lang)})")
    text_lines = [scale] + list(notes)
    y = top + 8.0 + 1.6 * size * len(text_lines)
    items.append(Text((0.0, y + 1.8 * size), title, LABELS, sizes.title_mm))
    for k, line in enumerate(text_lines):
        items.append(Text((0.0, y - 1.6 * size * k), line, LABELS, size))
    return make_view(name, items, pad_mm=2.0, meta={"mu": mu, "mu_phi": mu_phi, "base": base,
                                                    "span_mm": (top_v - low_v) / mu,
                                                    "curves": {text: xy for text, xy, _ in named},
                                                    "named": tuple([(text, xy) for text, xy, _ in named]
                                                                   + [(text, np.array([[x, y]])) for x, y, text in dots])})


def _extent(series: Sequence[Series], base: float) -> tuple[float, float]:
    """The highest value of `series` above `base` and the lowest below it (0 at least, at most)."""
    vals = np.concatenate([np.asarray(s.values, float)[np.isfinite(s.values)] for s in series] or [np.zeros(1)])
    top_v = max(float(vals.max()) - base, 0.0) if vals.size else 0.0
    low_v = min(float(vals.min()) - base, 0.0) if vals.size else 0.0
    return top_v, low_v


def ordinate_scale(series: Sequence[Series], base: float, height_mm: float) -> float:
    """The standard ordinate scale (units per mm) that `curve_panel` draws `series` about
    `base` at to keep their span within `height_mm`."""
    top_v, low_v = _extent(series, base)
    return standard_up(max(top_v - low_v, 1e-12 * max(1.0, abs(base))) / height_mm)


def _named(items: list, lines: list, named, marks, axes: list, length: float, size: float) -> list:
    """`items` with the curves' names (`named`: (name, points mm, index in `lines`)) where each
    stands apart (`_name_at`), with their leaders, and the `marks` ((x, y) mm, text): a dot and
    its label; the labels kept by what they name (`place_anchored`)."""
    names: list[Text] = []
    anchors: list = []
    kinds: list[str] = []
    led: list[Text] = []
    leaders: list = []
    obstacles = lines + axes + _text_boxes(items)
    written_boxes = [label_box(t) for t in items if isinstance(t, Text)]  # the leaders added are no texts
    written = [b.buffer(size) for b in written_boxes]
    for text, xy, i in named:
        # a name keeps a letter's height off the numbers and names already written: "4M_{д}" reads as one
        new = [label_box(t) for t in names + led if isinstance(t, Text)]
        spot, leader = _name_at(text, xy, [ln for j, ln in enumerate(lines) if j != i] + axes[:1],
                                lines + axes + leaders + written + [b.buffer(size) for b in new], length, size,
                                written_boxes + new)
        if leader is not None:  # placed for good, with its leader
            led.append(spot)
            items = items + [leader]
            leaders.append(shapely.LineString(leader.points))
            continue
        names.append(spot)
        anchors.append(lines[i])
        kinds.append("curve")
    items = list(items)
    for px, py, text in marks:
        items.append(Circle((px, py), 0.7, LAYER, "thin", "solid"))
        names.append(Text((px + 1.5, py + (1.5 if py >= 0 else -1.5 - size)), text, LABELS, size, "start",
                          "baseline"))
        anchors.append(shapely.Point(px, py))
        kinds.append("mark")
    # the lines as drawn strokes (`place_anchored` counts one entering a box as through its letters)
    strokes = [o.buffer(STROKE_MM) if o.geom_type == "LineString" else o for o in obstacles + leaders]
    return items + led + place_anchored(names, anchors, kinds, strokes + [label_box(t) for t in led],
                                        leader_layer=LABELS)


#: The half-width, mm, a curve or axis is kept off as when a name is moved clear of it: a line
#: grazing a name's box over a millimetre or more reads as crossing it.
STROKE_MM = 0.45


#: A thin curve within this of the φ axis, or of another curve, all along reads as that line, mm.
COINCIDE_MM = 1.0


def _merged(series: Sequence[Series], base: float, mu: float, unit_text: str,
            lang: Language) -> tuple[list[Series], list[str]]:
    """The series to draw at `mu` (units per mm; the φ axis at `base`) and the notes of those
    left out: a thin named curve within :data:`COINCIDE_MM` of the φ axis all along is listed
    as ≈ 0 with its largest value; one within it of a thick or dashed curve is named with it."""
    out: list[Series | None] = list(series)
    notes: list[str] = []
    for i, s in enumerate(series):
        v = np.asarray(s.values, float) - base
        ok = np.isfinite(v)
        if s.line != "thin" or not s.name or ok.sum() < 2:
            continue
        if np.max(np.abs(v[ok])) <= COINCIDE_MM * mu:
            out[i] = None
            notes.append(f"{s.name} ≈ 0 (|{s.name}| ≤ {number(float(np.max(np.abs(v[ok]))), lang, 2)} {unit_text})")
            continue
        for k, host in enumerate(out):
            if host is None or host.line == "thin" or not host.name:
                continue
            w = np.asarray(host.values, float) - base
            if np.all(np.isfinite(w[ok])) and np.max(np.abs(v[ok] - w[ok])) <= COINCIDE_MM * mu:
                out[k] = Series(host.values, host.line, f"{host.name} ≈ {s.name}")
                out[i] = None
                break
    return [s for s in out if s is not None], notes


def _name_at(text: str, xy: np.ndarray, others: list, obstacles: list, length: float,
             size: float, texts: Sequence = ()) -> tuple[Text, Polyline | None]:
    """The name `text` of the curve `xy` (mm) beside a point where the curve stands apart (up to
    8 mm) from the `others` lines and far from the φ axis: of those points, best first, the
    first where the name, above or below the curve, meets none of the `obstacles` (lines and
    text boxes), stays within the axis's `length` and is nearer the curve than the `others`;
    else a little away with a leader (`_led_name`), else beside the best point, on the side away
    from the nearest other line; the name and its leader (or None). A leader crosses none of
    the `texts` (boxes)."""

    width = float(np.ptp(np.asarray(label_box(Text((0.0, 0.0), text, LABELS, size)).exterior.coords)[:, 0]))
    own = shapely.LineString(xy)
    apart = _apart(xy, others, 8.0)
    score = 2.0 * apart + 0.1 * np.abs(xy[:, 1])
    score[(xy[:, 0] < 3.0) | (xy[:, 0] + 1.5 + width > length)] -= 100.0
    field = shapely.STRtree(obstacles) if obstacles else None
    order = np.argsort(-score, kind="stable")
    for j in order[:: max(1, len(order) // 240)][:120]:
        px, py = (float(c) for c in xy[j])
        for dy in (1.5, -1.5 - size):
            cand = Text((px + 1.5, py + dy), text, LABELS, size, "start", "baseline")
            box = label_box(cand)
            if field is not None and len(field.query(box.buffer(0.3), predicate="intersects")):
                continue
            d = box.distance(own)
            if d <= 3.0 and all(box.distance(ln) > d for ln in others):
                return cand, None
    led = _led_name(text, xy, order, others, field, size, texts)
    if led is not None:
        return led
    px, py = (float(c) for c in xy[int(order[0])])
    up = min((float(shapely.distance(shapely.Point(px, py + 3.0), ln)) for ln in others), default=np.inf)
    down = min((float(shapely.distance(shapely.Point(px, py - 3.0), ln)) for ln in others), default=np.inf)
    return Text((px + 1.5, py + 1.5 if up >= down else py - 1.5 - size), text, LABELS, size, "start", "baseline"), None


def _apart(xy: np.ndarray, others: list, cap: float) -> np.ndarray:
    """The distance of each point of `xy` (mm) to the nearest of the `others` lines, at most
    `cap` mm, as shapely measures it: of each line's segments that may be within `cap` of a
    point (`_near_segments`), those that plain arithmetic puts within :data:`_NEAR_TOL` mm of
    the nearest are measured by shapely (the point-to-segment distances a whole line's is the
    least of: the same numbers, for a fraction of the work)."""
    apart = np.full(len(xy), cap)
    for ln in others:
        coords = shapely.get_coordinates(ln)
        if len(coords) < 3:
            apart = np.minimum(apart, shapely.distance(shapely.points(xy), ln))
            continue
        i, j = _near_segments(xy, coords, cap)
        rough = _segment_distance(xy[i], coords[j], coords[j + 1])
        least = np.full(len(xy), np.inf)
        np.minimum.at(least, i, rough)
        keep = (rough <= least[i] + _NEAR_TOL) & (rough < cap + _NEAR_TOL)
        i, j = i[keep], j[keep]
        segments = shapely.linestrings(np.stack([coords[j], coords[j + 1]], axis=1))
        exact = shapely.distance(shapely.points(xy[i]), segments)
        np.minimum.at(apart, i, exact)
    return apart


def _near_segments(xy: np.ndarray, coords: np.ndarray, cap: float) -> tuple[np.ndarray, np.ndarray]:
    """(point, segment) index pairs holding, for each point of `xy`, every segment of the line
    through `coords` within `cap` mm of it, and more. A line whose x never decreases (a curve
    over the travel) gives each point the segments across from it within the distance to the
    one at its x; another line, those whose boxes come within `cap`."""
    x = coords[:, 0]
    if not np.all(x[1:] >= x[:-1]):
        near = shapely.box(xy[:, 0] - cap, xy[:, 1] - cap, xy[:, 0] + cap, xy[:, 1] + cap)
        segments = shapely.linestrings(np.stack([coords[:-1], coords[1:]], axis=1))
        i, j = shapely.STRtree(segments).query(near)
        return i, j
    k = np.clip(np.searchsorted(x, xy[:, 0]) - 1, 0, len(x) - 2)
    reach = np.minimum(_segment_distance(xy, coords[k], coords[k + 1]) + _NEAR_TOL, cap + _NEAR_TOL)
    lo = np.searchsorted(x[1:], xy[:, 0] - reach, "left")
    hi = np.searchsorted(x[:-1], xy[:, 0] + reach, "right")
    # a segment whose heights all lie more than `reach` above or below the point is not within
    # it: points with no other segment across from them are passed over whole
    y = coords[:, 1]
    low, high = np.minimum(y[:-1], y[1:]), np.maximum(y[:-1], y[1:])
    bounds = np.column_stack([np.minimum(lo, len(low)), np.minimum(hi, len(low))]).ravel()
    lowest = np.minimum.reduceat(np.append(low, np.inf), bounds)[0::2]
    highest = np.maximum.reduceat(np.append(high, -np.inf), bounds)[0::2]
    counts = np.where((hi > lo) & (lowest <= xy[:, 1] + reach) & (highest >= xy[:, 1] - reach), hi - lo, 0)
    i = np.repeat(np.arange(len(xy)), counts)
    j = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts - lo, counts)
    py, r = xy[i, 1], reach[i]
    near = (low[j] <= py + r) & (high[j] >= py - r)
    return i[near], j[near]


_NEAR_TOL = 1e-6
"""How far (mm) plain arithmetic's distance from a point to a segment may be from shapely's:
far more than the round-off of either (≈ 10⁻¹³ mm on a sheet)."""


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The distance of each point `p` (n × 2, mm) to its segment `a`–`b`, mm."""
    px, py, ax, ay = p[:, 0], p[:, 1], a[:, 0], a[:, 1]
    abx, aby = b[:, 0] - ax, b[:, 1] - ay
    len2 = abx * abx + aby * aby
    t = np.clip(((px - ax) * abx + (py - ay) * aby) / np.where(len2 > 0.0, len2, 1.0), 0.0, 1.0)
    return np.hypot(px - ax - t * abx, py - ay - t * aby)


def _led_name(text: str, xy: np.ndarray, order, others: list, field, size: float, texts: Sequence = ()):
    """The name `text` of the curve `xy` a little away from it, on a clear spot, joined to the
    curve's point (of `order`, best first) by a thin leader that crosses no other curve
    (`others`, the φ axis last) nor a text of `texts` (boxes): (the name, its leader), or None."""
    crossed = list(others[:-1]) + [b.buffer(0.3) for b in texts]
    curves = shapely.STRtree(crossed) if crossed else None
    for j in order[:: max(1, len(order) // 120)][:60]:
        px, py = (float(c) for c in xy[j])
        for r in (4.0, 6.0, 8.0, 10.0, 12.0):
            for dx, dy in ((0.7, 0.7), (0.7, -0.7), (0.0, 1.0), (0.0, -1.0), (-0.7, 0.7), (-0.7, -0.7)):
                cand = Text((px + r * dx, py + r * dy - (size if dy < 0 else 0.0)), text, LABELS, size,
                            "start" if dx >= 0 else "end", "baseline")
                box = label_box(cand)
                if field is not None and len(field.query(box.buffer(0.3), predicate="intersects")):
                    continue
                leader = shapely.shortest_line(shapely.Point(px, py), box)
                if curves is not None and len(curves.query(leader, predicate="intersects")):
                    continue
                (x0, y0), (x1, y1) = leader.coords
                return cand, Polyline([(x0, y0), (x1, y1)], LABELS, "thin")
    return None


def _text_boxes(items) -> list:
    """The boxes of the texts among `items`: the curves' names are placed clear of the
    numbers and titles already written."""
    from velplan.render.layout import label_box

    return [label_box(t) for t in items if isinstance(t, Text)]


#: An ordinate axis numbers at least this many ticks where its height allows.
MIN_NUMBERED_TICKS = 3
#: The least distance between two ticks of an ordinate axis, mm (2.5 mm numbers and a gap).
TICK_GAP_MM = 4.5


def _finer_step(step: float) -> float:
    """The step of the 1, 2, 2.5, 5 × 10ᵏ series next below `step`."""
    e = math.floor(math.log10(step) + 1e-9)
    m = round(step / 10.0**e, 6)
    lower = [c for c in (1.0, 2.0, 2.5, 5.0) if c < m - 1e-9]
    return (lower[-1] if lower else 5.0 / 10.0) * 10.0**e


def _tick_step(lo: float, hi: float, mu: float, base: float, clear: float) -> float:
    """The step of the ordinate's ticks: the largest of the 1, 2, 2.5, 5 series from
    `nice_step` down that numbers :data:`MIN_NUMBERED_TICKS` ticks (none within `clear` mm of
    the φ axis at `base`) with ticks :data:`TICK_GAP_MM` apart, else the one numbering most."""
    step = nice_step(hi - lo)
    best = (-1, step)
    while True:
        count = sum(abs(v - base) / mu >= clear for v in _ticks(lo, hi, step))
        if count >= MIN_NUMBERED_TICKS:
            return step
        if count > best[0]:
            best = (count, step)
        finer = _finer_step(step)
        if finer / mu < TICK_GAP_MM - 1e-9:
            return best[1]
        step = finer


def _ordinate_ticks(bottom: float, top: float, mu: float, base: float, base_label: str, lang: Language,
                    size: float) -> list[Primitive]:
    """Ticks and values of an ordinate axis drawn from `bottom` to `top` mm at `mu` units per mm
    whose zero is the value `base`: round values (`_tick_step` apart, to the step's decimals);
    where `base` is not 0, the φ axis's label (`base_label`, else the value) and no tick
    within a text height of it."""
    lo, hi = base + bottom * mu, base + top * mu
    clear = 1e-9 if base == 0 else 1.5 * size
    step = _tick_step(lo, hi, mu, base, max(clear, 1e-6))
    decimals = max(0, -math.floor(math.log10(step) + 1e-9) + (1 if f"{step:.3g}".rstrip("0").endswith("25") else 0))
    items: list[Primitive] = []
    for v in _ticks(lo, hi, step):
        y = (v - base) / mu
        if abs(y) >= clear:
            items.append(Polyline([(-1.0, y), (1.0, y)], LAYER, "thin"))
            items.append(Text((-1.8, y), fixed(v, lang, decimals), LABELS, 0.8 * size if size > 2.5 else size,
                              "end", "middle"))
    if base != 0:
        items.append(Text((-1.8, 0.0), base_label or number(base, lang, 4), LABELS, size, "end", "middle"))
    return items


def wittenbauer_view(w, curve_J: np.ndarray, curve_T: np.ndarray, points: Sequence[tuple[float, float]], *,
                     omega_mean: float, delta: float, lang: Language, sizes: DynamicsSizes = DynamicsSizes(),
                     numbers: bool = True) -> View:
    """Wittenbauer's energy–mass diagram: ΔT against the variable inertia J at the scales of
    ``w`` (a `velplan.dynamics.flywheel.Wittenbauer`), the positions numbered on the curve,
    the tangents at ψ_max and ψ_min to the ΔT axis, the segment kl they cut and J_I from it.

    Parameters
    ----------
    curve_J, curve_T : ndarray
        The closed curve: J (kg·m²) and ΔT (J) at fine travels over the cycle.
    points : sequence of (J, ΔT)
        The numbered positions.

    Returns
    -------
    View
        ``meta["marks"]``: (text, point in the view's content mm) of the letters k, l and the
        positions' numbers.
    """
    mJ, mT = w.mu_J, w.mu_T
    size = sizes.label_mm
    x, y = np.asarray(curve_J) / mJ, np.asarray(curve_T) / mT
    kx, ky = 0.0, w.intercept_max / mT
    lx, ly = 0.0, w.intercept_min / mT
    tmax = (w.touch_max[0] / mJ, w.touch_max[1] / mT)
    tmin = (w.touch_min[0] / mJ, w.touch_min[1] / mT)
    ends: dict[str, tuple[float, float]] = {}
    for mark, (ax, ay), (tx, ty) in (("k", (kx, ky), tmax), ("l", (lx, ly), tmin)):
        ex = tx + 10.0
        ends[mark] = (ex, ay + (ty - ay) * ex / tx if tx > 0 else ay)
    ey = [e[1] for e in ends.values()]
    right = max(float(x.max()), tmax[0], tmin[0]) + 12.0
    top = max(float(y.max()), ky, 0.0, *ey) + 10.0
    bottom = min(float(y.min()), ly, 0.0, *ey) - 6.0
    items: list[Primitive] = [
        Arrow((0.0, 0.0), (right, 0.0), LAYER, "thin", 3.0, 1.0),
        Arrow((0.0, bottom), (0.0, top), LAYER, "thin", 3.0, 1.0),
        Text((right + 1.0, -1.0), f"J, {unit('kg·m²', lang)}", LABELS, size, "start", "top"),
        Text((0.0, top + 1.0), f"ΔT, {unit('J', lang)}", LABELS, size, "middle", "baseline"),
        Polyline(np.column_stack([x, y]), LAYER, "thick"),
    ]
    names = []
    numbered = _numbered(points, mJ, mT)  # coincident positions under one label
    for _, p in numbered:
        items.append(Circle(p, 0.6, LAYER, "thin", "solid"))
    marked = [Text((px + 1.2, py + 1.2), t, LABELS, size, "start", "baseline") for t, (px, py) in numbered]
    # the tangents: from the ΔT axis through the touch points and a little beyond
    for (ax, ay), (tx, ty), psi, mark in (((kx, ky), tmax, w.psi_max_deg, "k"), ((lx, ly), tmin, w.psi_min_deg, "l")):
        ex, ey = ends[mark]
        items.append(Polyline([(ax, ay), (ex, ey)], LINES, "thin"))
        items.append(Circle((ax, ay), 0.7, LAYER, "thin", "solid"))
        items.append(Circle((tx, ty), 0.7, LAYER, "thin", "solid"))
        # beside the ΔT axis, never on it: k above its extension line, between the axis and the
        # dimension kl (the tangent leaves k up and to the right); l to the right of its point,
        # hung below its level, so under its rising tangent however flat (the curve lies above
        # that tangent), and off the axis's tail (an upright l beside a parallel line reads as
        # a tick)
        if mark == "k":
            # its box (descender depth included) 0.5 mm clear of the extension line it stands on
            items.append(Text((0.45 * KL_OFFSET_MM, ay + 0.5 + DESCENDER_DEPTH * sizes.title_mm), mark, LABELS,
                              sizes.title_mm, "middle", "baseline"))
        else:
            marked.append(Text((4.0, ay - 1.0), mark, LABELS, sizes.title_mm, "start", "top"))
        sym = indexed("ψ", "max" if mark == "k" else "min")
        names.append(Text((ex + 1.0, ey), f"{sym} = "
                          f"{number(psi, lang, 4)}°", LABELS, size, "start", "middle"))
    # the segment kl, dimensioned beside the ΔT axis
    dx = KL_OFFSET_MM
    items.append(Polyline([(0.0, ky), (dx - 2.0, ky)], LINES, "thin"))
    items.append(Polyline([(0.0, ly), (dx - 2.0, ly)], LINES, "thin"))
    mid = 0.5 * (ky + ly)
    items.append(Arrow((dx, mid), (dx, ky), LINES, "thin", 2.5, 0.8))
    items.append(Arrow((dx, mid), (dx, ly), LINES, "thin", 2.5, 0.8))
    items.append(Text((dx - 1.0, mid), f"kl = {number(w.segment_drawn_mm, lang, 4)} {unit('mm', lang)}",
                      LABELS, size, "middle", "baseline", 90.0))
    lines = [shapely.LineString(np.column_stack([x, y])),
             shapely.LineString([(0, bottom), (0, top)]), shapely.LineString([(0, 0), (right, 0)])]
    lines += [shapely.LineString([(0.0, ay), end]) for ay, end in ((ky, ends["k"]), (ly, ends["l"]))]
    # the numbers and l each by its own point, the nearest point to it (else led to it)
    marks = numbered + [("l", (lx, ly)), ("k", (kx, ky))]  # k last: its letter stays where it is
    dots = [shapely.Point(p).buffer(1.0) for _, p in marks]
    if numbers:
        items += place_anchored(marked, [shapely.Point(p) for _, p in marks], ["point"] * len(marks),
                                [ln.buffer(0.6) for ln in lines] + dots + _text_boxes(items), leader_layer=LABELS)
    else:  # a drawing only measured while its scales are sought: the numbers where first put
        items += marked
    items += list(place_labels(names, lines + _text_boxes(items)))
    w2d = omega_mean**2 * delta
    mu_j, mu_t, wm = indexed("μ", "J"), indexed("μ", "T"), indexed("ω", "m")
    text = [f"{mu_j} = {number(mJ, lang)} {unit('kg·m²', lang)}/{unit('mm', lang)};  "
            f"{mu_t} = {number(mT, lang)} {unit('J', lang)}/{unit('mm', lang)}",
            f"tg {indexed('ψ', 'max,min')} = ({mu_j}/{mu_t})·{wm}²(1 ± δ/2)²/2;  {wm} = {number(omega_mean, lang)} "
            f"{unit('rad/s', lang)}, δ = {number(delta, lang)}",
            f"{indexed('J', 'I')} = {mu_t}·kl/({wm}²·δ) = {number(mT, lang)}·{number(w.segment_drawn_mm, lang, 4)}/"
            f"{number(w2d, lang)} = {number(w.inertia_drawn, lang)} {unit('kg·m²', lang)}"]
    ytext = top + 4.0 + 1.6 * size * len(text)
    items.append(Text((0.0, ytext + 1.8 * size), label("energy_mass", lang), LABELS, sizes.title_mm))
    for k, line in enumerate(text):
        items.append(Text((0.0, ytext - 1.6 * size * k), line, LABELS, size))
    return make_view("wittenbauer", items, pad_mm=2.0, meta={"mu_J": mJ, "mu_T": mT,
                                                             "segment_mm": w.segment_drawn_mm,
                                                             "J_mm": float(x.max()),
                                                             "delta_T_mm": max(float(y.max()), ky, 0.0)
                                                             - min(float(y.min()), ly, 0.0),
                                                             "marks": tuple(marks)})


def _numbered(points, mJ: float, mT: float) -> list[tuple[str, tuple[float, float]]]:
    """(number, point mm) of the energy–mass diagram's positions, those within 1 mm of one
    numbered before them written with it ("2, 8")."""
    out: list[tuple[str, tuple[float, float]]] = []
    for k, (pj, pt) in enumerate(points):
        p = (float(pj / mJ), float(pt / mT))
        j = next((j for j, (_, q) in enumerate(out) if math.dist(p, q) < 1.0), None)
        if j is None:
            out.append((str(position_number(k)), p))
        else:
            out[j] = (f"{out[j][0]}, {position_number(k)}", out[j][1])
    return out


def flywheel_view(dims, *, scale: float, lang: Language, sizes: DynamicsSizes = DynamicsSizes(),
                  scale_text: str = "") -> View:
    """The flywheel's axial section at ``scale`` (m per mm): a disc, or a rim on a web and a
    hub, hatched, with its axis and the diameters (⌀426, as ESKD writes them: the sign and the
    size in mm) and the width b; mass and inertia.

    ``dims`` is a `velplan.dynamics.flywheel.FlywheelDimensions`."""
    s = 1.0 / scale
    R, b = 0.5 * dims.outer * s, dims.width * s
    size = sizes.label_mm
    items: list[Primitive] = []
    hub = max(0.12 * R, 3.0)
    if dims.shape == "disc":
        for sign in (1, -1):
            items.append(Polygon([(0, sign * hub), (b, sign * hub), (b, sign * R), (0, sign * R)],
                                 "flywheel", "thick", "hatch"))
    else:
        r1 = 0.5 * dims.inner * s
        web = max(0.25 * b, 1.0)
        hub_w = 0.8 * b
        for sign in (1, -1):
            items.append(Polygon([(0, sign * r1), (b, sign * r1), (b, sign * R), (0, sign * R)],
                                 "flywheel", "thick", "hatch"))
            items.append(Polygon([(0.5 * (b - web), sign * 1.6 * hub), (0.5 * (b + web), sign * 1.6 * hub),
                                  (0.5 * (b + web), sign * r1), (0.5 * (b - web), sign * r1)],
                                 "flywheel", "thick", "hatch"))
            items.append(Polygon([(0.5 * (b - hub_w), sign * hub), (0.5 * (b + hub_w), sign * hub),
                                  (0.5 * (b + hub_w), sign * 1.6 * hub), (0.5 * (b - hub_w), sign * 1.6 * hub)],
                                 "flywheel", "thick", "hatch"))
    # the axis
    items.append(Polyline([(-6.0, 0.0), (b + 6.0, 0.0)], "flywheel", "axis"))
    # the diameters to the left, b below
    diam = [(R, dims.outer)]
    if dims.shape == "rim":
        diam.append((0.5 * dims.inner * s, dims.inner))
    for k, (r, value) in enumerate(diam):
        xd = -8.0 - 8.0 * k
        items.append(Polyline([(0.0, r), (xd - 2.0, r)], "flywheel", "thin"))
        items.append(Polyline([(0.0, -r), (xd - 2.0, -r)], "flywheel", "thin"))
        items.append(Arrow((xd, 0.0), (xd, r), "flywheel", "thin", 2.5, 0.8))
        items.append(Arrow((xd, 0.0), (xd, -r), "flywheel", "thin", 2.5, 0.8))
        items.append(Text((xd - 1.0, 0.5 * r), f"⌀{number(1000 * value, lang, 4)}", LABELS, size,
                          "middle", "baseline", 90.0))
    items += _width_dimension(b, -R - 8.0, -R, number(1000 * dims.width, lang, 4), size)
    lines = [f"{label('flywheel', lang)} ({label(dims.shape, lang)}){'  ' + scale_text if scale_text else ''}",
             f"m = {number(dims.mass, lang)} {unit('kg', lang)};  J = {number(dims.inertia, lang)} "
             f"{unit('kg·m²', lang)} (≥ {number(dims.required, lang)})",
             f"ρ = {number(dims.density, lang)} {unit('kg/m³', lang)}"]
    x0, y = b + 10.0, R
    for k, line in enumerate(lines):
        height = sizes.title_mm if k == 0 else size
        y -= height
        items.append(Text((x0, y), line, LABELS, height))
        y -= 0.8 * height
    return make_view("flywheel", items, pad_mm=2.0, mu=scale, meta={"scale": scale})


def _width_dimension(b: float, y: float, edge: float, value: str, size: float) -> list[Primitive]:
    """The width `b` mm of a section whose lower edge is at `edge`, dimensioned as ESKD does at
    the level `y` below it: extension lines, the dimension line with its arrows (outside the
    extension lines where `b` leaves no room for two arrowheads) and the size over the line,
    between the extension lines or, too wide for them, beyond the right one on the line
    drawn out under it."""
    from velplan.render.shapes import text_extent

    arrow = 2.5
    items: list[Primitive] = [Polyline([(0.0, edge), (0.0, y - 2.0)], "flywheel", "thin"),
                              Polyline([(b, edge), (b, y - 2.0)], "flywheel", "thin")]
    if b >= 2.0 * arrow + 1.0:
        items += [Arrow((0.5 * b, y), (0.0, y), "flywheel", "thin", arrow, 0.8),
                  Arrow((0.5 * b, y), (b, y), "flywheel", "thin", arrow, 0.8)]
    else:
        items += [Arrow((-arrow - 2.0, y), (0.0, y), "flywheel", "thin", arrow, 0.8),
                  Arrow((b + arrow + 2.0, y), (b, y), "flywheel", "thin", arrow, 0.8),
                  Polyline([(0.0, y), (b, y)], "flywheel", "thin")]
    width = text_extent(value, size)[0]
    if width + 2.0 <= b:
        items.append(Text((0.5 * b, y + 1.0), value, LABELS, size, "middle", "baseline"))
    else:
        x0 = b + arrow + 3.0
        items += [Polyline([(b, y), (x0 + width + 1.0, y)], "flywheel", "thin"),
                  Text((x0, y + 1.0), value, LABELS, size, "start", "baseline")]
    return items


def bound(x: float, lang: Language) -> str:
    """An error bound ``x`` ≥ 0 rounded up to one significant figure: ``±0.004``, ``±2·10⁻¹¹``."""
    if not (math.isfinite(x) and x > 0):
        return "0" if x == 0 else "—"
    k = math.floor(math.log10(x))
    m = math.ceil(x / 10.0**k * (1 - 1e-12))
    if m == 10:
        m, k = 1, k + 1
    if -3 <= k <= 3:
        return "±" + number(m * 10.0**k, lang, 1)
    return "±" + power_of_ten(m * 10.0**k, lang, 1)


def error_rows(d, lang: Language, marked: bool = False) -> list[tuple[str, str, str]]:
    """(quantity, bound, unit) rows of the estimated errors of the main results
    (`velplan.dynamics.Dynamics.errors`); ``marked``: symbols' indices marked ``_{…}`` (drawn)."""
    e = d.errors
    name = label("estimated_error", lang)
    keys = (("driving_moment", indexed("M", constant_moment(d, lang)[1], marked), "N·m"),
            ("flywheel_exact", indexed("J", "I", marked), "kg·m²"),
            ("omega", "ω", "rad/s"), ("time", "t", "s"))
    return [(f"{name}: {sym}", bound(e[k], lang), unit(u, lang)) for k, sym, u in keys
            if k in e and e[k] and not (k == "driving_moment" and (d.run or d.periodic) is not None)]


def results_rows(d, w, lang: Language, errors: bool = True, marked: bool = False) -> list[tuple[str, str, str]]:
    """(quantity, value, unit) rows of the dynamics' results, then (``errors``) the estimated
    errors of the main ones; ``w`` the drawn `Wittenbauer` (or None); ``marked``: the symbols'
    indices marked ``_{…}`` (ω_{max}), as a drawing sets them, else written on the line (ωmax)."""
    rows = _result_rows(d, w, lang, marked)
    return rows + (error_rows(d, lang, marked) if errors else [])


def constant_moment(d, lang: Language) -> tuple[str, str, str]:
    """(the constant moment's name key, its index, the loads' reduced moment's index) in
    `lang`: the constant moment drives a machine whose loads resist (``d.driving`` ≥ 0: M_д
    against M_с); it resists an engine whose loads — the gas forces — drive (``d.driving`` < 0:
    M_с against M_д), as the course names them."""
    drv, res = label("symbol_drive", lang), label("symbol_resist", lang)
    if d.driving < 0.0 and d.run is None and d.periodic is None:
        return "resisting_moment", res, drv
    return "driving_moment", drv, res


def moment_scale(resisting) -> float:
    """The scale of the moments on the crank, N·m: the largest reduced moment of the loads
    over the cycle (``resisting``, `Dynamics.curves` ``"M_red"``); the driving moment within
    round-off of none of it is 0 (`velplan.views.base.number`'s ``scale``)."""
    values = np.abs(np.asarray(resisting, float))
    return float(values[np.isfinite(values)].max(initial=0.0))


def _result_rows(d, w, lang: Language, marked: bool) -> list[tuple[str, str, str]]:
    deg = unit("deg", lang)
    rads = unit("rad/s", lang)
    w_max, w_min, w_m = (indexed("ω", i, marked) for i in ("max", "min", "m"))
    j_one = indexed("J", "I", marked)
    if d.run is not None:
        r = d.run
        return [("t", number(r.time, lang, 5), unit("s", lang)),
                ("φ", number(math.degrees(r.travel), lang, 5), deg),
                ("ω₀", number(r.omega_start, lang, 5), rads),
                ("ω (t)", number(r.omega_end, lang, 5), rads),
                (w_max, number(r.omega_max, lang, 5), rads),
                (w_min + ", " + label("at_travel", lang).format(angle=f"{number(math.degrees(r.theta_min), lang, 4)}{deg}"),
                 number(r.omega_min, lang, 5), rads),
                (j_one, number(d.inertia, lang, 5), unit("kg·m²", lang))]
    rows = []
    if d.periodic is None:
        key, index, _ = constant_moment(d, lang)
        rows.append((label(key, lang) + " " + indexed("M", index, marked),
                     number(d.driving, lang, 5, scale=moment_scale(d.curves(72)["M_red"])), unit("N·m", lang)))
    st = d.steady or d.periodic
    if st is not None:
        rows += [
            (label("mean_speed", lang) + " " + w_m, number(st.omega_mean, lang, 5), unit("rad/s", lang)),
            (w_max + ", " + label("at_travel", lang).format(angle=f"{number(math.degrees(st.theta_max), lang, 4)}{deg}"),
             number(st.omega_max, lang, 5), unit("rad/s", lang)),
            (w_min + ", " + label("at_travel", lang).format(angle=f"{number(math.degrees(st.theta_min), lang, 4)}{deg}"),
             number(st.omega_min, lang, 5), unit("rad/s", lang)),
            (label("delta_obtained", lang), number(st.delta, lang, 4), ""),
        ]
    fly = d.flywheel
    if fly is not None:
        kgm2 = unit("kg·m²", lang)
        rows += [(label("delta_required", lang), number(fly.delta, lang, 4), ""),
                 (f"{j_one} ({label('method_exact', lang)})", number(fly.exact, lang, 6), kgm2),
                 (f"{j_one} ({label('method_wittenbauer', lang)})", number(fly.wittenbauer, lang, 6), kgm2)]
        if w is not None:
            err = 100.0 * (w.inertia_drawn - fly.exact) / fly.exact
            rows.append((f"{j_one} ({label('method_wittenbauer_drawn', lang)})",
                         f"{number(w.inertia_drawn, lang, 6)} ({'+' if err >= 0 else MINUS}{number(abs(err), lang, 2)} %)",
                         kgm2))
        rows += [(f"{j_one} ({label('method_mertsalov', lang)})",
                  f"{number(fly.mertsalov, lang, 6)} ({'+' if fly.mertsalov_difference >= 0 else MINUS}"
                  f"{number(abs(100 * fly.mertsalov_difference), lang, 3)} %)", kgm2),
                 (label("declared_inertia", lang), number(fly.declared, lang, 5), kgm2),
                 (label("flywheel_added", lang), number(fly.added, lang, 6) if fly.added > 0 else label("no_flywheel", lang),
                  kgm2 if fly.added > 0 else "")]
        if fly.added > 0:
            rows.append((label("flywheel_on_shaft", lang).format(ratio=number(fly.ratio, lang, 4)),
                         number(fly.on_shaft, lang, 6), kgm2))
    return rows


def results_view(rows: Sequence[tuple[str, str, str]], *, lang: Language, size_mm: float = 2.5,
                 title_mm: float = 3.5, width_factor: float = 1.0) -> View:
    """The results as a ruled table of three columns under its title, the cells' letters
    narrowed to `width_factor`."""
    grid = [[label("quantity", lang), label("value", lang), label("unit", lang)]] + [list(r) for r in rows]
    items, total_w, total_h = grid_table(grid, size_mm, width_factor=width_factor)
    items.append(table_title(label("dynamics_results", lang), title_mm, total_w, total_h, width_factor))
    return make_view("results", items, pad_mm=1.0, meta={"rows": len(rows), "size_mm": size_mm,
                                                           "width_factor": width_factor})


__all__ = ["DynamicsSizes", "Series", "bound", "constant_moment", "curve_panel", "error_rows", "flywheel_view",
           "moment_scale", "nice_step", "ordinate_scale", "results_rows", "results_view", "wittenbauer_view"]
