"""The table of values read off the drawn plans beside the analytic ones: for each plan on the
sheet, every point's speed (m/s) or acceleration (m/s²) as a draughtsman reads it — the
vector's length on the drawing rounded to the drawing's resolution (0.1 mm), times μ, printed
to the decimals that resolution gives — and the difference from the exact value in per cent;
each plan's position heads its two columns. Layer ``"table"``.
"""

from __future__ import annotations

import math

import numpy as np

from velplan.options import Language
from velplan.plans.table import natural_key
from velplan.render.i18n import label
from velplan.views.base import View, fixed, make_view, number, subscript, unit
from velplan.views.mechanism import special_points
from velplan.views.table import grid_table, table_title

PRECISION_MM = 0.1
"""Resolution the lengths are read to on the drawing, mm."""

SHORTEST_MM = 1.0
"""A vector shorter than this on the plan gets no per cent (it says nothing), mm."""


def read_decimals(scale: float, precision: float = PRECISION_MM) -> int:
    """Decimals of a value read off a plan of `scale` (units per mm) to `precision` mm: those
    of one significant figure of the value of `precision` mm (μv = 0.02 (m/s)/mm: 0.002, three)."""
    return max(0, -math.floor(math.log10(precision * scale)))


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


def readings_view(plans: dict, *, lang: Language = "ru", size_mm: float = 2.5, title_mm: float = 3.5,
                  width_factor: float = 1.0) -> View:
    """The table for ``plans`` (view name → (PlanResult, position number 1…n)): a row per point, for each
    plan (velocity plans first) the value read off it and its difference from the analytic
    value in per cent ("—" where the vector is shorter than `SHORTEST_MM`); the cells' letters
    narrowed to `width_factor`."""
    order = sorted(plans.items(), key=lambda kv: (kv[1][0].kind != "velocity", kv[1][1]))
    head = [label("position_short", lang)]
    units = [label("quantity", lang)]
    rows: dict[str, list[str]] = {}
    for k, (name, (res, position)) in enumerate(order):
        sym = "v" if res.kind == "velocity" else "a"
        u = unit("m/s", lang) if res.kind == "velocity" else unit("m/s²", lang)
        decimals = read_decimals(res.scale)
        head += [str(position), None]
        units += [f"{sym}, {u}", "δ, %"]
        for p, read, exact in readings(res, position):
            row = rows.setdefault(p, [""] * (2 * len(order)))
            # a per cent of a vector shorter than SHORTEST_MM says nothing: "—"
            err = 100.0 * (read - exact) / exact if exact / res.scale >= SHORTEST_MM else float("nan")
            row[2 * k:2 * k + 2] = [fixed(read, lang, decimals), fixed(err, lang, 1) if np.isfinite(err) else "—"]
    grid = [head, units] + [[subscript(q)] + rows[q] for q in sorted(rows, key=natural_key)]
    items, total_w, total_h = grid_table(grid, size_mm, width_factor=width_factor)
    items.append(table_title(f"{label('plan_readings', lang)} {number(PRECISION_MM, lang)} {unit('mm', lang)}",
                             title_mm, total_w, total_h, width_factor))
    return make_view("readings", items, pad_mm=1.0, meta={"rows": tuple(sorted(rows, key=natural_key)),
                                                          "size_mm": size_mm, "width_factor": width_factor})


__all__ = ["readings", "readings_view", "read_decimals", "PRECISION_MM", "SHORTEST_MM"]
