"""Drawing primitives as compact records that the page's script draws into SVG.

A record is a short JSON array in hundredths of a millimetre, y pointing down (the SVG's own
axes), so the page draws it without arithmetic on coordinates:

=============================  ==================================================================
``[0, line, x0, y0, x1, …]``   an open polyline
``[1, line, fill, x0, y0, …]``  a closed polygon; fill 0 none, 1 solid, 2 white (paper)
``[2, line, fill, cx, cy, r]``  a circle
``[3, line, x0, y0, x1, y1]``   an arrow from (x0, y0) to (x1, y1); the head is drawn by the page
``[4, 0, x, y, em, anchor,      one line of text at its alphabetic baseline; em is the font size,
rot, "text"]``                 anchor 0 start, 1 middle, 2 end, rot degrees clockwise on screen
``[5, line, x0, y0, x1, y1,     separate straight segments (hatching), four numbers each
…]``
=============================  ==================================================================

``line`` is the index of the line type in `velplan.render.style.LINE_TYPES`. Rounding to
0.01 mm is far below what a screen shows and keeps the page small and its bytes
deterministic. Hatching is computed here, with the sheets' own spacing and angle.
"""

from __future__ import annotations

import math

import numpy as np

from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Primitive, Text
from velplan.render.shapes import arrow_size, circle_outline, hatch_segments, text_origin
from velplan.render.style import LINE_TYPES, SheetStyle

#: Record codes.
POLYLINE, POLYGON, CIRCLE, ARROW, TEXT, SEGMENTS = range(6)
#: Units of a record coordinate per mm.
UNITS_PER_MM = 100
_FILL = {None: 0, "solid": 1, "white": 2, "hatch": 0}
_ANCHOR = {"start": 0, "middle": 1, "end": 2}
_LINE = {name: k for k, name in enumerate(LINE_TYPES)}


def _u(value: float) -> int:
    """A length in mm as an integer number of 0.01 mm."""
    return int(round(value * UNITS_PER_MM))


def _xy(points, dx: float, dy: float) -> list[int]:
    """Flat [x0, y0, x1, y1, …] in 0.01 mm, shifted by (dx, dy) mm and with y turned down."""
    k = UNITS_PER_MM
    return [u for x, y in points for u in (round((x - dx) * k), round((dy - y) * k))]  # as `_u` each


def encode(item: Primitive, style: SheetStyle, origin=(0.0, 0.0)) -> list[list]:
    """Records of one primitive (a hatched polygon or circle gives its hatch first).

    Parameters
    ----------
    item : Primitive
        In a view's mm, y up.
    style : SheetStyle
        The hatching's spacing and angle, the text's em size.
    origin : (float, float)
        The point of the view (mm) that becomes the record's (0, 0).
    """
    dx, dy = float(origin[0]), float(origin[1])
    kind = type(item)
    if kind is Arrow:  # the most common first, by exact type
        return [[ARROW, _LINE[item.line], *_xy((item.start, item.end), dx, dy)]]
    if kind is Polyline:
        return [[POLYLINE, _LINE[item.line], *_xy(item.points, dx, dy)]]
    if isinstance(item, Text):
        x, y = text_origin(item)
        em = style.font_size_em(item.size_mm)
        rot = round(-item.rotation_deg, 1) + 0.0
        return [[TEXT, 0, _u(x - dx), _u(dy - y), _u(em), _ANCHOR[item.anchor],
                 int(rot) if rot.is_integer() else rot, item.text]]
    line = LINE_TYPES.index(item.line)
    if isinstance(item, Arrow):
        return [[ARROW, line, *_xy([item.start, item.end], dx, dy)]]
    if isinstance(item, Polyline):
        return [[POLYLINE, line, *_xy(item.points, dx, dy)]]
    out: list[list] = []
    if isinstance(item, Circle):
        if item.fill == "hatch":
            out.append(_hatch(circle_outline(item.centre, item.radius), style, dx, dy))
        out.append([CIRCLE, line, _FILL[item.fill], *_xy([item.centre], dx, dy), _u(item.radius)])
        return out
    if isinstance(item, Polygon):
        if item.fill == "hatch":
            out.append(_hatch(item.points, style, dx, dy))
        out.append([POLYGON, line, _FILL[item.fill], *_xy(item.points, dx, dy)])
        return out
    raise TypeError(f"no record for {type(item).__name__}")


def _hatch(outline, style: SheetStyle, dx: float, dy: float) -> list:
    segments = hatch_segments(outline, style.hatch_spacing_mm, style.hatch_angle_deg)
    return [SEGMENTS, LINE_TYPES.index("thin"), *_xy(np.asarray(segments).reshape(-1, 2), dx, dy)]


def extent(records) -> tuple[int, int, int, int]:
    """(xmin, ymin, xmax, ymax) of the records' points in record units (text by its anchor,
    widened by its estimated length)."""
    xs: list[int] = []
    ys: list[int] = []
    for r in records:
        code = r[0]
        if code == TEXT:
            x, y, em, anchor, text = r[2], r[3], r[4], r[5], r[7]
            width = int(0.6 * em * len(text))
            left = x - width * anchor // 2
            xs += [left, left + width]
            ys += [y - em, y + em // 3]
        elif code == CIRCLE:
            cx, cy, radius = r[3], r[4], r[5]
            xs += [cx - radius, cx + radius]
            ys += [cy - radius, cy + radius]
        else:
            pts = r[3:] if code == POLYGON else r[2:]
            xs += pts[0::2]
            ys += pts[1::2]
    if not xs:
        return (0, 0, 0, 0)
    return (min(xs), min(ys), max(xs), max(ys))


def stroke_table(style: SheetStyle) -> list[dict]:
    """Per line type (in `LINE_TYPES` order): stroke width, dashes (0.01 mm) and the default
    arrowhead's length and width (0.01 mm), as the sheets draw them."""
    out = []
    for line in LINE_TYPES:
        width = style.width(line)
        head_length, head_width = arrow_size(None, None, style, width)
        out.append({"w": _u(width), "dash": [_u(d) for d in style.dash(line)],
                    "head": [_u(head_length), _u(head_width)]})
    return out


def round_sig(x: float, digits: int = 5) -> float | None:
    """`x` to `digits` significant figures (None for NaN or infinity): compact JSON."""
    x = float(x)
    if not math.isfinite(x):
        return None
    if x == 0:
        return 0.0
    return float(f"{x:.{digits}g}")
