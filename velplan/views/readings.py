"""The table of values read off the drawn plans beside the analytic ones: for each plan on the
sheet, every point's speed (m/s) or acceleration (m/s²) as a draughtsman reads it — the
vector's length on the drawing rounded to the drafting precision, times μ — the exact value
and the difference in per cent. Layer ``"table"``.
"""

from __future__ import annotations

import numpy as np

from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.scene import Text
from velplan.views.base import View, fixed, make_view, number, subscript, unit
from velplan.views.mechanism import special_points
from velplan.views.table import grid_table

PRECISION_MM = 0.5
"""Drafting precision the lengths are read to, mm."""


def readings(res, position: int, precision: float = PRECISION_MM) -> list[tuple[str, float, float]]:
    """(point, read value, exact value) of every moving point of plan ``res`` (not a triad's
    special point, a construction point) at position number ``position`` (1…n): |vector| read
    on the drawing at ``precision`` mm times μ, and the solver's."""
    kin = res.kin
    i = res.index_of(position)
    j = res.index[i]
    ground = dict(kin.mechanism.ground)
    ground.update(dict.fromkeys(special_points(kin.mechanism)))  # construction points
    ref = kin.velocities if res.kind == "velocity" else kin.accelerations
    out = []
    for p, v in res.vectors.items():
        if p in ground or p not in kin.point_index:
            continue
        length_mm = float(np.hypot(*v[i])) / res.scale
        read = round(length_mm / precision) * precision * res.scale
        exact = float(np.hypot(*ref[j, kin.point_index[p]]))
        out.append((p, read, exact))
    return out


def readings_view(plans: dict, *, lang: Language = "ru", size_mm: float = 2.5, title_mm: float = 3.5) -> View:
    """The table for ``plans`` (view name → (PlanResult, position number 1…n)): a row per point, for each
    plan (velocity plans first) the value read off it and its difference from the analytic
    value in per cent ("—" where the vector is shorter than two drafting steps, 1 mm)."""
    order = sorted(plans.items(), key=lambda kv: (kv[1][0].kind != "velocity", kv[1][1]))
    head = [label("position_short", lang)]
    units = [label("quantity", lang)]
    rows: dict[str, list[str]] = {}
    for k, (name, (res, position)) in enumerate(order):
        sym = "V" if res.kind == "velocity" else "a"
        u = unit("m/s", lang) if res.kind == "velocity" else unit("m/s²", lang)
        head += [str(position), ""]
        units += [f"{sym}, {u}", "δ, %"]
        for p, read, exact in readings(res, position):
            row = rows.setdefault(subscript(p), [""] * (2 * len(order)))
            # a per cent of a vector shorter than two drafting steps says nothing: "—"
            err = 100.0 * (read - exact) / exact if exact / res.scale >= 2 * PRECISION_MM else float("nan")
            row[2 * k:2 * k + 2] = [fixed(read, lang, 3), fixed(err, lang, 1) if np.isfinite(err) else "—"]
    grid = [head, units] + [[q] + vals for q, vals in rows.items()]
    items, total_w, total_h = grid_table(grid, size_mm)
    items.append(Text((0.0, total_h + 2.5), f"{label('plan_readings', lang)} "
                      f"{number(PRECISION_MM, lang)} {unit('mm', lang)}", "table", title_mm))
    return make_view("readings", items, pad_mm=1.0, meta={"rows": tuple(rows), "size_mm": size_mm})


__all__ = ["readings", "readings_view", "PRECISION_MM"]
