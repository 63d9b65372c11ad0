"""The table of transfer functions (velocity analogues) as drawn on a course sheet.

Columns are the positions 1…n, rows the crank angle, |v|/ω of the crank (m) of the mechanism's
points and ω/ω of the crank of its turning links, read off the velocity plans
(`velplan.plans.table`), named as the answer key and ``velplan check`` name them
(`velplan.plans.table.quantity_label`), each row to three significant figures of its largest
value. Grid lines are thin, the outline and the header rule thick (GOST 2.105 tables); a header
cell may span the cells after it. Layer ``"table"``.
"""

from __future__ import annotations

import math

import numpy as np

from velplan.analysis.numbering import position_number
from velplan.mechanism.model import Mechanism
from velplan.options import Language
from velplan.plans.table import TransferTable, quantity_label
from velplan.render.i18n import label
from velplan.render.scene import Polygon, Polyline, Primitive, Text
from velplan.render.shapes import DESCENDER_DEPTH, text_depth, text_extent
from velplan.views.base import View, digits_down, fixed, make_view, row_decimals, subscript, unit

_ROW_PITCH = 2.0  # row height over text height
# A table narrowed to save room saves height too: rows of 1.7·h, the text raised 0.1·h off
# the row's middle, leave 0.2·h between an index (dropped 0.25·h) or a descender and the rule
# below, 0.25·h above the capitals.
_NARROW_ROW_PITCH = 1.7
_NARROW_LIFT = 0.1
_PAD = 1.0  # cell padding each side, mm
# Rendered Cyrillic runs wider than the layout's 0.7·h estimate; columns take the margin.
_WIDE = 1.3
#: Digits, signs and separators render within 3 % of the estimate (the bundled font:
#: "−0,0833" is 3.61 em, estimated 3.57): a number's column needs less margin.
NUMBER_MARGIN = 1.1
_NUMBER = set("0123456789,.−-+")


def _cell_width(text: str | None, size_mm: float, numbers: float, width_factor: float = 1.0) -> float:
    """Estimated width a cell's text needs, mm: a number's estimate times `numbers`, any other
    text's times the Cyrillic margin; letters narrowed to `width_factor`."""
    if text is None:
        return 0.0
    margin = numbers if text and set(text) <= _NUMBER else _WIDE
    return margin * text_extent(text, size_mm)[0] * width_factor


def _row_label(name: str, crank: str, lang: Language) -> str:
    w1 = "ω" + digits_down(crank)
    if name.startswith("w_"):
        return f"ω{digits_down(name[2:])}/{w1}"
    return f"V{subscript(name[2:])}/{w1}, {unit('m', lang)}"


def _spans(row: list) -> list[tuple[int, int]]:
    """(first, last) columns of each cell of `row`: a None cell belongs to the cell before it."""
    spans: list[tuple[int, int]] = []
    for c, text in enumerate(row):
        if text is None and spans:
            spans[-1] = (spans[-1][0], c)
        else:
            spans.append((c, c))
    return spans


def grid_table(grid: list[list[str | None]], size_mm: float, *,
               numbers: float = _WIDE, width_factor: float = 1.0) -> tuple[list[Primitive], float, float]:
    """A ruled table of text cells with its lower-left corner at (0, 0): the first column left-
    aligned, the value columns of equal width and centred; the outline and the header rule
    thick, the body lines thin. A None cell merges with the cell before it in its row (a header
    over two columns): no rule between them, the text centred over both. ``numbers`` is the
    margin of a number's estimated width (`NUMBER_MARGIN` where the columns hold numbers of the
    bundled font); ``width_factor`` narrows the letters (`velplan.render.scene.Text`), the
    height kept, and then lowers the rows. Returns (primitives, width mm, height mm)."""
    n = len(grid[0]) - 1
    widths = [max(_cell_width(r[c], size_mm, numbers, width_factor) for r in grid) + 2 * _PAD
              for c in range(n + 1)]
    widths[1:] = [max(widths[1:])] * n  # equal value columns
    heights, lifts = _rows(grid, size_mm, width_factor)
    total_w, total_h = sum(widths), float(sum(heights))
    tops = total_h - np.concatenate([[0.0], np.cumsum(heights)])  # tops[r]: row r's top, tops[-1] = 0
    items: list[Primitive] = []
    xs = np.concatenate([[0.0], np.cumsum(widths)])
    for r in range(1, len(grid)):
        y = tops[r]
        items.append(Polyline([(0.0, y), (total_w, y)], "table", "thick" if r == 1 else "thin"))
    for c, x in enumerate(xs[1:-1], start=1):
        # the rule left of column c, broken where a merged cell spans it
        open_rows = [r for r, row in enumerate(grid) if row[c] is not None]
        for run in np.split(np.asarray(open_rows), np.flatnonzero(np.diff(open_rows) > 1) + 1):
            if run.size:
                items.append(Polyline([(x, tops[run[-1] + 1]), (x, tops[run[0]])], "table", "thin"))
    items.append(Polygon([(0.0, 0.0), (total_w, 0.0), (total_w, total_h), (0.0, total_h)],
                         "table", "thick"))
    for r, row in enumerate(grid):
        y = (tops[r] + tops[r + 1]) / 2 + lifts[r]
        for first, last in _spans(row):
            text = row[first]
            if first == 0:
                items.append(Text((xs[0] + _PAD, y), text, "table", size_mm, "start", "middle",
                                  0.0, width_factor))
            else:
                items.append(Text(((xs[first] + xs[last + 1]) / 2, y), text, "table", size_mm,
                                  "middle", "middle", 0.0, width_factor))
    return items, total_w, total_h


