"""Figures of the note: the sheets' own views, drawn side by side and rasterised to PNG at print
resolution through the sheets' PNG export (cairosvg, with the bundled font)."""

from __future__ import annotations

from dataclasses import replace

from velplan.render.scene import Scene, Text
from velplan.render.svg import to_svg
from velplan.views.base import ESKD_RATIOS, number, ratio_text, shift

DPI = 200.0
"""Resolution of the figures, dots per inch (print quality at their size on the page)."""
TEXT_WIDTH_MM = 170.0
"""Width of the text on an A4 page with the note's margins, mm."""
FIGURE_HEIGHT_MM = 200.0
"""Tallest figure on the page, mm (room left for its caption)."""
GAP_MM = 6.0
LETTER_MM = 2.5
"""The smallest printed lettering (ГОСТ 2.304): a figure shrunk to the page has its text
enlarged back to this where the sheet's text would print smaller."""


def views_png(views, style, *, dpi: float = DPI) -> tuple[bytes, float]:
    """PNG of `views` (placed or bare `View` objects) side by side, and the width (mm) it takes
    on the page: its size on the sheet, or less to fit the text width and `FIGURE_HEIGHT_MM`."""
    from velplan.render.export import _convert

    height = max(_view(v).height_mm for v in views)
    width = sum(_view(v).width_mm for v in views) + GAP_MM * (len(views) - 1)
    printed = min(width, TEXT_WIDTH_MM, width * FIGURE_HEIGHT_MM / height)
    if printed < width:
        printed = width * min(_standard_shrink(_view(v), printed / width) for v in views)
    shrink = printed / width
    items, x = [], 0.0
    for v in views:
        view = _view(v)
        items += [for_page(shift(p, x, (height - view.height_mm) / 2), view.mu, shrink) for p in view.primitives]
        x += view.width_mm + GAP_MM
    svg = to_svg(Scene(tuple(items), width, height), style)
    png = _convert("svg2png", svg, dpi=dpi * printed / width, background_color="white")
    return png, printed


def _standard_shrink(view, shrink: float) -> float:
    """A drawing at a length scale (its text states "1:2,5") shrinks to the next ESKD scale
    (1:5 rather than 1:4,967), so the scale written on the page is a standard one."""
    mu = view.mu
    if not mu or not any(isinstance(p, Text) and ratio_text(mu, lang) in p.text
                         for p in view.primitives for lang in ("ru", "en")):
        return shrink
    wanted = mu / shrink
    scales = sorted(0.001 * b / a for a, b in ESKD_RATIOS if 0.001 * b / a >= wanted * (1 - 1e-9))
    return mu / scales[0] if scales else shrink


def for_page(item, mu: float | None, shrink: float):
    """A primitive of a view drawn at ``shrink`` (printed/sheet size) for the page: its text
    no smaller than `LETTER_MM` printed (never larger than on the sheet), and a scale the view
    states (μ and the ESKD ratio of ``mu``) rewritten for the printed size."""
    if not isinstance(item, Text) or shrink >= 1.0:
        return item
    size = max(item.size_mm, min(LETTER_MM / shrink, item.size_mm / shrink))
    text = item.text
    if mu and "μ" in text:
        for lang in ("ru", "en"):  # the sheet's own decimal sign, rewritten once
            pairs = ((number(mu, lang), number(mu / shrink, lang)), (ratio_text(mu, lang), ratio_text(mu / shrink, lang)))
            if any(old in text for old, _ in pairs):
                for old, new in pairs:
                    text = text.replace(old, new)
                break
    return replace(item, size_mm=size, text=text)


def _view(v):
    return getattr(v, "view", v)
