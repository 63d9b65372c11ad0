"""The kinematic diagrams in a compact block for a small sheet (A3): s(φ) and v(φ) side by
side on one φ level, a(φ) under s(φ) on the same φ positions, and their scales, pole
distances and errors written once in the fourth quarter under v(φ), with the legend.

The scales are chosen for the height of the drawing rather than for its region: each
graphical curve spans at least a given ordinate range (30 mm on a sheet: a flatter curve
cannot be read), and as little more as a round scale allows, so that the block fits a corner
of the sheet. μs is a round number of the series :data:`RANGE_SERIES`; the pole distances
H come from :data:`~velplan.views.diagram.POLE_DISTANCES_MM`, as in the full form.

Examples
--------
>>> import velplan
>>> d = velplan.Study("crank-slider").diagrams
>>> view = compact_diagram_view(d, length_mm=72.0, min_range_mm=30.0, lang="en")
>>> all(r >= 30.0 for r in view.meta["drawn_ranges"]), view.meta["arrangement"]
(True, 'grid')
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Literal

import numpy as np
import shapely

from velplan.analysis.chord import Diagrams
from velplan.errors import ScaleError
from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.layout import label_box
from velplan.render.scene import Polyline, Primitive, Text
from velplan.render.shapes import text_extent
from velplan.views.base import View, bounds_of, make_view, number, scale_text, shift, unit
from velplan.views.diagram import (
    POLE_DISTANCES_MM, DiagramScales, DiagramSizes, _legend, _plot, ordinate_ranges)

Form = Literal["grid", "column"]

#: Mantissas of the compact diagrams' ordinate scale μs: finer steps than the plans' series
#: (1, 2, 2.5, 4, 5), so that a curve drawn at least 30 mm high is at most a quarter higher.
RANGE_SERIES: tuple[float, ...] = (1.0, 1.2, 1.4, 1.5, 1.6, 1.8, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 6.0, 7.0, 8.0, 9.0)
#: Largest pole distance of the compact form, as a share of the φ axis.
POLE_SHARE = 0.5
#: Pole distances of the compact form, mm: every whole millimetre from 5 to 20 (a steep curve
#: that a 10 mm pole would draw far higher than it needs; a curve held near its least range),
#: then the full form's.
COMPACT_POLES_MM: tuple[float, ...] = tuple(float(h) for h in range(5, 20)) + tuple(
    h for h in POLE_DISTANCES_MM if h >= 20.0)


def round_down(raw: float) -> float:
    """The largest value m·10ⁿ (m of :data:`RANGE_SERIES`) not above `raw`.

    >>> round_down(0.0179), round_down(0.0031), round_down(7.4), round_down(0.13)
    (0.016, 0.003, 7.0, 0.12)
    """
    if not (math.isfinite(raw) and raw > 0):
        raise ScaleError(f"cannot choose a diagram scale for a value per mm of {raw!r}")
    e = math.floor(math.log10(raw))
    for exp in (e, e - 1):
        for m in reversed(RANGE_SERIES):
            value = float(f"{m}e{exp}")
            if value <= raw * (1 + 1e-12):
                return value
    raise AssertionError("unreachable")


def drawn_values(d: Diagrams) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The values the graphical curves of s, v and a pass through (their thick lines)."""
    edge = 0.5 * (d.v_chord[0] + d.v_chord[-1])
    return np.asarray(d.s), np.r_[edge, d.v_chord], np.asarray(d.a_chord)


def scales_for_range(d: Diagrams, *, length_mm: float, min_range_mm: float) -> DiagramScales:
    """Scales that draw each graphical curve of `d` at least `min_range_mm` high on a φ axis
    `length_mm` long: μs the largest round value that does, each H the shortest pole
    distance of :data:`COMPACT_POLES_MM` that does (at most :data:`POLE_SHARE` of the axis: where none does, the
    longest, and the curve stays lower)."""
    if not (length_mm > 0 and min_range_mm > 0):
        raise ScaleError(f"diagram axes must be positive, got {length_mm} mm and a range of {min_range_mm} mm")
    mu_phi = 2 * math.pi / length_mm
    s, v, a = (max(float(np.ptp(y)), 1e-12) for y in drawn_values(d))
    mu_s = round_down(s / min_range_mm)
    allowed = [h for h in COMPACT_POLES_MM if h <= POLE_SHARE * length_mm + 1e-9] or [COMPACT_POLES_MM[0]]

    def pole(spread: float, mu_y: float) -> float:
        # drawn range = spread / (mu_y / (mu_phi·H)) ≥ min_range_mm
        need = min_range_mm * mu_y / (mu_phi * spread)
        return next((h for h in allowed if h >= need - 1e-9), allowed[-1])

    H_v = pole(v, mu_s)
    mu_v = mu_s / (mu_phi * H_v)
    H_a = pole(a, mu_v)
    return DiagramScales(length_mm, mu_phi, mu_s, H_v, mu_v, H_a, mu_a=mu_v / (mu_phi * H_a))


