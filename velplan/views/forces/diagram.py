"""The diagram M_b(φ) of the balancing moment over a revolution from position 1."""

from __future__ import annotations

import math

import numpy as np

from velplan.forces.curve import MomentCurve
from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.scene import Circle, Polyline, Primitive, Text
from velplan.views.base import View, axis_numbers_clear, make_view, scale_text, unit
from velplan.notation import number as _num
from velplan.views.diagram import phi_axes
from velplan.views.forces.common import newton_metre

#: Layers of the diagram: the axes and curves, and the text.
LAYER, TEXT_LAYER = "mb-diagram", "mb-diagram-labels"


def moment_diagram_view(curve: MomentCurve, *, length_mm: float = 240.0,
                        height_mm: float = 60.0, lang: Language = "ru",
                        label_mm: float = 2.5, title_mm: float = 3.5) -> View:
    """The diagram M_b(φ) over a revolution: the curve (thick), the n positions marked on
    the φ axis with their values as dots, the mean as a dash-dot line, the scales.

    Parameters
    ----------
    length_mm : float
        Length of the φ axis for a turn, mm (μφ = 2π / length).
    height_mm : float
        Largest span of the ordinates, mm: μM is the standard scale that keeps
        max M_b − min M_b within it.
    """
    from velplan.plans import standard_scale

    mom, at = curve.moment, curve.at_positions
    n = len(at)
    fin = mom[np.isfinite(mom)]
    top_v, bottom_v = max(float(fin.max()), 0.0), min(float(fin.min()), 0.0)
    span = max(top_v - bottom_v, 1e-12)
    mu_m = standard_scale(span / height_mm)
    mu_phi = 2 * math.pi / length_mm
    top, bottom = max(top_v / mu_m, 5.0), bottom_v / mu_m
    items = phi_axes(length_mm, top, bottom, n,
                     f"{label('symbol_balancing_moment', lang)}, {newton_metre(lang)}",
                     layer=LAYER, text_layer=TEXT_LAYER, label_mm=label_mm, tick_mm=label_mm)
    ok = np.isfinite(mom)
    xy = np.column_stack([curve.turn[ok] / mu_phi, mom[ok] / mu_m])
    items.append(Polyline(xy, LAYER, "thick"))
    mean = curve.mean
    if np.isfinite(mean):
        items += _mean_line(mean / mu_m, mean, length_mm, lang, label_mm)
    # the numbers kept clear of every line drawn over the axis: the curve and the mean's line
    items = axis_numbers_clear(items, [xy] + [p.points for p in items if isinstance(p, Polyline) and p.line == "axis"])
    for k, v in enumerate(at):
        if np.isfinite(v):
            items.append(Circle((k * length_mm / n, float(v) / mu_m), 0.6, LAYER, "thin", "solid"))
    y = top + 8.0 + 1.6 * label_mm
    items.append(Text((0.0, y + 1.8 * label_mm), label("balancing_moment_diagram", lang),
                      TEXT_LAYER, title_mm))
    items.append(Text((0.0, y), f"μM = {_num(mu_m, lang)} {newton_metre(lang)}/"
                      f"{unit('mm', lang)};  " + scale_text("μφ", mu_phi, "rad/mm", lang) +
                      f" ({_num(math.degrees(mu_phi), lang, 3)}°/{unit('mm', lang)})",
                      TEXT_LAYER, label_mm))
    return make_view("mb-diagram", items, pad_mm=2.0,
                     meta={"mu_m": mu_m, "mu_phi": mu_phi, "mean": mean})


def _mean_line(y: float, mean: float, length: float, lang: Language, size: float) -> list[Primitive]:
    """The mean `mean` (N·m) as a dash-dot line at height `y` (mm) and its value, written
    above a mean over the axis, below one under it (clear of the axis's φ)."""
    at, v_anchor = (y + 1.0, "baseline") if y >= 0 else (min(y - 1.0, -1.0 - size - 1.0), "top")
    return [Polyline([(0.0, y), (length, y)], LAYER, "axis"),
            Text((length + 2.0, at), f"{label('mean', lang)} {_num(mean, lang)} "
                 f"{newton_metre(lang)}", TEXT_LAYER, size, "start", v_anchor)]
