"""The table of the three balancing moments — kinetostatics, Zhukovsky's lever, the power
method — at every position of the sheet."""

from __future__ import annotations

import math

import numpy as np

from velplan.analysis.numbering import position_number
from velplan.forces.agreement import ForceAnalysis
from velplan.options import Language
from velplan.render.i18n import label
from velplan.views.base import View, fixed, make_view, unit
from velplan.views.forces.common import newton_metre
from velplan.views.table import grid_table, table_title


def moment_decimals(values) -> int:
    """Decimals that give the largest |M_b| four significant figures."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    top = float(np.max(np.abs(v))) if v.size else 0.0
    if top == 0.0:
        return 1
    return int(min(4, max(0, 3 - math.floor(math.log10(top)))))


def moments_table_view(fa: ForceAnalysis, *, lang: Language = "ru", size_mm: float = 2.5,
                       title_mm: float = 3.5, width_factor: float = 1.0) -> View:
    """The three balancing moments (kinetostatics, lever, power) at every position, N·m; the
    cells' letters narrowed to `width_factor`."""
    n = len(fa.kinematics)
    moments = fa.balancing_moments
    decimals = moment_decimals(moments["kinetostatics"])
    mb = label("symbol_balancing_moment", lang)
    head = [label("position", lang)] + [str(position_number(k)) for k in range(n)]
    rows = [[f"φ, {unit('deg', lang)}"] +
            [fixed(math.degrees(p) % 360.0, lang, 1) for p in fa.kinematics.phi]]
    for key in ("kinetostatics", "lever", "power"):
        rows.append([f"{mb} ({label('method_' + key, lang)})"] +
                    [fixed(float(v), lang, decimals) for v in moments[key]])
    items, total_w, total_h = grid_table([head] + rows, size_mm, width_factor=width_factor)
    items.append(table_title(f"{label('balancing_moment', lang)} {mb}, {newton_metre(lang)}",
                             title_mm, total_w, total_h, width_factor))
    return make_view("table", items, pad_mm=1.0, meta={"n": n, "size_mm": size_mm,
                                                      "decimals": decimals, "width_factor": width_factor})
