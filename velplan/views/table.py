"""The table of transfer functions (velocity analogues) as drawn on a course sheet.

Columns are the positions 1…n, rows the crank angle, |V|/ω1 (m) of the mechanism's points
and ω/ω1 of its turning links, read off the velocity plans (`velplan.plans.table`). Grid
lines are thin, the outline and the header rule thick (GOST 2.105 tables). Layer
``"table"``.
"""

from __future__ import annotations

import math

import numpy as np

from velplan.analysis.numbering import position_number
from velplan.mechanism.model import Mechanism
from velplan.options import Language
from velplan.plans.table import TransferTable
from velplan.render.i18n import label
from velplan.render.scene import Polygon, Polyline, Primitive, Text
from velplan.render.shapes import text_extent
from velplan.views.base import View, digits_down, fixed, make_view, subscript, unit

_ROW_PITCH = 2.0  # row height over text height
_PAD = 1.0  # cell padding each side, mm
# Rendered Cyrillic runs wider than the layout's 0.7·h estimate; columns take the margin.
_WIDE = 1.3


def _row_label(name: str, crank: str, lang: Language) -> str:
    w1 = "ω" + digits_down(crank)
    if name.startswith("w_"):
        return f"ω{digits_down(name[2:])}/{w1}"
    return f"V{subscript(name[2:])}/{w1}, {unit('m', lang)}"


def grid_table(grid: list[list[str]], size_mm: float) -> tuple[list[Primitive], float, float]:
    """A ruled table of text cells with its lower-left corner at (0, 0): the first column left-
    aligned, the value columns of equal width and centred; the outline and the header rule
    thick, the body lines thin. Returns (primitives, width mm, height mm)."""
    n = len(grid[0]) - 1
    widths = [max(_WIDE * text_extent(r[c], size_mm)[0] for r in grid) + 2 * _PAD
              for c in range(n + 1)]
    widths[1:] = [max(widths[1:])] * n  # equal value columns
    row_h = _ROW_PITCH * size_mm
    total_w, total_h = sum(widths), row_h * len(grid)
    items: list[Primitive] = []
    xs = np.concatenate([[0.0], np.cumsum(widths)])
    for r in range(1, len(grid)):
        y = total_h - r * row_h
        items.append(Polyline([(0.0, y), (total_w, y)], "table", "thick" if r == 1 else "thin"))
    for x in xs[1:-1]:
        items.append(Polyline([(x, 0.0), (x, total_h)], "table", "thin"))
    items.append(Polygon([(0.0, 0.0), (total_w, 0.0), (total_w, total_h), (0.0, total_h)],
                         "table", "thick"))
    for r, row in enumerate(grid):
        y = total_h - (r + 0.5) * row_h
        for c, text in enumerate(row):
            if c == 0:
                items.append(Text((xs[0] + _PAD, y), text, "table", size_mm, "start", "middle"))
            else:
                items.append(Text(((xs[c] + xs[c + 1]) / 2, y), text, "table", size_mm,
                                  "middle", "middle"))
    return items, total_w, total_h


def table_view(table: TransferTable, mech: Mechanism, *, lang: Language = "ru",
               size_mm: float = 2.5, title_mm: float = 3.5, decimals: int = 3) -> View:
    """The table as a view, its title above it.

    Parameters
    ----------
    table : TransferTable
        The study's table (`velplan.Study.table`).
    mech : Mechanism
        For the crank's name (ω1 is the crank's ω).
    size_mm, title_mm : float
        Text heights of the cells and of the title, mm.
    decimals : int
        Decimals of the values.
    """
    n = len(table.phi)
    head = [label("position", lang)] + [str(position_number(i)) for i in range(n)]
    rows = [[f"φ, {unit('deg', lang)}"] +
            [fixed(math.degrees(p) % 360.0, lang, 1) for p in table.phi]]
    for name, values in table.rows.items():
        rows.append([_row_label(name, mech.crank.link, lang)] +
                    [fixed(float(v), lang, decimals) for v in np.asarray(values)])
    items, total_w, total_h = grid_table([head] + rows, size_mm)
    items.append(Text((0.0, total_h + 2.5), f"{label('table_transfer', lang)} "
                      f"(V/ω{digits_down(mech.crank.link)}, {unit('m', lang)}; "
                      f"ω/ω{digits_down(mech.crank.link)})",
                      "table", title_mm))
    return make_view("table", items, pad_mm=1.0,
                     meta={"rows": tuple(table.rows), "n": n, "size_mm": size_mm})
