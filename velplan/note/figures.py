"""Figures of the note: the sheets' own views, drawn side by side as one SVG for the page, and
rasterised to PNG at print resolution (`velplan.note.pixels`, all of a note's figures in one
run) only when a format asks for pixels."""

from __future__ import annotations

from dataclasses import dataclass, replace

from velplan.note.page_text import boxed, settle
from velplan.render.scene import Scene, Text
from velplan.render.svg import to_svg
from velplan.views.base import ESKD_RATIOS, number, ratio_text, shift

DPI = 150.0
"""Resolution of the figures' PNGs, dots per inch at their size on the page: a figure the text's
width (170 mm) is 1000 pixels wide, print quality for grey line drawings (a .docx also
carries the SVG, which Word draws instead)."""
TEXT_WIDTH_MM = 170.0
"""Width of the text on an A4 page with the note's margins, mm."""
FIGURE_HEIGHT_MM = 200.0
"""Tallest figure on the page, mm (room left for its caption)."""
GAP_MM = 6.0
ROOM = 0.002
"""A figure whose box grew for its text is fitted again this much larger (the fixed point of
the shrink is approached from the side where the figure fits)."""
LETTER_MM = 2.5
"""The smallest printed lettering (ГОСТ 2.304): a figure shrunk to the page has its text
enlarged back to this where the sheet's text would print smaller."""


@dataclass(frozen=True)
class Picture:
    """A figure's drawing: its SVG document (sized in mm, at its size on the sheet) and the
    resolution its PNG is made at (dots per inch of the SVG's millimetres)."""

    svg: str
    dpi: float

    def png(self) -> bytes:
        """The PNG, made once (`pictures_png`)."""
        return pictures_png([self])[0]


_MADE: dict[tuple[str, float], bytes] = {}
"""The PNGs made lately, (SVG, dpi) → PNG: the last `_KEPT` of them."""
_KEPT = 64


def pictures_png(pictures) -> list[bytes]:
    """The PNG of each `Picture`, those not made lately made together in one run
    (`velplan.note.pixels.pngs`)."""
    from velplan.note import pixels

    keys = [(p.svg, float(p.dpi)) for p in pictures]
    wanted = [k for k in dict.fromkeys(keys) if k not in _MADE]
    made = dict(zip(wanted, pixels.pngs([Picture(*k) for k in wanted]))) if wanted else {}
    out = [made[k] if k in made else _MADE[k] for k in keys]
    _MADE.update(made)
    for old in list(_MADE)[:max(0, len(_MADE) - _KEPT)]:
        del _MADE[old]
    return out


def views_png(views, style, *, dpi: float = DPI) -> tuple[bytes, float]:
    """PNG of `views_figure` and the width (mm) it takes on the page."""
    picture, width = views_figure(views, style, dpi=dpi)
    return picture.png(), width


def views_figure(views, style, *, dpi: float = DPI) -> tuple[Picture, float]:
    """The `Picture` of `views` (placed or bare `View` objects) as laid out for the page
    (`page_scene`), and the width (mm) it takes on the page: its size on the sheet, or less
    to fit the text width and `FIGURE_HEIGHT_MM`; its PNG prints at ``dpi``."""
    scene, shrink = page_scene(views)
    return Picture(to_svg(scene, style), dpi * shrink), scene.width_mm * shrink


def page_scene(views) -> tuple[Scene, float]:
    """The figure of `views` as drawn for the page, and its shrink (printed/sheet size): the
    layout that shrinks them least, its text enlarged to `LETTER_MM` printed and laid out
    for that (`velplan.note.page_text`), its box grown to hold the text — and the shrink
    fitted again to the grown box until it fits the page."""
    return _laid_out(views)


def _laid_out(views) -> tuple[Scene, float]:
    views = [_view(v) for v in views]
    layout, shrink = max(((lay, _fit(views, lay)) for lay in _layouts(views)), key=lambda x: x[1])
    width, height, places = layout
    drawn = [(shift(p, x, y), getattr(view, "mu", None)) for view, (x, y) in zip(views, places)
             for p in view.primitives]
    for _ in range(12):
        items = settle([p for p, _ in drawn], [for_page(p, mu, shrink) for p, mu in drawn], shrink)
        items, w, h = boxed(items, width, height)
        if w * shrink <= TEXT_WIDTH_MM * (1 + 1e-9) and h * shrink <= FIGURE_HEIGHT_MM * (1 + 1e-9):
            break
        shrink = min(_fit(views, (w * (1 + ROOM), h * (1 + ROOM), None)), shrink * (1 - ROOM))
    return Scene(tuple(items), w, h), shrink


def lettered_for_page(draw, sizes, *, rounds: int = 4):
    """The view ``draw(sizes)`` drawn again with its lettering (a frozen dataclass of text
    heights, mm) enlarged until its smallest text prints at `LETTER_MM` at the size it
    takes on the page: the view lays out the larger text itself (a view of several panels
    whose titles and scales the enlargement in place would run into each other)."""
    from dataclasses import fields

    view = draw(sizes)
    for _ in range(rounds):
        least = min(getattr(sizes, f.name) for f in fields(sizes))
        need = LETTER_MM / (least * _laid_out([view])[1])
        if need <= 1.0 + 1e-6:
            break
        sizes = replace(sizes, **{f.name: getattr(sizes, f.name) * need * (1 + ROOM) for f in fields(sizes)})
        view = draw(sizes)
    return view


def _layouts(views):
    """(width, height, offsets) of the views side by side, and one above the other."""
    height = max(v.height_mm for v in views)
    x, side = 0.0, []
    for v in views:
        side.append((x, (height - v.height_mm) / 2))
        x += v.width_mm + GAP_MM
    out = [(x - GAP_MM, height, side)]
    if len(views) > 1:
        width = max(v.width_mm for v in views)
        y, stack = 0.0, []
        for v in views:
            stack.append(((width - v.width_mm) / 2, y))
            y += v.height_mm + GAP_MM
        total = y - GAP_MM  # y runs up the page: the first view goes on top
        stack = [(x0, total - y0 - v.height_mm) for (x0, y0), v in zip(stack, views)]
        out.append((width, total, stack))
    return out


def _fit(views, layout) -> float:
    """The shrink (printed/sheet size) of ``layout`` on the page, at a standard scale where a
    view is drawn to one."""
    width, height, _ = layout
    printed = min(width, TEXT_WIDTH_MM, width * FIGURE_HEIGHT_MM / height)
    if printed < width:
        return min(_standard_shrink(v, printed / width) for v in views)
    return 1.0


def _standard_shrink(view, shrink: float) -> float:
    """A drawing at a length scale (its text states "1:2,5") shrinks to the next ESKD scale
    (1:5 rather than 1:4,967), so the scale written on the page is a standard one."""
    mu = getattr(view, "mu", None)
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
