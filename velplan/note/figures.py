"""Figures of the note: the sheets' own views, drawn side by side and rasterised to PNG at print
resolution through the sheets' PNG export (cairosvg, with the bundled font)."""

from __future__ import annotations

from velplan.render.scene import Scene
from velplan.render.svg import to_svg
from velplan.views.base import shift

DPI = 200.0
"""Resolution of the figures, dots per inch (print quality at their size on the page)."""
TEXT_WIDTH_MM = 170.0
"""Width of the text on an A4 page with the note's margins, mm."""
FIGURE_HEIGHT_MM = 200.0
"""Tallest figure on the page, mm (room left for its caption)."""
GAP_MM = 6.0


def views_png(views, style, *, dpi: float = DPI) -> tuple[bytes, float]:
    """PNG of `views` (placed or bare `View` objects) side by side, and the width (mm) it takes
    on the page: its size on the sheet, or less to fit the text width and `FIGURE_HEIGHT_MM`."""
    from velplan.render.export import svg_to_png

    items, x = [], 0.0
    height = max(_view(v).height_mm for v in views)
    for v in views:
        view = _view(v)
        items += [shift(p, x, (height - view.height_mm) / 2) for p in view.primitives]
        x += view.width_mm + GAP_MM
    width = x - GAP_MM
    printed = min(width, TEXT_WIDTH_MM, width * FIGURE_HEIGHT_MM / height)
    svg = to_svg(Scene(tuple(items), width, height), style)
    png = svg_to_png(svg, dpi=dpi * printed / width)
    return png, printed


def _view(v):
    return getattr(v, "view", v)