def drawn_ranges(d: Diagrams, sc: DiagramScales) -> tuple[float, float, float]:
    """The ordinate range of the graphical curves of s, v and a at the scales `sc`, mm."""
    s, v, a = (float(np.ptp(y)) for y in drawn_values(d))
    return s / sc.mu_s, v / sc.mu_v, a / sc.mu_a


def compact_lines(d: Diagrams, sc: DiagramScales, lang: Language, omega: float) -> list[list[str]]:
    """The pieces of the text block: the scales of s and φ (and of time, read in time at the
    crank speed `omega` rad/s ≠ 0), then per derived diagram its pole distance, its scale and
    its error; a list of lines, each a list of pieces joined with ";  " where they fit."""
    w = abs(omega)
    sym = "μψ" if d.angular else "μs"
    head = [scale_text(sym, sc.mu_s, "rad/mm" if d.angular else "m/mm", lang),
            scale_text("μφ", sc.mu_phi, "rad/mm", lang) + f" ({number(math.degrees(sc.mu_phi), lang, 3)}°/{unit('mm', lang)})"]
    if w > 0:
        head.append(f"μt = μφ/ω1 = {number(sc.mu_phi / w, lang, 3)} {unit('s/mm', lang)}")
    lines = [head]
    per = "μt" if w > 0 else "μφ"
    for kind, H, mu, err in (("v", sc.H_v, sc.mu_v, d.error_v), ("a", sc.H_a, sc.mu_a, d.error_a)):
        up = sym if kind == "v" else "μv"
        if w > 0:
            value = mu * w if kind == "v" else mu * w * w
            unit_key = {("v", False): "(m/s)/mm", ("a", False): "(m/s²)/mm",
                        ("v", True): "(rad/s)/mm", ("a", True): "(rad/s²)/mm"}[kind, d.angular]
            text_unit = unit(unit_key, lang)
        else:
            value, text_unit = mu, unit("1/mm", lang) if d.angular else unit("m/mm", lang)
        lines.append([f"H = {number(H, lang, 3)} {unit('mm', lang)}",
                      f"μ{kind} = {up}/({per}·H) = {number(value, lang, 3)} {text_unit}",
                      f"δ{kind} = {number(100 * err, lang, 2)} %"])
    lines.append([f"δ — {label('error', lang)}, {label('chord_method', lang)}"])
    return lines


def _wrapped(lines: list[list[str]], size: float, width: float) -> list[str]:
    """Each line's pieces joined with ";  " while the line stays within `width` mm."""
    out = []
    for pieces in lines:
        current = pieces[0]
        for piece in pieces[1:]:
            joined = f"{current};  {piece}"
            if text_extent(joined, size)[0] <= width:
                current = joined
            else:
                out.append(current)
                current = piece
        out.append(current)
    return out


def _numbers_off_the_curves(items: list[Primitive]) -> list[Primitive]:
    """The position numbers of the φ axis that a curve still crosses (under the axis and above
    it) moved along the axis by up to half a character either way, or else to the other side,
    where that clears them (the number stays nearest its tick)."""
    curves = [shapely.LineString(p.points) for p in items if isinstance(p, Polyline)
              and p.line in ("thick", "hidden") and len(p.points) > 5]
    tree = shapely.STRtree(curves)

    def clear(t: Text) -> bool:
        return not len(tree.query(label_box(t), predicate="intersects"))

    out = []
    for p in items:
        if isinstance(p, Text) and p.text.isdigit() and abs(p.position[1]) < 3.0 and not clear(p):
            x, y = p.position
            flip: Literal["baseline", "top"] = "top" if p.baseline == "baseline" else "baseline"
            tries = [replace(p, position=(x + dx, y)) for dx in (0.6, -0.6, 1.2, -1.2)]
            tries += [replace(p, position=(x + dx, -y), baseline=flip) for dx in (0.0, 0.6, -0.6, 1.2, -1.2)]
            p = next((t for t in tries if clear(t)), p)
        out.append(p)
    return out