#: The least gap between a cell's text, as far as it reaches (`text_depth`), and its rules, as a
#: fraction of the text height.
_CLEAR = 0.1


def _rows(grid: list[list[str | None]], size_mm: float, width_factor: float) -> tuple[list[float], list[float]]:
    """(height, lift of the text's middle off the row's middle) of each row of `grid`, mm: the
    rows of `grid_table`'s pitch, the text raised as a narrowed table raises it; a row whose text
    reaches farther (a subscript's descender, a raised exponent: `text_depth`) taller, as much
    as it needs to keep :data:`_CLEAR` of the height to both rules, its text centred on its reach."""
    h = size_mm
    pitch, lift = (_ROW_PITCH, 0.0) if width_factor == 1.0 else (_NARROW_ROW_PITCH, _NARROW_LIFT * h)
    heights, lifts = [], []
    for row in grid:
        reach = [text_depth(t, h) for t in row if t]
        below = max((b for b, _ in reach), default=DESCENDER_DEPTH * h)
        above = max((a for _, a in reach), default=h)
        if below <= DESCENDER_DEPTH * h + 1e-9 and above <= h + 1e-9:
            heights.append(pitch * h)
            lifts.append(lift)
            continue
        heights.append(max(pitch * h, below + above + 2 * _CLEAR * h))
        lifts.append(0.5 * h - 0.5 * (above - below))  # the capitals' middle over the reach's middle
    return heights, lifts


def table_title(text: str, size_mm: float, table_w: float, table_h: float, width_factor: float = 1.0) -> Text:
    """The title over a table `table_w` × `table_h` mm: its letters narrowed, down to the
    table's `width_factor`, where it would run wider than the table."""
    natural = text_extent(text, size_mm)[0]
    fit = math.floor(100.0 * table_w / natural) / 100.0 if natural > table_w else 1.0
    return Text((0.0, table_h + 2.5), text, "table", size_mm, "start", "baseline", 0.0,
                max(width_factor, min(1.0, fit)))


def table_view(table: TransferTable, mech: Mechanism, *, lang: Language = "ru",
               size_mm: float = 2.5, title_mm: float = 3.5, digits: int = 3,
               width_factor: float = 1.0) -> View:
    """The table as a view, its title above it.

    Parameters
    ----------
    table : TransferTable
        The study's table (`velplan.Study.table`), its rows in point and link order.
    mech : Mechanism
        For the crank's name (the ω every row is divided by).
    size_mm, title_mm : float
        Text heights of the cells and of the title, mm.
    width_factor : float
        The cells' letters narrowed to this share of their width (the height kept).
    digits : int
        Significant figures of each row's largest value; the row's other values to the same
        decimals (`velplan.views.base.row_decimals`).
    """
    n = len(table.phi)
    crank = mech.crank.link
    head = [label("position", lang)] + [str(position_number(i)) for i in range(n)]
    rows = [[f"φ, {unit('deg', lang)}"] +
            [fixed(math.degrees(p) % 360.0, lang, 1) for p in table.phi]]
    for name, values in table.rows.items():
        values = np.asarray(values, float)
        decimals = row_decimals(values, digits)
        rows.append([quantity_label(name, crank)] + [fixed(float(v), lang, decimals) for v in values])
    items, total_w, total_h = grid_table([head] + rows, size_mm, numbers=NUMBER_MARGIN,
                                         width_factor=width_factor)
    w1 = f"ω_{{{crank}}}"
    items.append(table_title(f"{label('table_transfer', lang)} (v/{w1}, {unit('m', lang)}; ω/{w1})",
                             title_mm, total_w, total_h, width_factor))
    return make_view("table", items, pad_mm=1.0,
                     meta={"rows": tuple(table.rows), "n": n, "size_mm": size_mm,
                           "width_factor": width_factor})