def _titled(kind: str, d: Diagrams, sc: DiagramScales, lang: Language, sizes: DiagramSizes,
            omega: float) -> list[Primitive]:
    """One diagram without its text block, its title beside the tip of its ordinate axis."""
    items = _numbers_off_the_curves(_plot(kind, d, sc, lang=lang, sizes=sizes, omega=omega, titled=False))
    tip = max(p.position[1] for p in items if isinstance(p, Text))  # the ordinate's name, at top + 6
    key = {"s": "displacement_diagram", "v": "velocity_diagram", "a": "acceleration_diagram"}[kind]
    if kind != "s" and not abs(omega) > 0:
        key = {"v": "velocity_analogue_diagram", "a": "acceleration_analogue_diagram"}[kind]
    items.append(Text((2.5, tip), label(key, lang), "diagram-labels", sizes.title_mm, "start", "top"))
    return items


def compact_diagram_view(d: Diagrams, *, length_mm: float, min_range_mm: float = 30.0,
                         lang: Language = "ru", sizes: DiagramSizes = DiagramSizes(),
                         omega: float = 0.0, gap_mm: float = 5.0, form: Form = "grid") -> View:
    """The three diagrams of `d` as one compact view (the module's docstring): a φ axis
    `length_mm` long, each graphical curve at least `min_range_mm` high; ``omega`` as in
    :func:`~velplan.views.diagram.diagram_view`. The ``"grid"`` form sets s and v side by
    side and a under s, the text in the fourth quarter; the ``"column"`` form stacks s, v and
    a on one set of φ positions, the text under them."""
    sc = scales_for_range(d, length_mm=length_mm, min_range_mm=min_range_mm)
    plots = [_titled(k, d, sc, lang, sizes, omega) for k in "sva"]
    items, (x, y, width) = (_grid if form == "grid" else _column)(plots, gap_mm)
    step = 1.6 * sizes.label_mm
    y -= sizes.label_mm
    for line in _wrapped(compact_lines(d, sc, lang, omega), sizes.label_mm, width):
        items.append(Text((x, y), line, "diagram-labels", sizes.label_mm, "start", "top"))
        y -= step
    items += _legend(x, y - 0.5 * sizes.label_mm, lang, sizes.label_mm)
    return make_view("diagrams", items, pad_mm=2.0,
                     meta={"scales": sc, "error_v": d.error_v, "error_a": d.error_a,
                           "quantity": d.quantity, "omega": abs(omega), "arrangement": form,
                           "ranges": ordinate_ranges(d, sc), "drawn_ranges": drawn_ranges(d, sc)})


def _grid(plots, gap: float):
    """(items, (x, top, width) of the text block): s and v hanging from one top line, a under
    s on its φ positions, the text block under v."""
    s, v, a = plots
    (sx0, sy0, sx1, sy1), (vx0, vy0, vx1, vy1), (ax0, _, ax1, ay1) = (bounds_of(p) for p in plots)
    left = max(-sx0, -ax0)  # s and a share their φ positions: their origins one above the other
    col2 = left + max(sx1, ax1) + gap - vx0
    below = min(sy0 - sy1, vy0 - vy1) - gap
    items = [shift(q, left, -sy1) for q in s] + [shift(q, col2, -vy1) for q in v]
    items += [shift(q, left, below - ay1) for q in a]
    return items, (col2 + vx0, below, vx1 - vx0)


def _column(plots, gap: float):
    """(items, (x, top, width) of the text block): s, v and a one under another on one set of
    φ positions, the text block under them."""
    boxes = [bounds_of(p) for p in plots]
    left = max(-b[0] for b in boxes)
    items: list[Primitive] = []
    top = 0.0
    for p, (_, y0, _, y1) in zip(plots, boxes):
        items += [shift(q, left, top - y1) for q in p]
        top -= (y1 - y0) + gap
    x0, _, x1, _ = bounds_of(items)
    return items, (x0, top + gap - 0.5 * gap, x1 - x0)


__all__ = ["RANGE_SERIES", "compact_diagram_view", "drawn_ranges", "round_down", "scales_for_range"]
